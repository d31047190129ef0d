// viscosity.cpp - the viscosity plug-in of the OpenMP backend: Mueller et al.
// 2003's viscosity force (the Laplacian of the viscosity kernel) with
// params.fluid.viscosity, as kernels/forces.cl's viscosity kernels.
#include <cmath>
#include <memory>

#include "cpu/forces/cpu_force.h"
#include "cpu/lane_group.h"
#include "ff_sph.h"
#include "parallel/simd8.h"

namespace ff {

namespace {

using simd::f8;

// Viscosity sums of the particles b .. e-1 (kernels/forces.cl), 8 lanes each
// of x, y, z in out[0..23]: lane by lane, the neighbours in ascending sorted
// order, as the OpenCL kernels. With `nc` (the density phase's lists, group
// gi) it walks the candidates a lane reaches, in the same order (the others
// add exactly 0), else the grid.
template <class>
FF_SIMD_BODY void viscositySumsOf(const CpuFluid& f, const NeighbourCache* nc, size_t gi, uint32_t b,
                                  uint32_t e, float h, float mass, float* out) {
  const FluidState& s = f.s;
  std::vector<uint32_t>& spans = threadSpans();
  Group g;
  if (nc)
    g = lanesOf(s, b, e);
  else
    loadGroup(s, b, e, h, f.grid, g, spans);
  const int n = g.n;
  const float lap_coef = ff_visc_lap_coef(h);
  const f8 vxi = simd::loadN(&s.vx[b], n, 0.0f), vyi = simd::loadN(&s.vy[b], n, 0.0f),
           vzi = simd::loadN(&s.vz[b], n, 0.0f);
  const float *x = s.x.data(), *y = s.y.data(), *z = s.z.data();
  const float *vx = s.vx.data(), *vy = s.vy.data(), *vz = s.vz.data(), *rho = f.rho.data();
  const f8 zero = simd::splat(0.0f);
  f8 fx = zero, fy = zero, fz = zero;
  const auto add = [&](uint32_t j) __attribute__((always_inline)) {
    const f8 dx = g.x - x[j], dy = g.y - y[j], dz = g.z - z[j];
    const f8 dist = simd::sqrt8(dx * dx + dy * dy + dz * dz);
    const f8 cv = ff_visc_pair(ff_visc_lap(dist, h, lap_coef), rho[j], mass);
    fx += cv * (vx[j] - vxi), fy += cv * (vy[j] - vyi), fz += cv * (vz[j] - vzi);
  };
  if (nc) {
    const uint32_t* js = nc->neighbours(gi);
    const uint32_t m = nc->count(gi);
#pragma GCC unroll 4
    for (uint32_t q = 0; q < m; ++q) add(js[q]);
  } else {
    for (size_t r = 0; r < spans.size(); r += 2)
      for (uint32_t j = spans[r]; j < spans[r + 1]; ++j) add(j);
  }
  const f8 sums[3] = {fx, fy, fz};
  for (int k = 0; k < 3; ++k) simd::storeN(out + 8 * k, sums[k], n);
}
FF_SIMD_DISPATCH(viscositySums)

class CpuViscosity : public CpuForce {
 public:
  const char* name() const override { return "viscosity"; }
  bool apply(CpuForceContext& c, float) override {
    const FluidParams& p = c.params.fluid;
    const float h = p.smoothing_radius, m = p.particle_mass, mu = p.viscosity;
    if (!(mu > 0.0f)) return true;  // adds exactly 0
    CpuFluid& f = c.fluid;
    // The lists hold every neighbour within their radius: enough where it
    // is at least h.
    const NeighbourCache* nc =
        c.neighbours && c.neighbours->radius() >= h && c.neighbours->groups() == f.groups.size() / 2
            ? c.neighbours
            : nullptr;
    const auto walk = [&](size_t gi, uint32_t b, uint32_t e) {
      float sums[24];
      viscositySums(f, nc, gi, b, e, h, m, sums);
      bool finite = true;
      for (uint32_t i = b; i < e; ++i) {
        const size_t l = i - b;
        const float vs[3] = {sums[l], sums[8 + l], sums[16 + l]};
        float a[3] = {f.ax[i], f.ay[i], f.az[i]};
        ff_add_viscosity_accel(vs, mu, f.rho[i], a);
        f.ax[i] = a[0], f.ay[i] = a[1], f.az[i] = a[2];
        finite = finite && std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]);
      }
      return finite;
    };
    // With the lists, each thread walks its part of the groups (mostly the lists it filled).
    return nc ? forEachGroupInParts(nc->parts(), f.groups, walk) : forEachGroupIndexFinite(f.groups, walk);
  }
};

}  // namespace

std::unique_ptr<CpuForce> makeCpuViscosity() {
  return std::make_unique<CpuViscosity>();
}

}  // namespace ff
