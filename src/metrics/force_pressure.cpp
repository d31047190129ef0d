#include "metrics/force_pressure.h"

#include <cmath>

#include "ff_dfsph.h"
#include "grid/uniform_grid.h"

namespace ff {

ForcePressure forcePressure(const FluidState& s, const float* p, float support, const float n[3]) {
  const size_t count = s.size();
  ForcePressure out;
  out.p.resize(count), out.at.resize(count);
  if (count == 0) return out;
  UniformGrid grid;
  grid.build(count, s.x.data(), s.y.data(), s.z.data(), support, gridCellCap(count));
  const std::vector<uint32_t>& order = grid.order();
  const float inv_h = 1.0f / support, kg = ff_cubic_coef(support) * inv_h * inv_h, h2 = support * support;
#pragma omp parallel for schedule(dynamic, 64)
  for (long li = 0; li < long(count); ++li) {
    const size_t i = size_t(li);
    const float xi = s.x[i], yi = s.y[i], zi = s.z[i];
    float w = 0.0f, wp = 0.0f, wx = 0.0f;
    grid.forEachRange(xi, yi, zi, [&](uint32_t b, uint32_t e) {
      for (uint32_t q = b; q < e; ++q) {
        const uint32_t j = order[q];
        const float rx = xi - s.x[j], ry = yi - s.y[j], rz = zi - s.z[j];
        const float r2 = rx * rx + ry * ry + rz * rz;
        if (r2 >= h2) continue;
        const float g = ff_cubic_grad_factor(std::sqrt(r2), inv_h, kg);
        const float wij = ff_dfsph_readout_weight(g, rx * n[0] + ry * n[1] + rz * n[2]);
        w += wij, wp += wij * p[j], wx += wij * (s.x[j] * n[0] + s.y[j] * n[1] + s.z[j] * n[2]);
      }
    });
    out.p[i] = ff_dfsph_force_pressure(p[i], xi * n[0] + yi * n[1] + zi * n[2], w, wp, wx, &out.at[i]);
  }
  return out;
}

}  // namespace ff
