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

}  // namespace ff
