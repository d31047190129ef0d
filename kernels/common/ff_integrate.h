/* ff_integrate.h - phase "integrate" for one fluid particle: symplectic Euler
 * with the velocity limit (no particle moves more than max_step_fraction * h
 * in a substep) and the container clamp. Shared by the OpenMP backend
 * (src/cpu/fluid_cpu.cpp) and kernels/integrate.cl. */
#ifndef FF_INTEGRATE_H
#define FF_INTEGRATE_H
#include "ff_compat.h"

/* The squared speed, in one rounding order for both backends: the velocity
 * limit reads it, and so does the metrics' max_speed, which sets the CFL
 * substeps (a different rounding there would give the backends different
 * substeps where they carry over the frame, fluid.substep_carry). */
FF_FN float ff_speed2(float vx, float vy, float vz) {
  return vx * vx + vy * vy + vz * vz;
}

/* Advances velocity v and position x (3 floats each) by dt under the
 * acceleration a: v += dt a, limited to speed vmax, then x += dt v, kept
 * eps inside [lo, hi] with the velocity into a wall zeroed. Returns 1 when
 * the speed limit cut the velocity (a "velocity clamp", docs/METRICS.md),
 * else 0. */
FF_FN int ff_integrate_particle(float* v, float* x, const float* a, float dt, float vmax, const float* lo,
                                const float* hi, float eps) {
  for (int d = 0; d < 3; ++d) v[d] = v[d] + dt * a[d];
  const float sp = FF_SQRT(ff_speed2(v[0], v[1], v[2]));
  int clamped = 0;
  if (sp > vmax) {
    const float c = vmax / sp;
    v[0] *= c, v[1] *= c, v[2] *= c;
    clamped = 1;
  }
  for (int d = 0; d < 3; ++d) {
    x[d] = x[d] + dt * v[d];
    const float l = lo[d] + eps, u = hi[d] - eps;
    if (x[d] < l) x[d] = l, v[d] = v[d] < 0.0f ? 0.0f : v[d];
    if (x[d] > u) x[d] = u, v[d] = v[d] > 0.0f ? 0.0f : v[d];
  }
  return clamped;
}

#endif /* FF_INTEGRATE_H */
