// dfsph_sums.cl - the neighbour walks of DFSPH (ff_dfsph.h): the density
// phase's factor (rho, alpha, the wall's gradient, bulk), the rate of rho_hat
// of a velocity field, and the velocity change of a k field. They mirror
// factorSums / rateSums / kappaSums of src/cpu/dfsph_solver.cpp term by term,
// in the same order (neighbours ascending in sorted order), and finish with
// the same ff_dfsph.h bodies. Each comes as one particle per work-item (27
// cells: GPUs) and as 8 particles per work-item in float8 lanes (ff_lanes.h:
// CPU devices), with the same sums bit for bit. A kernel with `gated` set does
// nothing once state[0] says the solve has converged (dfsph_solve.cl).
#pragma OPENCL FP_CONTRACT OFF
#include "ff_check.h"
#include "ff_dfsph.h"
#include "ff_grid.h"
#include "ff_lanes.h"

inline float dfsph_within(float r2, float h2) {
  return r2 < h2 ? 1.0f : 0.0f;
}
inline float8 dfsph_within_8(float8 r2, float h2) {
  return select((float8)(0.0f), (float8)(1.0f), r2 < h2);
}

// The walk of one particle (xi, yi, zi) over the 27 cells around it; `body`
// sees j, dx, dy, dz.
#define DFSPH_WALK_ONE(body)                                                                                \
  {                                                                                                         \
    uint wb[9], we[9];                                                                                      \
    ff_grid_ranges(start, ff_cell_coord(xi, geo.x, geo.w, dims.x), ff_cell_coord(yi, geo.y, geo.w, dims.y), \
                   ff_cell_coord(zi, geo.z, geo.w, dims.z), dims.x, dims.y, dims.z, wb, we);                \
    for (int r = 0; r < 9; ++r)                                                                             \
      for (uint j = wb[r]; j < we[r]; ++j) {                                                                \
        const float dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];                                         \
        body                                                                                                \
      }                                                                                                     \
  }
// The walk of 8 lanes (float8 xi, yi, zi; int8 valid) over the rows within reach of their box.
#define DFSPH_WALK_LANES(body)                                                                            \
  {                                                                                                       \
    const float reach = ff_query_reach(P.h, P.cell);                                                      \
    const FfLanesRows q = ff_lanes_rows(xi, yi, zi, valid, geo, dims, reach);                             \
    for (int cz = q.z0; cz <= q.z1; ++cz)                                                                 \
      for (int cy = q.y0; cy <= q.y1; ++cy) {                                                             \
        uint wb, we;                                                                                      \
        if (!ff_row_span(start, q.lo, q.hi, reach, cy, cz, q.o, P.cell, geo.w, q.nn, &wb, &we)) continue; \
        for (uint j = wb; j < we; ++j) {                                                                  \
          const float8 dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];                                    \
          body                                                                                            \
        }                                                                                                 \
      }                                                                                                   \
  }
#define DFSPH_LANES_BEGIN                                                                                    \
  const uint i0 = 8u * get_global_id(0);                                                                     \
  if (i0 >= n) return;                                                                                       \
  const int8 valid = ff_lane_valid(i0, n);                                                                   \
  const float8 xi = ff_load_lanes(x, i0, valid, FF_LANE_FAR), yi = ff_load_lanes(y, i0, valid, FF_LANE_FAR), \
               zi = ff_load_lanes(z, i0, valid, FF_LANE_FAR);                                                \
  const uint m = n - i0 < 8u ? n - i0 : 8u;

// The bodies take the value type T and the name suffix S of the formulas
// (float and nothing, or float8 and _8: FF_GENERIC).

// Factor sums: w = sum W, a = sum g r_ij, ssq = sum g^2 |r_ij|^2, cnt = neighbours within H.
#define DFSPH_FACTOR_BODY(T, S)                              \
  const T r2 = dx * dx + dy * dy + dz * dz;                  \
  const T dist = sqrt(r2);                                   \
  const T gf = ff_cubic_grad_factor##S(dist, P.inv_h, P.kg); \
  w += ff_cubic##S(dist, P.inv_h, P.k);                      \
  ax += gf * dx, ay += gf * dy, az += gf * dz;               \
  ssq += gf * gf * r2;                                       \
  cnt += dfsph_within##S(r2, h2);

