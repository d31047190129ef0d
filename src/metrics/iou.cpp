#include "metrics/iou.h"

#include "ff_sph.h"

namespace ff {

double voxelIou(const TargetShape& target, const RigidFrame& frame, int pad, const float* x, const float* y,
                const float* z, const UniformGrid& grid, float mass, float h, float rho0, float fraction) {
  const VoxelGrid& g = target.grid;
  const ff_mat3 r = ff_quat_to_mat3(frame.q);
  const float h2 = h * h, coef = ff_poly6_coef(h), threshold = fraction * rho0;
  const int nx = g.nx + 2 * pad, ny = g.ny + 2 * pad, nz = g.nz + 2 * pad;
  const long total = long(nx) * ny * nz;
  const auto& order = grid.order();
  long inter = 0, uni = 0;
#pragma omp parallel for schedule(static) reduction(+ : inter, uni)
  for (long v = 0; v < total; ++v) {
    const int i = int(v % nx) - pad, j = int((v / nx) % ny) - pad, k = int(v / (long(nx) * ny)) - pad;
    const bool in_target =
        i >= 0 && j >= 0 && k >= 0 && i < g.nx && j < g.ny && k < g.nz && g.inside[g.index(i, j, k)];
    const Vec3 c = g.center(i, j, k);
    const ff_float3 w =
        ff_mat3_mul_vec(r, FF_F3(c.x() - frame.rest_c[0], c.y() - frame.rest_c[1], c.z() - frame.rest_c[2])) +
        FF_F3(frame.c[0], frame.c[1], frame.c[2]);
    float sum = 0.0f;
    grid.forEachRange(w.x, w.y, w.z, [&](uint32_t b, uint32_t e) {
      for (uint32_t kk = b; kk < e; ++kk) {
        const uint32_t p = order[kk];
        const float dx = w.x - x[p], dy = w.y - y[p], dz = w.z - z[p];
        sum += ff_poly6(dx * dx + dy * dy + dz * dz, h2, coef);
      }
    });
    const bool in_fluid = mass * sum >= threshold;
    inter += (in_target && in_fluid) ? 1 : 0;
    uni += (in_target || in_fluid) ? 1 : 0;
  }
  return uni > 0 ? double(inter) / double(uni) : 0.0;
}

}  // namespace ff
