// integrate.cl - phase "integrate": symplectic Euler with the velocity limit
// (no particle moves more than max_step_fraction * h per step) and the
// container clamp, ff_integrate_particle (kernels/common/ff_integrate.h) as in
// integrateFluid (src/cpu/fluid_cpu.cpp). Each velocity clamp adds 1 to
// *clamps (a count, so the order of the atomic adds does not matter).
#pragma OPENCL FP_CONTRACT OFF
#include "ff_check.h"
#include "ff_integrate.h"

__kernel void integrate(__global float* x, __global float* y, __global float* z, __global float* vx,
                        __global float* vy, __global float* vz, __global const float* ax,
                        __global const float* ay, __global const float* az, uint n, float dt, float vmax,
                        float eps, float4 box_lo, float4 box_hi, __global uint* clamps, __global int* bad,
                        int tag) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  float v[3] = {vx[i], vy[i], vz[i]}, p[3] = {x[i], y[i], z[i]};
  const float a[3] = {ax[i], ay[i], az[i]};
  const float lo[3] = {box_lo.x, box_lo.y, box_lo.z}, hi[3] = {box_hi.x, box_hi.y, box_hi.z};
  if (ff_integrate_particle(v, p, a, dt, vmax, lo, hi, eps)) atomic_inc(clamps);
  x[i] = p[0], y[i] = p[1], z[i] = p[2];
  vx[i] = v[0], vy[i] = v[1], vz[i] = v[2];
  int ok = 1;
  for (int d = 0; d < 3; ++d) ok = ok && isfinite(p[d]) && isfinite(v[d]);
  if (!ok) ff_report_nonfinite(bad, tag);
}
