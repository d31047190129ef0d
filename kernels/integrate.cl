// integrate.cl - phase "integrate": symplectic Euler with the velocity limit
// (no particle moves more than max_step_fraction * h per step) and the
// container clamp. Mirrors integrateFluid in src/cpu/fluid_cpu.cpp.
#pragma OPENCL FP_CONTRACT OFF
#include "ff_check.h"
#include "ff_compat.h"

__kernel void integrate(__global float* x, __global float* y, __global float* z, __global float* vx,
                        __global float* vy, __global float* vz, __global const float* ax,
                        __global const float* ay, __global const float* az, uint n, float dt, float vmax,
                        float eps, float4 box_lo, float4 box_hi, __global int* bad, int tag) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  float v[3] = {vx[i] + dt * ax[i], vy[i] + dt * ay[i], vz[i] + dt * az[i]};
  const float sp = FF_SQRT(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (sp > vmax) {
    const float c = vmax / sp;
    v[0] *= c, v[1] *= c, v[2] *= c;
  }
  float p[3] = {x[i] + dt * v[0], y[i] + dt * v[1], z[i] + dt * v[2]};
  const float lo[3] = {box_lo.x, box_lo.y, box_lo.z}, hi[3] = {box_hi.x, box_hi.y, box_hi.z};
  for (int d = 0; d < 3; ++d) {
    const float l = lo[d] + eps, u = hi[d] - eps;
    if (p[d] < l) p[d] = l, v[d] = v[d] < 0.0f ? 0.0f : v[d];
    if (p[d] > u) p[d] = u, v[d] = v[d] > 0.0f ? 0.0f : v[d];
  }
  x[i] = p[0], y[i] = p[1], z[i] = p[2];
  vx[i] = v[0], vy[i] = v[1], vz[i] = v[2];
  int ok = 1;
  for (int d = 0; d < 3; ++d) ok = ok && isfinite(p[d]) && isfinite(v[d]);
  if (!ok) ff_report_nonfinite(bad, tag);
}
