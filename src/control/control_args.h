// control_args.h - the scalars of the control forces (FfControlArgs,
// kernels/common/ff_control_pull.h), filled once for both backends from the
// run's parameters.
#pragma once
#include "control/recapture_field.h"
#include "core/params.h"
#include "ff_control_pull.h"

namespace ff {

// 4-byte fields with no padding: the kernels read the same bytes.
static_assert(sizeof(FfControlArgs) == 30 * 4, "FfControlArgs must hold 4-byte fields only");

// cp: the control parameters (radius already derived for the target);
// gravity and particle_mass: the fluid's; cp_volume: a control particle's
// rest volume; dt: the step; cell: the control grid's cell; field: the
// recapture field's geometry over that grid; masked: only part of the fluid
// is controlled; tag: the phase's non-finite tag (OpenCL).
FfControlArgs controlArgs(const ControlParams& cp, const float gravity[3], float particle_mass,
                          float cp_volume, float dt, float cell, const RecaptureFieldGeom& field, bool masked,
                          int tag);

}  // namespace ff
