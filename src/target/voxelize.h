// voxelize.h - which voxel centres of a regular grid lie inside a triangle mesh.
#pragma once
#include <cstdint>
#include <vector>

#include "target/mesh_io.h"
#include "target/target_shape.h"

namespace ff {

// A grid covering [lo, hi] with at least one whole empty voxel on every side,
// centred on the box and then shifted by `shift` voxels (each in [-0.5, 0.5];
// a non-zero shift adds one voxel along that axis). Throws ff::Error when the
// voxel size is not positive or the grid would be unreasonably large.
VoxelGrid makeVoxelGrid(const Vec3& lo, const Vec3& hi, float voxel, const Vec3& shift = Vec3::Zero());

// Sets grid.inside (resized to the grid) for the voxels whose centre is inside
// `mesh`: a 2-of-3 majority vote of ray parity along x, y and z (see the .cpp).
void voxelizeMesh(const TriangleMesh& mesh, VoxelGrid& grid);

// One vote: `parity` (one entry per voxel, grid index order) is 1 where an odd
// number of triangles cross the ray along `axis` (0, 1, 2) below the voxel centre.
void rayParity(const TriangleMesh& mesh, const VoxelGrid& grid, int axis, std::vector<uint8_t>& parity);

}  // namespace ff
