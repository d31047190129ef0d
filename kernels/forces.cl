// forces.cl - phase "forces": the kernels of the non-pressure force plug-ins
// (host/forces/), each adding its acceleration to a as its OpenMP
// counterpart in src/cpu/forces/ does, with the same body of ff_sph.h.
// - `gravity` (host/forces/gravity.cpp): ff_add_gravity_accel.
// - `viscosity` and `viscosity_lanes` (host/forces/viscosity.cpp): one
//   neighbour walk in ascending sorted order, finished by
//   ff_add_viscosity_accel. Two kernels with the same sums, as density.cl:
//   `viscosity` (one particle per work-item, 27 cells: for GPUs) and
//   `viscosity_lanes` (8 particles per work-item as float8 lanes, ff_lanes.h:
//   for CPU devices).
#pragma OPENCL FP_CONTRACT OFF
#include "ff_check.h"
#include "ff_grid.h"
#include "ff_lanes.h"
#include "ff_sph.h"

__kernel void gravity(__global float* ax, __global float* ay, __global float* az, uint n, float4 gravity,
                      __global int* bad, int tag) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float g[3] = {gravity.x, gravity.y, gravity.z};
  float a[3] = {ax[i], ay[i], az[i]};
  ff_add_gravity_accel(g, a);
  ax[i] = a[0], ay[i] = a[1], az[i] = a[2];
  if (!isfinite(a[0]) || !isfinite(a[1]) || !isfinite(a[2])) ff_report_nonfinite(bad, tag);
}

inline void viscosity_finish(uint i, float rhoi, float fx, float fy, float fz, float mu, __global float* ax,
                             __global float* ay, __global float* az, __global int* bad, int tag) {
  const float vs[3] = {fx, fy, fz};
  float a[3] = {ax[i], ay[i], az[i]};
  ff_add_viscosity_accel(vs, mu, rhoi, a);
  ax[i] = a[0], ay[i] = a[1], az[i] = a[2];
  if (!isfinite(a[0]) || !isfinite(a[1]) || !isfinite(a[2])) ff_report_nonfinite(bad, tag);
}

__kernel void viscosity(__global const float* x, __global const float* y, __global const float* z,
                        __global const float* vx, __global const float* vy, __global const float* vz,
                        __global const float* rho, uint n, __global const uint* start, float4 geo, int4 dims,
                        FfSphArgs P, __global float* ax, __global float* ay, __global float* az,
                        __global int* bad, int tag) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float h = P.h, mass = P.mass, mu = P.mu;
  const float lap_coef = ff_visc_lap_coef(h);
  const float xi = x[i], yi = y[i], zi = z[i];
  const float vxi = vx[i], vyi = vy[i], vzi = vz[i];
  float fx = 0.0f, fy = 0.0f, fz = 0.0f;
  uint b[9], e[9];
  ff_grid_ranges(start, ff_cell_coord(xi, geo.x, geo.w, dims.x), ff_cell_coord(yi, geo.y, geo.w, dims.y),
                 ff_cell_coord(zi, geo.z, geo.w, dims.z), dims.x, dims.y, dims.z, b, e);
  for (int r = 0; r < 9; ++r)
    for (uint j = b[r]; j < e[r]; ++j) {
      const float dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];
      const float dist = sqrt(dx * dx + dy * dy + dz * dz);
      const float c = ff_visc_pair(ff_visc_lap(dist, h, lap_coef), rho[j], mass);
      fx += c * (vx[j] - vxi), fy += c * (vy[j] - vyi), fz += c * (vz[j] - vzi);
    }
  viscosity_finish(i, rho[i], fx, fy, fz, mu, ax, ay, az, bad, tag);
}

// P.cell: the grid's cell size (1 / geo.w). rho holds a multiple of 8 floats.
__kernel void viscosity_lanes(__global const float* x, __global const float* y, __global const float* z,
                              __global const float* vx, __global const float* vy, __global const float* vz,
                              __global const float* rho, uint n, __global const uint* start, float4 geo,
                              int4 dims, FfSphArgs P, __global float* ax, __global float* ay,
                              __global float* az, __global int* bad, int tag) {
  const uint i0 = 8u * get_global_id(0);
  if (i0 >= n) return;
  const float cell = P.cell, h = P.h, mass = P.mass, mu = P.mu;
  const float lap_coef = ff_visc_lap_coef(h);
  const int8 valid = ff_lane_valid(i0, n);
  const float8 zero = (float8)(0.0f);
  float8 fx = zero, fy = zero, fz = zero;
  const float8 xi = ff_load_lanes(x, i0, valid, FF_LANE_FAR), yi = ff_load_lanes(y, i0, valid, FF_LANE_FAR),
               zi = ff_load_lanes(z, i0, valid, FF_LANE_FAR);
  const float8 vxi = ff_load_lanes(vx, i0, valid, 0.0f), vyi = ff_load_lanes(vy, i0, valid, 0.0f),
               vzi = ff_load_lanes(vz, i0, valid, 0.0f);
  const float reach = ff_query_reach(h, cell);
  const FfLanesRows q = ff_lanes_rows(xi, yi, zi, valid, geo, dims, reach);
  for (int cz = q.z0; cz <= q.z1; ++cz)
    for (int cy = q.y0; cy <= q.y1; ++cy) {
      uint b, e;
      if (!ff_row_span(start, q.lo, q.hi, reach, cy, cz, q.o, cell, geo.w, q.nn, &b, &e)) continue;
      for (uint j = b; j < e; ++j) {
        const float8 dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];
        const float8 dist = sqrt(dx * dx + dy * dy + dz * dz);
        const float8 cv = ff_visc_pair_8(ff_visc_lap_8(dist, h, lap_coef), rho[j], mass);
        fx += cv * (vx[j] - vxi), fy += cv * (vy[j] - vyi), fz += cv * (vz[j] - vzi);
      }
    }
  float s[3][8];
  vstore8(fx, 0, s[0]), vstore8(fy, 0, s[1]), vstore8(fz, 0, s[2]);
  const uint m = n - i0 < 8u ? n - i0 : 8u;
  for (uint l = 0; l < m; ++l)
    viscosity_finish(i0 + l, rho[i0 + l], s[0][l], s[1][l], s[2][l], mu, ax, ay, az, bad, tag);
}
