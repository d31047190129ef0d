// forces.cl - phase "forces": symmetric pressure force / rho_i with the
// analytic wall's pressure, viscosity (Laplacian of the viscosity kernel) and
// gravity. Mirrors computeWcsphForces of src/cpu/fluid_cpu.cpp: one neighbour
// walk (ascending sorted order; the 27 cells around the particle, as
// density.cl) with the two sums kept apart, and the same final additions.
#pragma OPENCL FP_CONTRACT OFF
#include "ff_check.h"
#include "ff_grid.h"
#include "ff_sph.h"

__kernel void forces(__global const float* x, __global const float* y, __global const float* z,
                     __global const float* vx, __global const float* vy, __global const float* vz,
                     __global const float* rho, __global const float* p, uint n, __global const uint* start,
                     float4 geo, int4 dims, float h, float mass, float mu, float4 gravity, float4 box_lo,
                     float4 box_hi, __global float* ax, __global float* ay, __global float* az,
                     __global int* bad, int tag) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float grad_coef = ff_spiky_grad_coef(h), lap_coef = ff_visc_lap_coef(h);
  const float xi = x[i], yi = y[i], zi = z[i], pi = p[i], rhoi = rho[i];
  const float vxi = vx[i], vyi = vy[i], vzi = vz[i];
  uint b[9], e[9];
  ff_grid_ranges(start, ff_cell_coord(xi, geo.x, geo.w, dims.x), ff_cell_coord(yi, geo.y, geo.w, dims.y),
                 ff_cell_coord(zi, geo.z, geo.w, dims.z), dims.x, dims.y, dims.z, b, e);
  float px = 0.0f, py = 0.0f, pz = 0.0f;  // pressure
  float fx = 0.0f, fy = 0.0f, fz = 0.0f;  // viscosity
  const int viscous = mu > 0.0f;
  for (int r = 0; r < 9; ++r)
    for (uint j = b[r]; j < e[r]; ++j) {
      const float dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];
      const float dist = sqrt(dx * dx + dy * dy + dz * dz);
      const float rhoj = rho[j];
      const float g = ff_spiky_grad_factor(dist, h, grad_coef);  // grad W = -g r_ij
      if (g != 0.0f) {
        const float c = mass * (pi + p[j]) / (2.0f * rhoj) * g;
        px += c * dx, py += c * dy, pz += c * dz;
      }
      if (viscous) {
        const float c = mass * ff_visc_lap(dist, h, lap_coef) / rhoj;
        fx += c * (vx[j] - vxi), fy += c * (vy[j] - vyi), fz += c * (vz[j] - vzi);
      }
    }
  float a[3] = {px / rhoi, py / rhoi, pz / rhoi};
  const float pos[3] = {xi, yi, zi}, lo[3] = {box_lo.x, box_lo.y, box_lo.z},
              hi[3] = {box_hi.x, box_hi.y, box_hi.z};
  for (int d = 0; d < 3; ++d) {
    const float dlo = pos[d] - lo[d], dhi = hi[d] - pos[d];
    if (dlo < h) a[d] += ff_wall_pressure_accel(dlo, h, pi, rhoi);
    if (dhi < h) a[d] += -1.0f * ff_wall_pressure_accel(dhi, h, pi, rhoi);
  }
  const float inv = mu / rhoi;
  // As the CPU: the pressure part (from 0), then viscosity + gravity.
  float rx = 0.0f + a[0], ry = 0.0f + a[1], rz = 0.0f + a[2];
  rx += fx * inv + gravity.x, ry += fy * inv + gravity.y, rz += fz * inv + gravity.z;
  ax[i] = rx, ay[i] = ry, az[i] = rz;
  if (!isfinite(rx) || !isfinite(ry) || !isfinite(rz)) ff_report_nonfinite(bad, tag);
}
