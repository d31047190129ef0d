// forces.cl - phase "forces": symmetric pressure force / rho_i with the
// analytic wall's pressure, viscosity (Laplacian of the viscosity kernel) and
// gravity. Mirrors computeWcsphForces of src/cpu/fluid_cpu.cpp: one neighbour
// walk (ascending sorted order) with the two sums kept apart, and the same
// final additions. Two kernels with the same sums, as density.cl: `forces`
// (one particle per work-item, 27 cells: for GPUs) and `forces_lanes` (8
// particles per work-item as float8 lanes, ff_lanes.h: for CPU devices).
#pragma OPENCL FP_CONTRACT OFF
#include "ff_check.h"
#include "ff_grid.h"
#include "ff_lanes.h"
#include "ff_sph.h"

// Acceleration of particle i from its pressure sums px.. and viscosity sums fx..
inline void forces_finish(uint i, float xi, float yi, float zi, float pi, float rhoi, float px, float py,
                          float pz, float fx, float fy, float fz, float h, float mu, float4 gravity,
                          float4 box_lo, float4 box_hi, __global float* ax, __global float* ay,
                          __global float* az, __global int* bad, int tag) {
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
        const float c = ff_pressure_pair(g, pi, p[j], rhoj, mass);
        px += c * dx, py += c * dy, pz += c * dz;
      }
      if (viscous) {
        const float c = ff_visc_pair(ff_visc_lap(dist, h, lap_coef), rhoj, mass);
        fx += c * (vx[j] - vxi), fy += c * (vy[j] - vyi), fz += c * (vz[j] - vzi);
      }
    }
  forces_finish(i, xi, yi, zi, pi, rhoi, px, py, pz, fx, fy, fz, h, mu, gravity, box_lo, box_hi, ax, ay, az,
                bad, tag);
}

// cell: the grid's cell size (1 / geo.w). rho and p hold a multiple of 8 floats.
__kernel void forces_lanes(__global const float* x, __global const float* y, __global const float* z,
                           __global const float* vx, __global const float* vy, __global const float* vz,
                           __global const float* rho, __global const float* p, uint n,
                           __global const uint* start, float4 geo, int4 dims, float cell, float h, float mass,
                           float mu, float4 gravity, float4 box_lo, float4 box_hi, __global float* ax,
                           __global float* ay, __global float* az, __global int* bad, int tag) {
  const uint i0 = 8u * get_global_id(0);
  if (i0 >= n) return;
  const float grad_coef = ff_spiky_grad_coef(h), lap_coef = ff_visc_lap_coef(h);
  const int8 valid = ff_lane_valid(i0, n);
  const float8 xi = ff_load_lanes(x, i0, valid, FF_LANE_FAR), yi = ff_load_lanes(y, i0, valid, FF_LANE_FAR),
               zi = ff_load_lanes(z, i0, valid, FF_LANE_FAR);
  const float8 pi = ff_load_lanes(p, i0, valid, 0.0f);
  const float8 vxi = ff_load_lanes(vx, i0, valid, 0.0f), vyi = ff_load_lanes(vy, i0, valid, 0.0f),
               vzi = ff_load_lanes(vz, i0, valid, 0.0f);
  const float lo[3] = {ff_lanes_min(xi, valid), ff_lanes_min(yi, valid), ff_lanes_min(zi, valid)};
  const float hi[3] = {ff_lanes_max(xi, valid), ff_lanes_max(yi, valid), ff_lanes_max(zi, valid)};
  const float o[3] = {geo.x, geo.y, geo.z};
  const int nn[3] = {dims.x, dims.y, dims.z};
  const float reach = ff_query_reach(h, cell);
  const int z0 = ff_cell_coord(lo[2] - reach, o[2], geo.w, nn[2]),
            z1 = ff_cell_coord(hi[2] + reach, o[2], geo.w, nn[2]);
  const int y0 = ff_cell_coord(lo[1] - reach, o[1], geo.w, nn[1]),
            y1 = ff_cell_coord(hi[1] + reach, o[1], geo.w, nn[1]);
  const float8 zero = (float8)(0.0f);
  float8 px = zero, py = zero, pz = zero;  // pressure
  float8 fx = zero, fy = zero, fz = zero;  // viscosity
  const int viscous = mu > 0.0f;
  for (int cz = z0; cz <= z1; ++cz)
    for (int cy = y0; cy <= y1; ++cy) {
      uint b, e;
      if (!ff_row_span(start, lo, hi, reach, cy, cz, o, cell, geo.w, nn, &b, &e)) continue;
      for (uint j = b; j < e; ++j) {
        const float8 dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];
        const float8 dist = sqrt(dx * dx + dy * dy + dz * dz);
        const float rhoj = rho[j];
        const float8 g = ff_spiky_grad_factor_8(dist, h, grad_coef);  // grad W = -g r_ij
        const float8 c = ff_pressure_pair_8(g, pi, p[j], rhoj, mass);
        px += c * dx, py += c * dy, pz += c * dz;
        if (viscous) {
          const float8 cv = ff_visc_pair_8(ff_visc_lap_8(dist, h, lap_coef), rhoj, mass);
          fx += cv * (vx[j] - vxi), fy += cv * (vy[j] - vyi), fz += cv * (vz[j] - vzi);
        }
      }
    }
  float s[9][8];
  vstore8(xi, 0, s[0]), vstore8(yi, 0, s[1]), vstore8(zi, 0, s[2]);
  vstore8(px, 0, s[3]), vstore8(py, 0, s[4]), vstore8(pz, 0, s[5]);
  vstore8(fx, 0, s[6]), vstore8(fy, 0, s[7]), vstore8(fz, 0, s[8]);
  const uint m = n - i0 < 8u ? n - i0 : 8u;
  for (uint l = 0; l < m; ++l) {
    const uint i = i0 + l;
    forces_finish(i, s[0][l], s[1][l], s[2][l], p[i], rho[i], s[3][l], s[4][l], s[5][l], s[6][l], s[7][l],
                  s[8][l], h, mu, gravity, box_lo, box_hi, ax, ay, az, bad, tag);
  }
}
