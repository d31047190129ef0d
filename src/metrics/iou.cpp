#include "metrics/iou.h"

#include <algorithm>
#include <vector>

#include "ff_sph.h"
#include "parallel/simd8.h"

namespace ff {

namespace {

using simd::f8;

// Unused lanes sit this far away: out of every particle's reach.
constexpr float kFar = 1.0e18f;

// Which of the n voxel centres (c*[0 .. n-1], as lanes) the fluid fills: m sum_j W >= threshold.
// Each lane sums the particles of the grid ranges within h of the lanes'
// bounding box in ascending sorted order: its terms and their order are those
// of a walk over the 27 cells around its own centre (a particle out of reach
// adds an exact 0). The sums only grow, so once every lane has reached the
// threshold the rest of the walk could not change the answer and is skipped.
template <class>
FF_SIMD_BODY int fluidLanesOf(const float* cx, const float* cy, const float* cz, int n,
                              const UniformGrid& grid, const float* x, const float* y, const float* z,
                              float mass, float h, float threshold, std::vector<uint32_t>& spans) {
  const f8 wx = simd::loadN(cx, n, kFar), wy = simd::loadN(cy, n, kFar), wz = simd::loadN(cz, n, kFar);
  const float lo[3] = {simd::hmin(wx, n), simd::hmin(wy, n), simd::hmin(wz, n)};
  const float hi[3] = {simd::hmax(wx, n), simd::hmax(wy, n), simd::hmax(wz, n)};
  grid.rangesNear(lo, hi, h, spans);
  const float h2 = h * h, coef = ff_poly6_coef(h);
  const uint32_t* order = grid.order().data();
  f8 sum = simd::splat(0.0f);
  auto filled = [&] {
    int mask = 0;
    for (int l = 0; l < n; ++l) mask |= mass * sum[l] >= threshold ? 1 << l : 0;
    return mask;
  };
  const int all = (1 << n) - 1;
  int mask = filled();
  for (size_t r = 0; r < spans.size() && mask != all; r += 2) {
    for (uint32_t kk = spans[r]; kk < spans[r + 1]; ++kk) {
      const uint32_t p = order[kk];
      const f8 dx = wx - x[p], dy = wy - y[p], dz = wz - z[p];
      sum += ff_poly6(dx * dx + dy * dy + dz * dz, h2, coef);
    }
    mask = filled();
  }
  return mask;
}
FF_SIMD_DISPATCH(fluidLanes)

std::vector<uint32_t>& threadSpans() {
  static thread_local std::vector<uint32_t> spans;
  return spans;
}

}  // namespace

IouCounts voxelIou(const TargetShape& target, const RigidFrame& frame, int pad, const float* x,
                   const float* y, const float* z, const UniformGrid& grid, float mass, float h, float rho0,
                   float fraction, const uint8_t* thin) {
  const VoxelGrid& g = target.grid;
  const ff_mat3 r = ff_quat_to_mat3(frame.q);
  const float threshold = fraction * rho0;
  const int nx = g.nx + 2 * pad, ny = g.ny + 2 * pad, nz = g.nz + 2 * pad;
  // Runs of 8 voxels along x, as lanes.
  const int runs = (nx + 7) / 8;
  const long total = long(runs) * ny * nz;
  long inter = 0, uni = 0, inter_thin = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : inter, uni, inter_thin)
  for (long v = 0; v < total; ++v) {
    const int i0 = int(v % runs) * 8, j = int((v / runs) % ny) - pad, k = int(v / (long(runs) * ny)) - pad;
    const int n = std::min(8, nx - i0);
    float wx[8], wy[8], wz[8];
    bool in_target[8], in_thin[8];
    for (int l = 0; l < n; ++l) {
      const int i = i0 + l - pad;
      const bool in_grid = i >= 0 && j >= 0 && k >= 0 && i < g.nx && j < g.ny && k < g.nz;
      in_target[l] = in_grid && g.inside[g.index(i, j, k)];
      in_thin[l] = in_grid && thin && thin[g.index(i, j, k)];
      const Vec3 c = g.center(i, j, k);
      const ff_float3 w = ff_mat3_mul_vec(r, FF_F3(c.x() - frame.rest_c[0], c.y() - frame.rest_c[1],
                                                   c.z() - frame.rest_c[2])) +
                          FF_F3(frame.c[0], frame.c[1], frame.c[2]);
      wx[l] = w.x, wy[l] = w.y, wz[l] = w.z;
    }
    const int fluid = fluidLanes(wx, wy, wz, n, grid, x, y, z, mass, h, threshold, threadSpans());
    for (int l = 0; l < n; ++l) {
      const bool in_fluid = (fluid >> l) & 1;
      inter += (in_target[l] && in_fluid) ? 1 : 0;
      inter_thin += (in_thin[l] && in_fluid) ? 1 : 0;
      uni += (in_target[l] || in_fluid) ? 1 : 0;
    }
  }
  IouCounts c;
  c.inter = inter, c.uni = uni, c.inter_thin = inter_thin;
  return c;
}

}  // namespace ff
