// ply_writer.h - particle snapshots as binary little-endian PLY point clouds.
// Each file is written to PATH.tmp and renamed into place, so a failed write
// never leaves a half-written PATH. Errors throw ff::Error naming the path.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace ff {

// Fluid particles: vertex properties `float x y z vx vy vz` and `uint id`.
// `id` may be null (ids 0 .. n-1 are written).
void writeFluidPly(const std::string& path, size_t n, const float* x, const float* y, const float* z,
                   const float* vx, const float* vy, const float* vz, const uint32_t* id);

// Control particles: vertex properties `float x y z x0 y0 z0 s`: the current
// position, the reference position (x0) and the density ratio s.
void writeControlPly(const std::string& path, size_t n, const float* x, const float* y, const float* z,
                     const float* x0, const float* y0, const float* z0, const float* s);

}  // namespace ff
