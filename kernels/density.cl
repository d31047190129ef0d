// density.cl - phase "density": rho_i = m sum_j W_poly6 + the analytic wall
// term (the walls' shares combined as in ff_combine_wall_fractions),
// p_i = k (rho_i - rho0). Mirrors computeDensityPressure in
// src/cpu/fluid_cpu.cpp term by term and in the same summation order
// (neighbours in ascending sorted order; walls x, y, z, low then high).
// Two kernels with the same sums: `density` (one particle per work-item, the
// 27 cells around it: for GPUs) and `density_lanes` (8 particles per
// work-item as float8 lanes, ff_lanes.h: for CPU devices).
#pragma OPENCL FP_CONTRACT OFF
#include "ff_check.h"
#include "ff_grid.h"
#include "ff_lanes.h"
#include "ff_sph.h"

// Density and pressure of particle i from its neighbour sum.
inline void density_finish(uint i, float xi, float yi, float zi, float sum, float h, float coef, float mass,
                           float rho0, float gas_k, float4 box_lo, float4 box_hi, __global float* rho_out,
                           __global float* p_out, __global int* bad, int tag) {
  const float pos[3] = {xi, yi, zi}, lo[3] = {box_lo.x, box_lo.y, box_lo.z},
              hi[3] = {box_hi.x, box_hi.y, box_hi.z};
  const float rho = mass * sum + rho0 * ff_wall_density_share(pos, lo, hi, h, coef);
  const float p = ff_pressure(rho, rho0, gas_k);
  rho_out[i] = rho;
  p_out[i] = p;
  if (!isfinite(rho) || !isfinite(p)) ff_report_nonfinite(bad, tag);
}

__kernel void density(__global const float* x, __global const float* y, __global const float* z, uint n,
                      __global const uint* start, float4 geo, int4 dims, FfSphArgs P, __global float* rho_out,
                      __global float* p_out, __global int* bad, int tag) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float h = P.h, mass = P.mass, rho0 = P.rho0, gas_k = P.gas_k;
  const float4 box_lo = (float4)(P.lo[0], P.lo[1], P.lo[2], 0.0f),
               box_hi = (float4)(P.hi[0], P.hi[1], P.hi[2], 0.0f);
  const float h2 = h * h, coef = ff_poly6_coef(h);
  const float xi = x[i], yi = y[i], zi = z[i];
  uint b[9], e[9];
  ff_grid_ranges(start, ff_cell_coord(xi, geo.x, geo.w, dims.x), ff_cell_coord(yi, geo.y, geo.w, dims.y),
                 ff_cell_coord(zi, geo.z, geo.w, dims.z), dims.x, dims.y, dims.z, b, e);
  float sum = 0.0f;
  for (int r = 0; r < 9; ++r)
    for (uint j = b[r]; j < e[r]; ++j) {
      const float dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];
      sum += ff_poly6(dx * dx + dy * dy + dz * dz, h2, coef);
    }
  density_finish(i, xi, yi, zi, sum, h, coef, mass, rho0, gas_k, box_lo, box_hi, rho_out, p_out, bad, tag);
}

// P.cell: the grid's cell size (1 / geo.w).
__kernel void density_lanes(__global const float* x, __global const float* y, __global const float* z, uint n,
                            __global const uint* start, float4 geo, int4 dims, FfSphArgs P,
                            __global float* rho_out, __global float* p_out, __global int* bad, int tag) {
  const uint i0 = 8u * get_global_id(0);
  if (i0 >= n) return;
  const float cell = P.cell, h = P.h, mass = P.mass, rho0 = P.rho0, gas_k = P.gas_k;
  const float4 box_lo = (float4)(P.lo[0], P.lo[1], P.lo[2], 0.0f),
               box_hi = (float4)(P.hi[0], P.hi[1], P.hi[2], 0.0f);
  const float h2 = h * h, coef = ff_poly6_coef(h);
  const int8 valid = ff_lane_valid(i0, n);
  const float8 xi = ff_load_lanes(x, i0, valid, FF_LANE_FAR), yi = ff_load_lanes(y, i0, valid, FF_LANE_FAR),
               zi = ff_load_lanes(z, i0, valid, FF_LANE_FAR);
  const float reach = ff_query_reach(h, cell);
  const FfLanesRows q = ff_lanes_rows(xi, yi, zi, valid, geo, dims, reach);
  float8 sum = (float8)(0.0f);
  for (int cz = q.z0; cz <= q.z1; ++cz)
    for (int cy = q.y0; cy <= q.y1; ++cy) {
      uint b, e;
      if (!ff_row_span(start, q.lo, q.hi, reach, cy, cz, q.o, cell, geo.w, q.nn, &b, &e)) continue;
      for (uint j = b; j < e; ++j) {
        const float8 dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];
        sum += ff_poly6_8(dx * dx + dy * dy + dz * dz, h2, coef);
      }
    }
  float xs[8], ys[8], zs[8], sums[8];
  vstore8(xi, 0, xs), vstore8(yi, 0, ys), vstore8(zi, 0, zs), vstore8(sum, 0, sums);
  const uint m = n - i0 < 8u ? n - i0 : 8u;
  for (uint l = 0; l < m; ++l)
    density_finish(i0 + l, xs[l], ys[l], zs[l], sums[l], h, coef, mass, rho0, gas_k, box_lo, box_hi, rho_out,
                   p_out, bad, tag);
}
