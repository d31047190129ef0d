#include "cpu/fluid_cpu.h"

#include <cmath>

#include "cpu/lane_group.h"
#include "ff_integrate.h"
#include "ff_sph.h"
#include "parallel/simd8.h"

namespace ff {

using simd::f8;

size_t CpuFluid::memoryBytes() const {
  size_t floats = s.x.capacity() + s.y.capacity() + s.z.capacity() + s.vx.capacity() + s.vy.capacity() +
                  s.vz.capacity() + rho.capacity() + p.capacity() + ax.capacity() + ay.capacity() +
                  az.capacity() + scratch.capacity();
  size_t uints = s.id.capacity() + groups.capacity() + scratch_u.capacity();
  return floats * sizeof(float) + uints * sizeof(uint32_t) + grid.memoryBytes();
}

void buildFluidIndex(CpuFluid& f, float h, const ContainerDesc& box) {
  const FluidState& s = f.s;
  const float lo[3] = {box.min.x(), box.min.y(), box.min.z()},
              hi[3] = {box.max.x(), box.max.y(), box.max.z()};
  f.grid.build(s.size(), s.x.data(), s.y.data(), s.z.data(), h, lo, hi, gridCellCap(s.size()));
  f.sorted = false;
}

void buildFluidGrid(CpuFluid& f, float h, const ContainerDesc& box) {
  FluidState& s = f.s;
  if (!f.grid_current) buildFluidIndex(f, h, box);
  f.grid_current = false;  // after the reorder its order() no longer maps input indices
  const auto& order = f.grid.order();
  for (auto* a : {&s.x, &s.y, &s.z, &s.vx, &s.vy, &s.vz}) permute(*a, order, f.scratch);
  permute(s.id, order, f.scratch_u);
  // After the reorder particle k is the k-th in sorted order, so the grid's
  // ranges index the arrays directly.
  f.grid.rowGroups(8, f.groups);
  f.sorted = true;
}

namespace {

// Density sums of the particles b .. e-1: lane by lane, the neighbours in
// ascending sorted order, as the OpenCL kernel (kernels/density.cl).
template <class>
FF_SIMD_BODY void densitySumsOf(const CpuFluid& f, uint32_t b, uint32_t e, float h, float coef, float* out) {
  const FluidState& s = f.s;
  std::vector<uint32_t>& spans = threadSpans();
  Group g;
  loadGroup(s, b, e, h, f.grid, g, spans);
  const float h2 = h * h;
  const float *x = s.x.data(), *y = s.y.data(), *z = s.z.data();
  f8 sum = simd::splat(0.0f);
  for (size_t r = 0; r < spans.size(); r += 2)
    for (uint32_t j = spans[r]; j < spans[r + 1]; ++j) {
      const f8 dx = g.x - x[j], dy = g.y - y[j], dz = g.z - z[j];
      sum += ff_poly6(dx * dx + dy * dy + dz * dz, h2, coef);
    }
  simd::storeN(out, sum, g.n);
}
FF_SIMD_DISPATCH(densitySums)

// WCSPH pressure sums of the particles b .. e-1 (kernels/pressure_wcsph.cl),
// 8 lanes each of x, y, z in out[0..23].
template <class>
FF_SIMD_BODY void pressureSumsOf(const CpuFluid& f, uint32_t b, uint32_t e, float h, float mass, float* out) {
  const FluidState& s = f.s;
  std::vector<uint32_t>& spans = threadSpans();
  Group g;
  loadGroup(s, b, e, h, f.grid, g, spans);
  const int n = g.n;
  const float grad_coef = ff_spiky_grad_coef(h);
  const f8 pi = simd::loadN(&f.p[b], n, 0.0f);
  const float *x = s.x.data(), *y = s.y.data(), *z = s.z.data(), *rho = f.rho.data(), *p = f.p.data();
  const f8 zero = simd::splat(0.0f);
  f8 px = zero, py = zero, pz = zero;
  for (size_t r = 0; r < spans.size(); r += 2)
    for (uint32_t j = spans[r]; j < spans[r + 1]; ++j) {
      const f8 dx = g.x - x[j], dy = g.y - y[j], dz = g.z - z[j];
      const f8 dist = simd::sqrt8(dx * dx + dy * dy + dz * dz);
      const f8 grad = ff_spiky_grad_factor(dist, h, grad_coef);  // grad W = -g r_ij
      const f8 c = ff_pressure_pair(grad, pi, p[j], rho[j], mass);
      px += c * dx, py += c * dy, pz += c * dz;
    }
  const f8 sums[3] = {px, py, pz};
  for (int k = 0; k < 3; ++k) simd::storeN(out + 8 * k, sums[k], n);
}
FF_SIMD_DISPATCH(pressureSums)

}  // namespace

bool computeDensityPressure(CpuFluid& f, const FluidParams& p, const ContainerDesc& box) {
  const size_t n = f.size();
  f.rho.resize(n), f.p.resize(n);
  const float h = p.smoothing_radius, coef = ff_poly6_coef(h), m = p.particle_mass;
  const float rho0 = p.rest_density, k = p.gas_constant;
  const float lo[3] = {box.min.x(), box.min.y(), box.min.z()},
              hi[3] = {box.max.x(), box.max.y(), box.max.z()};
  const FluidState& s = f.s;
  return forEachGroupFinite(f.groups, [&](uint32_t b, uint32_t e) {
    float sum[8];
    densitySums(f, b, e, h, coef, sum);
    bool finite = true;
    for (uint32_t i = b; i < e; ++i) {
      const float pos[3] = {s.x[i], s.y[i], s.z[i]};
      const float rho = m * sum[i - b] + rho0 * ff_wall_density_share(pos, lo, hi, h, coef);
      f.rho[i] = rho;
      f.p[i] = ff_pressure(rho, rho0, k);
      finite = finite && std::isfinite(rho) && std::isfinite(f.p[i]);
    }
    return finite;
  });
}

void clearAccelerations(CpuFluid& f) {
  for (auto* a : {&f.ax, &f.ay, &f.az}) a->assign(f.size(), 0.0f);
}

bool addWcsphPressure(CpuFluid& f, const FluidParams& p, const ContainerDesc& box) {
  const float h = p.smoothing_radius, m = p.particle_mass;
  const float lo[3] = {box.min.x(), box.min.y(), box.min.z()},
              hi[3] = {box.max.x(), box.max.y(), box.max.z()};
  const FluidState& s = f.s;
  return forEachGroupFinite(f.groups, [&](uint32_t b, uint32_t e) {
    float sums[24];
    pressureSums(f, b, e, h, m, sums);
    bool finite = true;
    for (uint32_t i = b; i < e; ++i) {
      const size_t l = i - b;
      const float pos[3] = {s.x[i], s.y[i], s.z[i]}, ps[3] = {sums[l], sums[8 + l], sums[16 + l]};
      float a[3];
      ff_wcsph_pressure_accel(pos, lo, hi, h, f.p[i], f.rho[i], ps, a);
      const float r[3] = {f.ax[i] + a[0], f.ay[i] + a[1], f.az[i] + a[2]};
      f.ax[i] = r[0], f.ay[i] = r[1], f.az[i] = r[2];
      finite = finite && std::isfinite(r[0]) && std::isfinite(r[1]) && std::isfinite(r[2]);
    }
    return finite;
  });
}

bool integrateFluid(CpuFluid& f, const FluidParams& p, const ContainerDesc& box, float dt) {
  const long n = long(f.size());
  const float vmax = p.max_step_fraction * p.smoothing_radius / dt;
  const float eps = 1e-6f * p.smoothing_radius;
  const float lo[3] = {box.min[0], box.min[1], box.min[2]}, hi[3] = {box.max[0], box.max[1], box.max[2]};
  FluidState& s = f.s;
  f.grid_current = false, f.sorted = false;
  int bad = 0;
  long clamps = 0;
#pragma omp parallel for schedule(static) reduction(| : bad) reduction(+ : clamps)
  for (long i = 0; i < n; ++i) {
    float v[3] = {s.vx[i], s.vy[i], s.vz[i]}, x[3] = {s.x[i], s.y[i], s.z[i]};
    const float a[3] = {f.ax[i], f.ay[i], f.az[i]};
    clamps += ff_integrate_particle(v, x, a, dt, vmax, lo, hi, eps);
    s.x[i] = x[0], s.y[i] = x[1], s.z[i] = x[2];
    s.vx[i] = v[0], s.vy[i] = v[1], s.vz[i] = v[2];
    for (int d = 0; d < 3; ++d) bad |= std::isfinite(x[d]) && std::isfinite(v[d]) ? 0 : 1;
  }
  f.velocity_clamps += clamps;
  return !bad;
}

}  // namespace ff
