// pressure_wcsph.cl - phase "pressure" with the WCSPH solver: adds the
// symmetric pressure force / rho_i and the analytic wall's mirrored pressure
// (ff_wcsph_pressure_accel) to the accelerations of the earlier phases.
// Mirrors addWcsphPressure of src/cpu/fluid_cpu.cpp: one neighbour walk in
// ascending sorted order. `pressure_wcsph` (one particle per work-item: for
// GPUs) and `pressure_wcsph_lanes` (8 particles as float8 lanes: CPU devices).
#pragma OPENCL FP_CONTRACT OFF
#include "ff_check.h"
#include "ff_grid.h"
#include "ff_lanes.h"
#include "ff_sph.h"

inline void pressure_finish(uint i, float xi, float yi, float zi, float pi, float rhoi, float px, float py,
                            float pz, float h, float4 box_lo, float4 box_hi, __global float* ax,
                            __global float* ay, __global float* az, __global int* bad, int tag) {
  const float pos[3] = {xi, yi, zi}, lo[3] = {box_lo.x, box_lo.y, box_lo.z},
              hi[3] = {box_hi.x, box_hi.y, box_hi.z}, ps[3] = {px, py, pz};
  float a[3];
  ff_wcsph_pressure_accel(pos, lo, hi, h, pi, rhoi, ps, a);
  const float rx = ax[i] + a[0], ry = ay[i] + a[1], rz = az[i] + a[2];
  ax[i] = rx, ay[i] = ry, az[i] = rz;
  if (!isfinite(rx) || !isfinite(ry) || !isfinite(rz)) ff_report_nonfinite(bad, tag);
}

__kernel void pressure_wcsph(__global const float* x, __global const float* y, __global const float* z,
                             __global const float* rho, __global const float* p, uint n,
                             __global const uint* start, float4 geo, int4 dims, FfSphArgs P,
                             __global float* ax, __global float* ay, __global float* az, __global int* bad,
                             int tag) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float h = P.h, mass = P.mass;
  const float4 box_lo = (float4)(P.lo[0], P.lo[1], P.lo[2], 0.0f),
               box_hi = (float4)(P.hi[0], P.hi[1], P.hi[2], 0.0f);
  const float grad_coef = ff_spiky_grad_coef(h);
  const float xi = x[i], yi = y[i], zi = z[i], pi = p[i];
  uint b[9], e[9];
  ff_grid_ranges(start, ff_cell_coord(xi, geo.x, geo.w, dims.x), ff_cell_coord(yi, geo.y, geo.w, dims.y),
                 ff_cell_coord(zi, geo.z, geo.w, dims.z), dims.x, dims.y, dims.z, b, e);
  float px = 0.0f, py = 0.0f, pz = 0.0f;
  for (int r = 0; r < 9; ++r)
    for (uint j = b[r]; j < e[r]; ++j) {
      const float dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];
      const float dist = sqrt(dx * dx + dy * dy + dz * dz);
      const float g = ff_spiky_grad_factor(dist, h, grad_coef);  // grad W = -g r_ij
      if (g != 0.0f) {
        const float c = ff_pressure_pair(g, pi, p[j], rho[j], mass);
        px += c * dx, py += c * dy, pz += c * dz;
      }
    }
  pressure_finish(i, xi, yi, zi, pi, rho[i], px, py, pz, h, box_lo, box_hi, ax, ay, az, bad, tag);
}

// P.cell: the grid's cell size (1 / geo.w). rho and p hold a multiple of 8 floats.
__kernel void pressure_wcsph_lanes(__global const float* x, __global const float* y, __global const float* z,
                                   __global const float* rho, __global const float* p, uint n,
                                   __global const uint* start, float4 geo, int4 dims, FfSphArgs P,
                                   __global float* ax, __global float* ay, __global float* az,
                                   __global int* bad, int tag) {
  const uint i0 = 8u * get_global_id(0);
  if (i0 >= n) return;
  const float cell = P.cell, h = P.h, mass = P.mass;
  const float4 box_lo = (float4)(P.lo[0], P.lo[1], P.lo[2], 0.0f),
               box_hi = (float4)(P.hi[0], P.hi[1], P.hi[2], 0.0f);
  const float grad_coef = ff_spiky_grad_coef(h);
  const int8 valid = ff_lane_valid(i0, n);
  const float8 xi = ff_load_lanes(x, i0, valid, FF_LANE_FAR), yi = ff_load_lanes(y, i0, valid, FF_LANE_FAR),
               zi = ff_load_lanes(z, i0, valid, FF_LANE_FAR);
  const float8 pi = ff_load_lanes(p, i0, valid, 0.0f);
  const float reach = ff_query_reach(h, cell);
  const FfLanesRows q = ff_lanes_rows(xi, yi, zi, valid, geo, dims, reach);
  const float8 zero = (float8)(0.0f);
  float8 px = zero, py = zero, pz = zero;
  for (int cz = q.z0; cz <= q.z1; ++cz)
    for (int cy = q.y0; cy <= q.y1; ++cy) {
      uint b, e;
      if (!ff_row_span(start, q.lo, q.hi, reach, cy, cz, q.o, cell, geo.w, q.nn, &b, &e)) continue;
      for (uint j = b; j < e; ++j) {
        const float8 dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];
        const float8 dist = sqrt(dx * dx + dy * dy + dz * dz);
        const float8 g = ff_spiky_grad_factor_8(dist, h, grad_coef);  // grad W = -g r_ij
        const float8 c = ff_pressure_pair_8(g, pi, p[j], rho[j], mass);
        px += c * dx, py += c * dy, pz += c * dz;
      }
    }
  float s[6][8];
  vstore8(xi, 0, s[0]), vstore8(yi, 0, s[1]), vstore8(zi, 0, s[2]);
  vstore8(px, 0, s[3]), vstore8(py, 0, s[4]), vstore8(pz, 0, s[5]);
  const uint m = n - i0 < 8u ? n - i0 : 8u;
  for (uint l = 0; l < m; ++l) {
    const uint i = i0 + l;
    pressure_finish(i, s[0][l], s[1][l], s[2][l], p[i], rho[i], s[3][l], s[4][l], s[5][l], h, box_lo, box_hi,
                    ax, ay, az, bad, tag);
  }
}
