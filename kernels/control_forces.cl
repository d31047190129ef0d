// control_forces.cl - phase "control forces": on every fluid particle the
// attraction of eq. 4, the velocity force of eq. 6 integrated implicitly, and
// the share of gravity the control carries. Control particles are found
// through their own grid (cell size = the control radius), gathered into cell
// order first. Mirrors Controller::addForces in src/control/controller.cpp.
// Two kernels with the same sums, as density.cl: `control_forces` (one fluid
// particle per work-item: for GPUs) and `control_forces_lanes` (8 per
// work-item as float8 lanes, ff_lanes.h: for CPU devices).
#pragma OPENCL FP_CONTRACT OFF
#include "ff_check.h"
#include "ff_control.h"
#include "ff_control_pull.h"
#include "ff_grid.h"
#include "ff_lanes.h"
#include "ff_recapture_field.h"
#include "ff_sph.h"

// Control particles (position, s, velocity) copied into their grid's order.
__kernel void control_gather(__global const uint* order, uint nc, __global const float* x,
                             __global const float* y, __global const float* z, __global const float* s,
                             __global const float* vx, __global const float* vy, __global const float* vz,
                             __global float* sx, __global float* sy, __global float* sz, __global float* ss,
                             __global float* svx, __global float* svy, __global float* svz) {
  const uint k = get_global_id(0);
  if (k >= nc) return;
  const uint i = order[k];
  sx[k] = x[i], sy[k] = y[i], sz[k] = z[i], ss[k] = s[i];
  svx[k] = vx[i], svy[k] = vy[i], svz[k] = vz[i];
}

// The recapture's centre (out[0..2]), fade (out[3]), whether it aims at
// the centre (out[4]: 1 where the centre lies within `spacing` of a control
// particle, ff_recapture_among; else 0 and the field of targets), whether it
// acts (out[5]: `enabled`, however full the shape reads) and whether its field
// seeds from every control particle (out[6]: none is unfilled,
// ff_recapture_seed_any), from the control particles' positions and s in
// their fixed order: one work-item, as Controller::addForces sums them.
// enabled: params.control.recapture > 0.
// sx, sy, sz, start: the control particles in their grid's order, and the grid.
__kernel void control_recapture_centre(__global const float* x, __global const float* y,
                                       __global const float* z, __global const float* s, uint nc, int enabled,
                                       __global const float* sx, __global const float* sy,
                                       __global const float* sz, __global const uint* start, float4 geo,
                                       int4 dims, float cell, float spacing, __global float* out) {
  if (get_global_id(0) != 0) return;
  float ucx = 0.0f, ucy = 0.0f, ucz = 0.0f, cw = 0.0f, uw = 0.0f;
  for (uint i = 0; i < nc; ++i) {
    const float w = ff_recapture_centre_weight(s[i]);
    ucx += w * x[i], ucy += w * y[i], ucz += w * z[i], cw += w;
    uw += ff_recapture_weight(s[i]);
  }
  const float c[3] = {ucx / cw, ucy / cw, ucz / cw};
  const float fade = enabled ? ff_recapture_fade(uw, (float)nc) : 0.0f;
  const float o3[3] = {geo.x, geo.y, geo.z};
  const int n3[3] = {dims.x, dims.y, dims.z};
  out[0] = c[0], out[1] = c[1], out[2] = c[2], out[3] = fade;
  out[4] = enabled && ff_recapture_among(start, sx, sy, sz, c[0], c[1], c[2], spacing, o3, cell, geo.w, n3)
               ? 1.0f
               : 0.0f;
  out[5] = enabled ? 1.0f : 0.0f;
  out[6] = ff_recapture_seed_any(uw) ? 1.0f : 0.0f;
}

