// voxel_size_search.h - finds a voxel size whose voxelisation has (about) a
// requested number of inside voxels.
#pragma once
#include <functional>
#include <string>

#include "target/target_shape.h"

namespace ff {

// Voxelises the shape for a voxel size and a grid shift (see makeVoxelGrid).
using Voxelizer = std::function<VoxelGrid(float voxel, const Vec3& shift)>;

// Returns a voxelisation whose inside count is within `tolerance` (a
// fraction, e.g. 0.03) of `count`, refined towards 0.5% while that is cheap.
// Starts from (volume / count)^(1/3), then steps with the model count ~
// volume / voxel^3 and falls back to bisection on the bracket (the count is a
// step function of the voxel size, not always monotonic); tries a few grid
// shifts when a jump of the count straddles the band. Throws ff::Error
// starting with `context` (e.g. "target 'bunny.obj'") and giving the closest
// count reached.
VoxelGrid searchVoxelSize(int count, double tolerance, double volume, const Voxelizer& voxelize,
                          const std::string& context);

// Returns a voxelisation near `voxel` whose inside voxels hold `volume`
// (count x voxel^3) within `tolerance`, or the closest of a few tries: the
// fixed point voxel = (volume / count(voxel))^(1/3), which a box reaches in
// one step (a whole number of voxels per side), from `voxel` and from a few
// grid shifts, never beyond a factor of 1.25 from `voxel`. A shape a few
// voxels thick (a disc, a letter, a limb) loses or gains a layer of voxels to
// the rounding of its thickness; at the given voxel its voxels could hold 30%
// more than the fluid that is to fill them.
VoxelGrid searchVoxelVolume(float voxel, double volume, double tolerance, const Voxelizer& voxelize);

}  // namespace ff
