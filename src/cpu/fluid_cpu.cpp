#include "cpu/fluid_cpu.h"

#include <cmath>

#include "parallel/simd8.h"
#include "ff_sph.h"

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

// Unused lanes sit this far away: out of every neighbour's reach.
constexpr float kFar = 1.0e18f;

// The neighbour ranges of one group, reused by each thread.
std::vector<uint32_t>& threadSpans() {
  static thread_local std::vector<uint32_t> spans;
  return spans;
}

// Sum over the 6 walls of the container within h of the particle.
template <class F>
inline void forEachWall(float x, float y, float z, float h, const ContainerDesc& box, F&& f) {
  const float pos[3] = {x, y, z};
  for (int d = 0; d < 3; ++d) {
    const float dlo = pos[d] - box.min[d], dhi = box.max[d] - pos[d];
    if (dlo < h) f(d, dlo, 1.0f);
    if (dhi < h) f(d, dhi, -1.0f);
  }
}

// The particles b .. e-1 (at most 8) as lanes, their bounding box, and the
// grid ranges within `radius` of it.
struct Group {
  f8 x, y, z;
  int n;
};
inline void loadGroup(const FluidState& s, uint32_t b, uint32_t e, float radius, const UniformGrid& grid,
                      Group& g, std::vector<uint32_t>& spans) {
  g.n = int(e - b);
  g.x = simd::loadN(&s.x[b], g.n, kFar), g.y = simd::loadN(&s.y[b], g.n, kFar);
  g.z = simd::loadN(&s.z[b], g.n, kFar);
  const float lo[3] = {simd::hmin(g.x, g.n), simd::hmin(g.y, g.n), simd::hmin(g.z, g.n)};
  const float hi[3] = {simd::hmax(g.x, g.n), simd::hmax(g.y, g.n), simd::hmax(g.z, g.n)};
  grid.rangesNear(lo, hi, radius, spans);
}

// Density sums of the particles b .. e-1: lane by lane, the neighbours in
// ascending sorted order, as the OpenCL kernel (kernels/density.cl).
FF_SIMD_CLONES void densitySums(const CpuFluid& f, uint32_t b, uint32_t e, float h, float coef, float* out) {
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

// Pressure and viscosity sums of the particles b .. e-1 in one neighbour walk
// (kernels/forces.cl): out[0..2] pressure, out[3..5] viscosity, 8 lanes each.
FF_SIMD_CLONES void forceSums(const CpuFluid& f, uint32_t b, uint32_t e, float h, float mass, bool viscous,
                              float* out) {
  const FluidState& s = f.s;
  std::vector<uint32_t>& spans = threadSpans();
  Group g;
  loadGroup(s, b, e, h, f.grid, g, spans);
  const int n = g.n;
  const float grad_coef = ff_spiky_grad_coef(h), lap_coef = ff_visc_lap_coef(h);
  const f8 pi = simd::loadN(&f.p[b], n, 0.0f);
  const f8 vxi = simd::loadN(&s.vx[b], n, 0.0f), vyi = simd::loadN(&s.vy[b], n, 0.0f),
           vzi = simd::loadN(&s.vz[b], n, 0.0f);
  const float *x = s.x.data(), *y = s.y.data(), *z = s.z.data();
  const float *vx = s.vx.data(), *vy = s.vy.data(), *vz = s.vz.data(), *rho = f.rho.data(), *p = f.p.data();
  const f8 zero = simd::splat(0.0f);
  f8 px = zero, py = zero, pz = zero, fx = zero, fy = zero, fz = zero;
  for (size_t r = 0; r < spans.size(); r += 2)
    for (uint32_t j = spans[r]; j < spans[r + 1]; ++j) {
      const f8 dx = g.x - x[j], dy = g.y - y[j], dz = g.z - z[j];
      const f8 dist = simd::sqrt8(dx * dx + dy * dy + dz * dz);
      const float rhoj = rho[j];
      const f8 grad = ff_spiky_grad_factor(dist, h, grad_coef);  // grad W = -g r_ij
      const f8 c = ff_pressure_pair(grad, pi, p[j], rhoj, mass);
      px += c * dx, py += c * dy, pz += c * dz;
      if (viscous) {
        const f8 cv = ff_visc_pair(ff_visc_lap(dist, h, lap_coef), rhoj, mass);
        fx += cv * (vx[j] - vxi), fy += cv * (vy[j] - vyi), fz += cv * (vz[j] - vzi);
      }
    }
  const f8 sums[6] = {px, py, pz, fx, fy, fz};
  for (int k = 0; k < 6; ++k) simd::storeN(out + 8 * k, sums[k], n);
}

}  // namespace