inline void dfsph_factor_finish(uint i, float xi, float yi, float zi, float w, float ax, float ay, float az,
                                float ssq, float cnt, FfDfsphArgs P, __global float* rho,
                                __global float* alpha, __global float* wgx, __global float* wgy,
                                __global float* wgz, __global float* vax, __global float* vay,
                                __global float* vaz, __global float* q, __global float* wall,
                                __global uchar* bulk, __global int* bad, int tag) {
  const float pos[3] = {xi, yi, zi}, a[3] = {ax, ay, az}, lo[3] = {P.lo[0], P.lo[1], P.lo[2]},
              hi[3] = {P.hi[0], P.hi[1], P.hi[2]};
  float rho_hat, wg[3], share, va[3], qi;
  const float al = ff_dfsph_factor_parts(pos, lo, hi, P.spacing, P.h, P.inv_h, P.vol, w, a, ssq, P.eps,
                                         &rho_hat, wg, &share, va, &qi);
  alpha[i] = al;
  wgx[i] = wg[0], wgy[i] = wg[1], wgz[i] = wg[2];
  vax[i] = va[0], vay[i] = va[1], vaz[i] = va[2], q[i] = qi, wall[i] = share;
  const float r = P.rho0 * rho_hat;
  rho[i] = r;
  bulk[i] = (uchar)ff_dfsph_bulk(cnt, rho_hat - P.vol * w, P.full, P.bulk_share);
  if (!isfinite(r) || !isfinite(al)) ff_report_nonfinite(bad, tag);
}

#define DFSPH_FACTOR_ARGS                                                                    \
  __global const float *x, __global const float *y, __global const float *z, uint n,         \
      __global const uint *start, float4 geo, int4 dims, FfDfsphArgs P, __global float *rho, \
      __global float *alpha, __global float *wgx, __global float *wgy, __global float *wgz,  \
      __global float *vax, __global float *vay, __global float *vaz, __global float *q,      \
      __global float *wall, __global uchar *bulk, __global int *bad, int tag

__kernel void dfsph_factor(DFSPH_FACTOR_ARGS) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float h2 = P.h * P.h, xi = x[i], yi = y[i], zi = z[i];
  float w = 0.0f, ax = 0.0f, ay = 0.0f, az = 0.0f, ssq = 0.0f, cnt = 0.0f;
  DFSPH_WALK_ONE(DFSPH_FACTOR_BODY(float, ))
  dfsph_factor_finish(i, xi, yi, zi, w, ax, ay, az, ssq, cnt, P, rho, alpha, wgx, wgy, wgz, vax, vay, vaz, q,
                      wall, bulk, bad, tag);
}

__kernel void dfsph_factor_lanes(DFSPH_FACTOR_ARGS) {
  DFSPH_LANES_BEGIN
  const float h2 = P.h * P.h;
  const float8 zero = (float8)(0.0f);
  float8 w = zero, ax = zero, ay = zero, az = zero, ssq = zero, cnt = zero;
  DFSPH_WALK_LANES(DFSPH_FACTOR_BODY(float8, _8))
  float s[10][8];
  vstore8(xi, 0, s[0]), vstore8(yi, 0, s[1]), vstore8(zi, 0, s[2]), vstore8(w, 0, s[3]);
  vstore8(ax, 0, s[4]), vstore8(ay, 0, s[5]), vstore8(az, 0, s[6]), vstore8(ssq, 0, s[7]);
  vstore8(cnt, 0, s[8]);
  for (uint l = 0; l < m; ++l)
    dfsph_factor_finish(i0 + l, s[0][l], s[1][l], s[2][l], s[3][l], s[4][l], s[5][l], s[6][l], s[7][l],
                        s[8][l], P, rho, alpha, wgx, wgy, wgz, vax, vay, vaz, q, wall, bulk, bad, tag);
}

// Rate of rho_hat of the velocities (ux, uy, uz): rs = sum g (u_i - u_j).r_ij.
#define DFSPH_RATE_BODY(T, S)                                                             \
  const T gf = ff_cubic_grad_factor##S(sqrt(dx * dx + dy * dy + dz * dz), P.inv_h, P.kg); \
  rs += gf * ((uxi - ux[j]) * dx + (uyi - uy[j]) * dy + (uzi - uz[j]) * dz);

#define DFSPH_RATE_ARGS                                                                                      \
  __global const float *x, __global const float *y, __global const float *z, uint n,                         \
      __global const uint *start, float4 geo, int4 dims, FfDfsphArgs P, __global const float *ux,            \
      __global const float *uy, __global const float *uz, __global const float *wgx,                         \
      __global const float *wgy, __global const float *wgz, __global float *rate, __global const int *state, \
      int gated

