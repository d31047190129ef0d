// placement.h - control particles from reference particles (paper Fig. 7).
#pragma once
#include "control/control_set.h"
#include "core/params.h"
#include "core/vec3.h"
#include "target/target_shape.h"

namespace ff {

// Places one control particle per reference particle of `target`, by the
// linear map of the reference particles' bounding box onto [lo, hi] (the
// bounding box of the user's fluid region). Rest positions are the reference
// positions; velocities start at zero; clusters are built from the voxels.
ControlSet placeControlParticles(const TargetShape& target, const Vec3& lo, const Vec3& hi,
                                 const ShapeMatchParams& sm);

}  // namespace ff
