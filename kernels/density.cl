// density.cl - phase "density": rho_i = m sum_j W_poly6 + the analytic wall
// term (the walls' shares combined as in ff_combine_wall_fractions),
// p_i = k (rho_i - rho0). Mirrors computeDensityPressure in
// src/cpu/fluid_cpu.cpp term by term and in the same summation order
// (neighbours in ascending sorted order; walls x, y, z, low then high). The
// grid's cells are at least h wide, so the 27 cells around a particle hold its
// neighbours (pruning them to the sphere, as the OpenMP backend does, changes
// no sum but made PoCL's vectorised work-groups slower here).
#pragma OPENCL FP_CONTRACT OFF
#include "ff_check.h"
#include "ff_grid.h"
#include "ff_sph.h"

__kernel void density(__global const float* x, __global const float* y, __global const float* z, uint n,
                      __global const uint* start, float4 geo, int4 dims, float h, float mass, float rho0,
                      float gas_k, float4 box_lo, float4 box_hi, __global float* rho_out,
                      __global float* p_out, __global int* bad, int tag) {
  const uint i = get_global_id(0);
  if (i >= n) return;
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
  const float pos[3] = {xi, yi, zi}, lo[3] = {box_lo.x, box_lo.y, box_lo.z},
              hi[3] = {box_hi.x, box_hi.y, box_hi.z};
  float fluid_side = 1.0f;  // the kernel's share on the fluid side of every wall within h
  for (int d = 0; d < 3; ++d) {
    const float dlo = pos[d] - lo[d], dhi = hi[d] - pos[d];
    if (dlo < h) fluid_side *= 1.0f - ff_poly6_wall_fraction(dlo, h, coef);
    if (dhi < h) fluid_side *= 1.0f - ff_poly6_wall_fraction(dhi, h, coef);
  }
  const float rho = mass * sum + rho0 * ff_combine_wall_fractions(fluid_side);
  const float p = ff_pressure(rho, rho0, gas_k);
  rho_out[i] = rho;
  p_out[i] = p;
  if (!isfinite(rho) || !isfinite(p)) ff_report_nonfinite(bad, tag);
}