// The accelerations of fluid particle e from its sums over the control
// particles: attraction fa, weight wsum and weighted velocity vs*
// (ff_control_fluid_accel, with the recapture's); reached[e]: whether a
// control particle was within the radius (wsum > 0). The recapture reads its
// centre, fade and aim (rcentre, from control_recapture_centre), its field of
// targets (seeds over the control particles sx, sy, sz: recapture_field.cl)
// and the controlled fluid by identity (all of it when P.use_mask is 0).
inline void control_forces_finish(uint e, ff_float3 fa, float wsum, float vsx, float vsy, float vsz,
                                  __global const float* x, __global const float* y, __global const float* z,
                                  __global const float* vx, __global const float* vy,
                                  __global const float* vz, __global const float* rho, FfControlArgs P,
                                  __global const float* rcentre, __global const uint* seeds,
                                  __global const float* sx, __global const float* sy,
                                  __global const float* sz, __global const uint* id,
                                  __global const uchar* controlled, __global float* ax, __global float* ay,
                                  __global float* az, __global uchar* reached, __global int* bad) {
  reached[e] = wsum > 0.0f ? 1 : 0;
  FfRecaptureNow R;
  R.centre[0] = rcentre[0], R.centre[1] = rcentre[1], R.centre[2] = rcentre[2], R.fade = rcentre[3];
  R.at_centre = rcentre[4] != 0.0f ? 1 : 0;
  const int recaptured = rcentre[5] != 0.0f && (!P.use_mask || controlled[id[e]]) ? 1 : 0;
  int changed = 0;
  const ff_float3 a = ff_control_fluid_accel(P, R, FF_F3(ax[e], ay[e], az[e]), fa, wsum, FF_F3(vsx, vsy, vsz),
                                             FF_F3(x[e], y[e], z[e]), FF_F3(vx[e], vy[e], vz[e]),
                                             P.pull_mode == FF_PULL_PER_DENSITY ? rho[e] : 1.0f, recaptured,
                                             seeds, sx, sy, sz, &changed);
  if (!changed) return;
  ax[e] = a.x, ay[e] = a.y, az[e] = a.z;
  if (!isfinite(a.x) || !isfinite(a.y) || !isfinite(a.z)) ff_report_nonfinite(bad, P.tag);
}

// The scalars travel in P (FfControlArgs, ff_control_pull.h).
// The control grid (cells of P.cell = radius / FF_CONTROL_GRID_DIVISIONS) is
// read in its rows within reach of P.radius, ascending: the order of
// Controller::addForces. Every control particle weighs with the poly6 kernel
// of the control radius (adaptive control's own radii act in eq. 5 only,
// control_scale.cl; docs/CONTROL_UNITS.md, "Thin features").
__kernel void control_forces(__global const float* x, __global const float* y, __global const float* z,
                             __global const float* vx, __global const float* vy, __global const float* vz,
                             __global const float* rho, uint n, __global const float* sx,
                             __global const float* sy, __global const float* sz, __global const float* ss,
                             __global const float* svx, __global const float* svy, __global const float* svz,
                             __global const uint* start, float4 geo, int4 dims, FfControlArgs P,
                             __global const float* rcentre, __global const uint* seeds,
                             __global const uint* id, __global const uchar* controlled, __global float* ax,
                             __global float* ay, __global float* az, __global uchar* reached,
                             __global int* bad) {
  const uint e = get_global_id(0);
  if (e >= n) return;
  const float xe = x[e], ye = y[e], ze = z[e];
  const float reach = ff_query_reach(P.radius, P.cell);
  const int z0 = ff_cell_coord(ze - reach, geo.z, geo.w, dims.z),
            z1 = ff_cell_coord(ze + reach, geo.z, geo.w, dims.z);
  const int y0 = ff_cell_coord(ye - reach, geo.y, geo.w, dims.y),
            y1 = ff_cell_coord(ye + reach, geo.y, geo.w, dims.y);
  ff_float3 fa = FF_F3(0.0f, 0.0f, 0.0f);
  float wsum = 0.0f, vsx = 0.0f, vsy = 0.0f, vsz = 0.0f;
  const float p3[3] = {xe, ye, ze}, o3[3] = {geo.x, geo.y, geo.z};
  const int n3[3] = {dims.x, dims.y, dims.z};
  for (int cz = z0; cz <= z1; ++cz) {
    for (int cy = y0; cy <= y1; ++cy) {
      uint b, en;
      if (!ff_row_span(start, p3, p3, reach, cy, cz, o3, P.cell, geo.w, n3, &b, &en)) continue;
      for (uint k = b; k < en; ++k) {
        const ff_float3 d = FF_F3(sx[k] - xe, sy[k] - ye, sz[k] - ze);
        const float d2 = FF_DOT(d, d);
        const float w = ff_poly6(d2, P.r2, P.coef);
        if (w <= 0.0f) continue;
        fa += ff_attraction_term(d, FF_SQRT(d2), ss[k], w);
        wsum += w;
        vsx += w * svx[k], vsy += w * svy[k], vsz += w * svz[k];
      }
    }
  }
  control_forces_finish(e, fa, wsum, vsx, vsy, vsz, x, y, z, vx, vy, vz, rho, P, rcentre, seeds, sx, sy, sz,
                        id, controlled, ax, ay, az, reached, bad);
}