inline void dfsph_rate_finish(uint i, float rs, float vol, __global const float* ux, __global const float* uy,
                              __global const float* uz, __global const float* wgx, __global const float* wgy,
                              __global const float* wgz, __global float* rate) {
  const float u[3] = {ux[i], uy[i], uz[i]}, wg[3] = {wgx[i], wgy[i], wgz[i]};
  rate[i] = ff_dfsph_rate(rs, vol, u, wg);
}

__kernel void dfsph_rate(DFSPH_RATE_ARGS) {
  const uint i = get_global_id(0);
  if (i >= n || (gated && state[0])) return;
  const float xi = x[i], yi = y[i], zi = z[i], uxi = ux[i], uyi = uy[i], uzi = uz[i];
  float rs = 0.0f;
  DFSPH_WALK_ONE(DFSPH_RATE_BODY(float, ))
  dfsph_rate_finish(i, rs, P.vol, ux, uy, uz, wgx, wgy, wgz, rate);
}

// ux, uy, uz hold a multiple of 8 floats.
__kernel void dfsph_rate_lanes(DFSPH_RATE_ARGS) {
  if (gated && state[0]) return;
  DFSPH_LANES_BEGIN
  const float8 uxi = ff_load_lanes(ux, i0, valid, 0.0f), uyi = ff_load_lanes(uy, i0, valid, 0.0f),
               uzi = ff_load_lanes(uz, i0, valid, 0.0f);
  float8 rs = (float8)(0.0f);
  DFSPH_WALK_LANES(DFSPH_RATE_BODY(float8, _8))
  float s[8];
  vstore8(rs, 0, s);
  for (uint l = 0; l < m; ++l) dfsph_rate_finish(i0 + l, s[l], P.vol, ux, uy, uz, wgx, wgy, wgz, rate);
}

// Velocity change of k: ks = sum g (k_i + k_j) r_ij.
#define DFSPH_KAPPA_BODY(T, S)                                                                         \
  const T c = ff_cubic_grad_factor##S(sqrt(dx * dx + dy * dy + dz * dz), P.inv_h, P.kg) * (ki + k[j]); \
  kx += c * dx, ky += c * dy, kz += c * dz;

#define DFSPH_KAPPA_ARGS                                                                                    \
  __global const float *x, __global const float *y, __global const float *z, uint n,                        \
      __global const uint *start, float4 geo, int4 dims, FfDfsphArgs P, __global const float *k,            \
      __global const float *wgx, __global const float *wgy, __global const float *wgz, __global float *dux, \
      __global float *duy, __global float *duz, __global const int *state, int gated

inline void dfsph_kappa_finish(uint i, float kx, float ky, float kz, float ki, float vol,
                               __global const float* wgx, __global const float* wgy,
                               __global const float* wgz, __global float* dux, __global float* duy,
                               __global float* duz) {
  const float sum[3] = {kx, ky, kz}, wg[3] = {wgx[i], wgy[i], wgz[i]};
  float du[3];
  ff_dfsph_velocity_change(sum, ki, vol, wg, du);
  dux[i] = du[0], duy[i] = du[1], duz[i] = du[2];
}

__kernel void dfsph_kappa(DFSPH_KAPPA_ARGS) {
  const uint i = get_global_id(0);
  if (i >= n || (gated && state[0])) return;
  const float xi = x[i], yi = y[i], zi = z[i], ki = k[i];
  float kx = 0.0f, ky = 0.0f, kz = 0.0f;
  DFSPH_WALK_ONE(DFSPH_KAPPA_BODY(float, ))
  dfsph_kappa_finish(i, kx, ky, kz, ki, P.vol, wgx, wgy, wgz, dux, duy, duz);
}

// k holds a multiple of 8 floats.
__kernel void dfsph_kappa_lanes(DFSPH_KAPPA_ARGS) {
  if (gated && state[0]) return;
  DFSPH_LANES_BEGIN
  const float8 ki = ff_load_lanes(k, i0, valid, 0.0f);
  const float8 zero = (float8)(0.0f);
  float8 kx = zero, ky = zero, kz = zero;
  DFSPH_WALK_LANES(DFSPH_KAPPA_BODY(float8, _8))
  float s[4][8];
  vstore8(kx, 0, s[0]), vstore8(ky, 0, s[1]), vstore8(kz, 0, s[2]), vstore8(ki, 0, s[3]);
  for (uint l = 0; l < m; ++l)
    dfsph_kappa_finish(i0 + l, s[0][l], s[1][l], s[2][l], s[3][l], P.vol, wgx, wgy, wgz, dux, duy, duz);
}
