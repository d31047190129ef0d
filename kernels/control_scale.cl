// control_scale.cl - phase "control scale": the density scale s_i of every
// control particle (eq. 5) and u_bar, the kernel-weighted mean fluid velocity
// around it (for the fluid feedback). The fluid is found through an index grid
// of cell size = the control radius (order[] maps sorted slots to particles).
// Mirrors Controller::computeScale in src/control/controller.cpp.
#pragma OPENCL FP_CONTRACT OFF
#include "ff_control.h"
#include "ff_grid.h"
#include "ff_sph.h"

__kernel void control_scale(__global const float* cx, __global const float* cy, __global const float* cz,
                            uint nc, __global const float* fx, __global const float* fy,
                            __global const float* fz, __global const float* fvx, __global const float* fvy,
                            __global const float* fvz, __global const uint* order, __global const uint* start,
                            float4 geo, int4 dims, float radius, float volume, __global float* s_out,
                            __global float* ux_out, __global float* uy_out, __global float* uz_out,
                            __global int* bad) {
  const uint i = get_global_id(0);
  if (i >= nc) return;
  const float r2 = radius * radius, coef = ff_poly6_coef(radius);
  const float px = cx[i], py = cy[i], pz = cz[i];
  uint b[9], e[9];
  ff_grid_ranges(start, ff_cell_coord(px, geo.x, geo.w, dims.x), ff_cell_coord(py, geo.y, geo.w, dims.y),
                 ff_cell_coord(pz, geo.z, geo.w, dims.z), dims.x, dims.y, dims.z, b, e);
  float sum = 0.0f, ux = 0.0f, uy = 0.0f, uz = 0.0f;
  for (int r = 0; r < 9; ++r)
    for (uint k = b[r]; k < e[r]; ++k) {
      const uint j = order[k];
      const float dx = px - fx[j], dy = py - fy[j], dz = pz - fz[j];
      const float w = ff_poly6(dx * dx + dy * dy + dz * dz, r2, coef);
      if (w <= 0.0f) continue;
      sum += w;
      ux += w * fvx[j], uy += w * fvy[j], uz += w * fvz[j];
    }
  const float rho_hat = volume * sum;
  const float s = ff_control_scale(rho_hat);
  // Where the kernel is only partly filled the missing part counts as still air.
  const float norm = sum > 0.0f ? volume / FF_FMAX(rho_hat, 1.0f) : 0.0f;
  s_out[i] = s;
  ux_out[i] = ux * norm, uy_out[i] = uy * norm, uz_out[i] = uz * norm;
  if (!isfinite(s) || !isfinite(ux * norm) || !isfinite(uy * norm) || !isfinite(uz * norm)) atomic_or(bad, 1);
}