// The same sums, 8 fluid particles per work-item (the fluid buffers hold a multiple of 8 floats).
__kernel void control_forces_lanes(
    __global const float* x, __global const float* y, __global const float* z, __global const float* vx,
    __global const float* vy, __global const float* vz, __global const float* rho, uint n,
    __global const float* sx, __global const float* sy, __global const float* sz, __global const float* ss,
    __global const float* svx, __global const float* svy, __global const float* svz,
    __global const uint* start, float4 geo, int4 dims, FfControlArgs P, __global const float* rcentre,
    __global const uint* seeds, __global const uint* id, __global const uchar* controlled, __global float* ax,
    __global float* ay, __global float* az, __global uchar* reached, __global int* bad) {
  const uint i0 = 8u * get_global_id(0);
  if (i0 >= n) return;
  const int8 valid = ff_lane_valid(i0, n);
  const float8 xe = ff_load_lanes(x, i0, valid, FF_LANE_FAR), ye = ff_load_lanes(y, i0, valid, FF_LANE_FAR),
               ze = ff_load_lanes(z, i0, valid, FF_LANE_FAR);
  const float reach = ff_query_reach(P.radius, P.cell);
  const FfLanesRows q = ff_lanes_rows(xe, ye, ze, valid, geo, dims, reach);
  const float8 zero = (float8)(0.0f);
  float8 fax = zero, fay = zero, faz = zero, wsum = zero, vsx = zero, vsy = zero, vsz = zero;
  for (int cz = q.z0; cz <= q.z1; ++cz)
    for (int cy = q.y0; cy <= q.y1; ++cy) {
      uint b, en;
      if (!ff_row_span(start, q.lo, q.hi, reach, cy, cz, q.o, P.cell, geo.w, q.nn, &b, &en)) continue;
      for (uint k = b; k < en; ++k) {
        const float8 dx = sx[k] - xe, dy = sy[k] - ye, dz = sz[k] - ze;
        const float8 d2 = dx * dx + dy * dy + dz * dz;
        if (!any(d2 < P.r2)) continue;  // no lane in reach: every term is 0
        const float8 w = ff_poly6_8(d2, P.r2, P.coef);
        const float8 a = ff_attraction_factor_8(sqrt(d2), ss[k], w);
        fax += dx * a, fay += dy * a, faz += dz * a;
        wsum += w;
        vsx += w * svx[k], vsy += w * svy[k], vsz += w * svz[k];
      }
    }
  float s[7][8];
  vstore8(fax, 0, s[0]), vstore8(fay, 0, s[1]), vstore8(faz, 0, s[2]), vstore8(wsum, 0, s[3]);
  vstore8(vsx, 0, s[4]), vstore8(vsy, 0, s[5]), vstore8(vsz, 0, s[6]);
  const uint m = n - i0 < 8u ? n - i0 : 8u;
  for (uint l = 0; l < m; ++l)
    control_forces_finish(i0 + l, FF_F3(s[0][l], s[1][l], s[2][l]), s[3][l], s[4][l], s[5][l], s[6][l], x, y,
                          z, vx, vy, vz, rho, P, rcentre, seeds, sx, sy, sz, id, controlled, ax, ay, az,
                          reached, bad);
}
