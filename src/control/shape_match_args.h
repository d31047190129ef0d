// shape_match_args.h - the scalars of a shape-matching step (FfShapeMatchArgs,
// kernels/common/ff_shape_match.h), filled once for both backends from the
// run's parameters.
#pragma once
#include <cstdint>

#include "core/params.h"
#include "ff_shape_match.h"

namespace ff {

// 4-byte fields with no padding: the kernels read the same bytes.
static_assert(sizeof(FfShapeMatchArgs) == 19 * 4, "FfShapeMatchArgs must hold 4-byte fields only");

// sm, feedback: the shape-matching parameters and the control's fluid
// feedback; n, nclusters: the control set's particles and clusters; w: the
// rest-shape blend's weight this step; gravity: the fluid's (the anchor acts
// where it is on and there is gravity to tell up by); lo, hi: the container
// (null: no clamp); tag: the phase's non-finite tag (OpenCL).
FfShapeMatchArgs shapeMatchArgs(const ShapeMatchParams& sm, float feedback, uint32_t n, uint32_t nclusters,
                                float w, const float gravity[3], const float* lo, const float* hi, int tag);

}  // namespace ff