bool computeDensityPressure(CpuFluid& f, const FluidParams& p, const ContainerDesc& box) {
  const size_t n = f.size();
  f.rho.resize(n), f.p.resize(n);
  const float h = p.smoothing_radius, coef = ff_poly6_coef(h), m = p.particle_mass;
  const float rho0 = p.rest_density, k = p.gas_constant;
  const FluidState& s = f.s;
  const long groups = long(f.groups.size() / 2);
  int bad = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(| : bad)
  for (long gi = 0; gi < groups; ++gi) {
    const uint32_t b = f.groups[2 * size_t(gi)], e = f.groups[2 * size_t(gi) + 1];
    float sum[8];
    densitySums(f, b, e, h, coef, sum);
    for (uint32_t i = b; i < e; ++i) {
      float fluid_side = 1.0f;
      forEachWall(s.x[i], s.y[i], s.z[i], h, box,
                  [&](int, float d, float) { fluid_side *= 1.0f - ff_poly6_wall_fraction(d, h, coef); });
      const float rho = m * sum[i - b] + rho0 * ff_combine_wall_fractions(fluid_side);
      f.rho[i] = rho;
      f.p[i] = ff_pressure(rho, rho0, k);
      bad |= std::isfinite(rho) && std::isfinite(f.p[i]) ? 0 : 1;
    }
  }
  return !bad;
}

bool computeWcsphForces(CpuFluid& f, const FluidParams& p, const ContainerDesc& box) {
  const size_t n = f.size();
  for (auto* a : {&f.ax, &f.ay, &f.az}) a->resize(n);
  const float h = p.smoothing_radius, m = p.particle_mass, mu = p.viscosity;
  const FluidState& s = f.s;
  const long groups = long(f.groups.size() / 2);
  int bad = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(| : bad)
  for (long gi = 0; gi < groups; ++gi) {
    const uint32_t b = f.groups[2 * size_t(gi)], e = f.groups[2 * size_t(gi) + 1];
    float sums[48];
    forceSums(f, b, e, h, m, mu > 0.0f, sums);
    for (uint32_t i = b; i < e; ++i) {
      const size_t l = i - b;
      const float pi = f.p[i], rhoi = f.rho[i];
      float a[3] = {sums[l] / rhoi, sums[8 + l] / rhoi, sums[16 + l] / rhoi};
      forEachWall(s.x[i], s.y[i], s.z[i], h, box, [&](int d, float dist, float sign) {
        a[d] += sign * ff_wall_pressure_accel(dist, h, pi, rhoi);
      });
      // The pressure part, then viscosity and gravity (as kernels/forces.cl).
      const float inv = mu / rhoi;
      float r[3] = {0.0f + a[0], 0.0f + a[1], 0.0f + a[2]};
      for (int d = 0; d < 3; ++d) r[d] += sums[8 * (3 + d) + l] * inv + p.gravity[d];
      f.ax[i] = r[0], f.ay[i] = r[1], f.az[i] = r[2];
      bad |= std::isfinite(r[0]) && std::isfinite(r[1]) && std::isfinite(r[2]) ? 0 : 1;
    }
  }
  return !bad;
}

bool integrateFluid(CpuFluid& f, const FluidParams& p, const ContainerDesc& box, float dt) {
  const long n = long(f.size());
  const float vmax = p.max_step_fraction * p.smoothing_radius / dt;
  const float eps = 1e-6f * p.smoothing_radius;
  FluidState& s = f.s;
  f.grid_current = false, f.sorted = false;
  int bad = 0;
#pragma omp parallel for schedule(static) reduction(| : bad)
  for (long i = 0; i < n; ++i) {
    float v[3] = {s.vx[i] + dt * f.ax[i], s.vy[i] + dt * f.ay[i], s.vz[i] + dt * f.az[i]};
    const float sp = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (sp > vmax) {
      const float c = vmax / sp;
      v[0] *= c, v[1] *= c, v[2] *= c;
    }
    float x[3] = {s.x[i] + dt * v[0], s.y[i] + dt * v[1], s.z[i] + dt * v[2]};
    for (int d = 0; d < 3; ++d) {
      const float lo = box.min[d] + eps, hi = box.max[d] - eps;
      if (x[d] < lo) x[d] = lo, v[d] = v[d] < 0.0f ? 0.0f : v[d];
      if (x[d] > hi) x[d] = hi, v[d] = v[d] > 0.0f ? 0.0f : v[d];
    }
    s.x[i] = x[0], s.y[i] = x[1], s.z[i] = x[2];
    s.vx[i] = v[0], s.vy[i] = v[1], s.vz[i] = v[2];
    for (int d = 0; d < 3; ++d) bad |= std::isfinite(x[d]) && std::isfinite(v[d]) ? 0 : 1;
  }
  return !bad;
}

}  // namespace ff
