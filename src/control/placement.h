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
//
// Shape matching keeps the placed particles' centre of mass, so the target
// forms around it. Where the rigid shape around that centre would cross the
// container [box_lo, box_hi], all particles are shifted so that it fits (a
// shape that is larger than the container along an axis is centred on it):
// otherwise the walls would push the forming shape away from its fluid. The
// shift is at most half the region's extent along each axis, so the particles
// still start over the fluid they control.
ControlSet placeControlParticles(const TargetShape& target, const Vec3& lo, const Vec3& hi,
                                 const ShapeMatchParams& sm, const Vec3& box_lo, const Vec3& box_hi);

}  // namespace ff
