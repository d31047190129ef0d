// dfsph_solve.cl - the per-particle steps of a DFSPH solve between the
// neighbour walks of dfsph_sums.cl, mirroring DfsphSolver::iterate / solve of
// src/cpu/dfsph_solver.cpp with the same ff_dfsph.h bodies: the sources b and
// their sum (per work-group partials), the warm start, the Jacobi increment,
// the velocity updates, the stopping test, the prediction with every other
// acceleration and the final accelerations and pressure. The stopping test
// runs on the device (dfsph_check), so the host enqueues several iterations
// at once and reads the solve's state only after each batch: state[0] = 1
// once the solve stopped (converged or capped), state[1] = its iterations,
// state[2] = 1 if it stopped at the cap. Kernels with `gated` set do nothing
// once state[0] is set. The sum of b is taken in double precision where the
// device has it (cl_khr_fp64), as the OpenMP solver's, so that the stopping
// test decides as the CPU's does; in float elsewhere.
#pragma OPENCL FP_CONTRACT OFF
#include "ff_check.h"
#include "ff_dfsph.h"

#if defined(cl_khr_fp64)
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double dfsph_sum_t;
#else
typedef float dfsph_sum_t;
#endif

// b = the compression the velocities still cause (density: after dt, from
// rho and the walls' share at x + dt u, and the walls' gradient wp there and
// the factor alpha_p with it for this iteration's push and increment,
// ff_dfsph_density_source_at with the density phase's S(x) in `wall`; else
// the divergence where the support is filled), and the sum of b per
// work-group into partial[group] (local size a power of two, at most 8
// bytes of local memory per work-item).
__kernel void dfsph_source(__global const float* rate, __global const float* rho, __global const uchar* bulk,
                           __global const float* x, __global const float* y, __global const float* z,
                           __global const float* ux, __global const float* uy, __global const float* uz,
                           FfDfsphArgs P, uint n, int density, float inv_rho0, float dt, __global float* b,
                           __global dfsph_sum_t* partial, __local dfsph_sum_t* tmp, __global const int* state,
                           int gated, __global const float* alpha, __global const float* wgx,
                           __global const float* wgy, __global const float* wgz, __global const float* vax,
                           __global const float* vay, __global const float* vaz, __global const float* q,
                           __global const float* wall, __global float* wpx, __global float* wpy,
                           __global float* wpz, __global float* alpha_p) {
  if (gated && state[0]) return;  // the same for every work-item: no barrier is skipped by some only
  dfsph_sum_t sum = 0.0f;
  for (uint i = get_global_id(0); i < n; i += get_global_size(0)) {
    float bi;
    if (density) {
      const float pos[3] = {x[i], y[i], z[i]}, u[3] = {ux[i], uy[i], uz[i]}, g0[3] = {wgx[i], wgy[i], wgz[i]},
                  lo[3] = {P.lo[0], P.lo[1], P.lo[2]}, hi[3] = {P.hi[0], P.hi[1], P.hi[2]};
      float g1[3], al;
      bi = ff_dfsph_density_source_at(i, pos, u, rho[i] * inv_rho0, rate[i], dt, g0, alpha[i], wall, vax, vay,
                                      vaz, q, P.eps, lo, hi, P.spacing, P.vol, P.h, P.inv_h, g1, &al);
      wpx[i] = g1[0], wpy[i] = g1[1], wpz[i] = g1[2], alpha_p[i] = al;
    } else {
      bi = ff_dfsph_divergence_source(rate[i], (float)bulk[i]);
    }
    b[i] = bi;
    sum += (dfsph_sum_t)bi;
  }
  const uint lid = get_local_id(0);
  tmp[lid] = sum;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint s = get_local_size(0) / 2; s > 0; s >>= 1) {
    if (lid < s) tmp[lid] = tmp[lid] + tmp[lid + s];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0) partial[get_group_id(0)] = tmp[0];
}

