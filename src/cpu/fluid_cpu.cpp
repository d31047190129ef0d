#include "cpu/fluid_cpu.h"

#include <cmath>

#include "ff_sph.h"

namespace ff {

void buildFluidGrid(CpuFluid& f, float h) {
  FluidState& s = f.s;
  if (!f.grid_current) f.grid.build(s.size(), s.x.data(), s.y.data(), s.z.data(), h);
  f.grid_current = false;  // after the reorder its order() no longer maps input indices
  const auto& order = f.grid.order();
  for (auto* a : {&s.x, &s.y, &s.z, &s.vx, &s.vy, &s.vz}) permute(*a, order, f.scratch);
  permute(s.id, order, f.scratch_u);
  // After the reorder particle k is the k-th in sorted order, so the grid's
  // ranges index the arrays directly.
}

namespace {

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

}  // namespace

void computeDensityPressure(CpuFluid& f, const FluidParams& p, const ContainerDesc& box) {
  const long n = long(f.size());
  f.rho.resize(size_t(n)), f.p.resize(size_t(n));
  const float h = p.smoothing_radius, h2 = h * h, coef = ff_poly6_coef(h), m = p.particle_mass;
  const float rho0 = p.rest_density, k = p.gas_constant;
  const FluidState& s = f.s;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const float xi = s.x[i], yi = s.y[i], zi = s.z[i];
    float sum = 0.0f;
    f.grid.forEachRange(xi, yi, zi, [&](uint32_t b, uint32_t e) {
      for (uint32_t j = b; j < e; ++j) {
        const float dx = xi - s.x[j], dy = yi - s.y[j], dz = zi - s.z[j];
        sum += ff_poly6(dx * dx + dy * dy + dz * dz, h2, coef);
      }
    });
    float fluid_side = 1.0f;
    forEachWall(xi, yi, zi, h, box,
                [&](int, float d, float) { fluid_side *= 1.0f - ff_poly6_wall_fraction(d, h, coef); });
    const float rho = m * sum + rho0 * ff_combine_wall_fractions(fluid_side);
    f.rho[i] = rho;
    f.p[i] = ff_pressure(rho, rho0, k);
  }
}

void addPressureAccel(CpuFluid& f, const FluidParams& p, const ContainerDesc& box) {
  const long n = long(f.size());
  const float h = p.smoothing_radius, coef = ff_spiky_grad_coef(h), m = p.particle_mass;
  const FluidState& s = f.s;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const float xi = s.x[i], yi = s.y[i], zi = s.z[i], pi = f.p[i], rhoi = f.rho[i];
    float fx = 0.0f, fy = 0.0f, fz = 0.0f;
    f.grid.forEachRange(xi, yi, zi, [&](uint32_t b, uint32_t e) {
      for (uint32_t j = b; j < e; ++j) {
        const float dx = xi - s.x[j], dy = yi - s.y[j], dz = zi - s.z[j];
        const float r = std::sqrt(dx * dx + dy * dy + dz * dz);
        const float g = ff_spiky_grad_factor(r, h, coef);  // grad W = -g r_ij
        if (g == 0.0f) continue;
        const float c = m * (pi + f.p[j]) / (2.0f * f.rho[j]) * g;  // -(...) * grad W = +c r_ij
        fx += c * dx, fy += c * dy, fz += c * dz;
      }
    });
    float a[3] = {fx / rhoi, fy / rhoi, fz / rhoi};
    forEachWall(xi, yi, zi, h, box, [&](int d, float dist, float sign) {
      a[d] += sign * ff_wall_pressure_accel(dist, h, pi, rhoi);
    });
    f.ax[i] += a[0], f.ay[i] += a[1], f.az[i] += a[2];
  }
}

void addViscosityGravity(CpuFluid& f, const FluidParams& p) {
  const long n = long(f.size());
  const float h = p.smoothing_radius, coef = ff_visc_lap_coef(h), m = p.particle_mass, mu = p.viscosity;
  const FluidState& s = f.s;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const float xi = s.x[i], yi = s.y[i], zi = s.z[i];
    float fx = 0.0f, fy = 0.0f, fz = 0.0f;
    if (mu > 0.0f) {
      f.grid.forEachRange(xi, yi, zi, [&](uint32_t b, uint32_t e) {
        for (uint32_t j = b; j < e; ++j) {
          const float dx = xi - s.x[j], dy = yi - s.y[j], dz = zi - s.z[j];
          const float r = std::sqrt(dx * dx + dy * dy + dz * dz);
          const float c = m * ff_visc_lap(r, h, coef) / f.rho[j];
          fx += c * (s.vx[j] - s.vx[i]), fy += c * (s.vy[j] - s.vy[i]), fz += c * (s.vz[j] - s.vz[i]);
        }
      });
    }
    const float inv = mu / f.rho[i];
    f.ax[i] += fx * inv + p.gravity[0], f.ay[i] += fy * inv + p.gravity[1],
        f.az[i] += fz * inv + p.gravity[2];
  }
}

void integrateFluid(CpuFluid& f, const FluidParams& p, const ContainerDesc& box, float dt) {
  const long n = long(f.size());
  const float vmax = p.max_step_fraction * p.smoothing_radius / dt;
  const float eps = 1e-6f * p.smoothing_radius;
  FluidState& s = f.s;
  f.grid_current = false;
#pragma omp parallel for schedule(static)
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
  }
}

}  // namespace ff