// The stopping test after the sources of iteration state[1] + 1 (`first`:
// iteration 0): the mean of b against tol = tol_hi + tol_lo (a double split
// into two floats), at least min_it and at most max_it iterations, in the
// order of DfsphSolver::iterate. One work-item.
__kernel void dfsph_check(__global const dfsph_sum_t* partial, uint groups, uint n, float tol_hi,
                          float tol_lo, int min_it, int max_it, int first, __global int* state) {
  if (get_global_id(0) != 0 || state[0]) return;
  dfsph_sum_t err = 0.0f;
  for (uint g = 0; g < groups; ++g) err += partial[g];
  err = err / (dfsph_sum_t)n;
  const dfsph_sum_t tol = (dfsph_sum_t)tol_hi + (dfsph_sum_t)tol_lo;
  const int it = first ? 0 : state[1] + 1;
  state[1] = it;
  if (it >= min_it && err <= tol)
    state[0] = 1;
  else if (it >= max_it)
    state[0] = 1, state[2] = 1;
}

// The warm start: `warm` times the last substep's k where the particle compresses.
__kernel void dfsph_warm(__global float* k, __global const float* b, uint n, float warm) {
  const uint i = get_global_id(0);
  if (i < n) k[i] = ff_dfsph_warm_start(k[i], b[i], warm);
}

// inc = the Jacobi increment; k += inc.
__kernel void dfsph_increment(__global float* k, __global float* inc, __global const float* b,
                              __global const float* alpha, uint n, __global const int* state, int gated) {
  const uint i = get_global_id(0);
  if (i >= n || (gated && state[0])) return;
  const float d = ff_dfsph_increment(b[i], alpha[i]);
  inc[i] = d;
  k[i] += d;
}

// u += du * inv (inv = 1 / dt for the density solve, 1 for the divergence solve).
__kernel void dfsph_apply(__global float* ux, __global float* uy, __global float* uz,
                          __global const float* dux, __global const float* duy, __global const float* duz,
                          uint n, float inv, __global const int* state, int gated) {
  const uint i = get_global_id(0);
  if (i >= n || (gated && state[0])) return;
  ux[i] += dux[i] * inv, uy[i] += duy[i] * inv, uz[i] += duz[i] * inv;
}

// u += dt (a + the walls' support): every other acceleration of the substep,
// before the density solve.
__kernel void dfsph_predict(__global const float* x, __global const float* y, __global const float* z,
                            __global float* ux, __global float* uy, __global float* uz,
                            __global const float* ax, __global const float* ay, __global const float* az,
                            uint n, FfDfsphArgs P, float dt) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float pos[3] = {x[i], y[i], z[i]}, acc[3] = {ax[i], ay[i], az[i]},
              lo[3] = {P.lo[0], P.lo[1], P.lo[2]}, hi[3] = {P.hi[0], P.hi[1], P.hi[2]};
  float u[3] = {ux[i], uy[i], uz[i]};
  ff_dfsph_predict(pos, lo, hi, P.spacing, P.vol, P.h, P.inv_h, acc, dt, u);
  ux[i] = u[0], uy[i] = u[1], uz[i] = u[2];
}

// The accelerations that take v to the solved u, and the pressure of both solves.
__kernel void dfsph_finish(__global const float* ux, __global const float* uy, __global const float* uz,
                           __global const float* vx, __global const float* vy, __global const float* vz,
                           __global const float* kd, __global const float* kv, uint n, float inv_dt,
                           float rho0, __global float* ax, __global float* ay, __global float* az,
                           __global float* p, __global int* bad, int tag) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float a0 = (ux[i] - vx[i]) * inv_dt, a1 = (uy[i] - vy[i]) * inv_dt, a2 = (uz[i] - vz[i]) * inv_dt;
  const float pi = ff_dfsph_pressure(kd[i], kv[i], inv_dt, rho0);
  ax[i] = a0, ay[i] = a1, az[i] = a2, p[i] = pi;
  if (!isfinite(a0) || !isfinite(a1) || !isfinite(a2) || !isfinite(pi)) ff_report_nonfinite(bad, tag);
}

// The warm-start k in the grid's new order (new i = old order[i]).
__kernel void dfsph_reorder(__global const uint* order, uint n, __global const float* kd,
                            __global const float* kv, __global float* kd_out, __global float* kv_out) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  kd_out[i] = kd[order[i]], kv_out[i] = kv[order[i]];
}
