// control_scale.cl - phase "control scale": the density scale s_i of every
// control particle (eq. 5) and u_bar, the kernel-weighted mean fluid velocity
// around it (for the fluid feedback). The fluid, sorted by its grid (cell h),
// is read in the grid's rows within reach of the control particle, 8
// consecutive sorted positions at a time: position k adds to lane k mod 8,
// and the lanes combine by ff_lane_sum8. Mirrors Controller::computeScale in
// src/control/controller.cpp. The fluid buffers hold a multiple of 8 floats.
// Each control particle sums within its own radius: `radius` times its scale
// rs[i] (ff_control_radius, adaptive control).
#pragma OPENCL FP_CONTRACT OFF
#include "ff_check.h"
#include "ff_control.h"
#include "ff_grid.h"
#include "ff_sph.h"

float ff_total8(float8 v) {
  return ff_lane_sum8(v.s0, v.s1, v.s2, v.s3, v.s4, v.s5, v.s6, v.s7);
}

// s_i and u_bar (ff_control_scale_of) from the lane-combined sums of W, W vx,
// W vy, W vz.
void control_scale_store(uint i, float total, float tx, float ty, float tz, FfScaleArgs A,
                         __global float* s_out, __global float* ux_out, __global float* uy_out,
                         __global float* uz_out, __global int* bad) {
  ff_float3 u;
  const float s = ff_control_scale_of(total, FF_F3(tx, ty, tz), A.volume, &u);
  s_out[i] = s;
  ux_out[i] = u.x, uy_out[i] = u.y, uz_out[i] = u.z;
  if (!isfinite(s) || !isfinite(u.x) || !isfinite(u.y) || !isfinite(u.z)) ff_report_nonfinite(bad, A.tag);
}

// The reach of control particle i's sums: its own radius (adaptive control)
// and the fluid grid's slabs within it.
typedef struct {
  float radius, r2, coef, reach;
  int y0, y1, z0, z1;
} ScaleReach;

ScaleReach control_scale_reach(float radius, float px, float py, float pz, FfScaleArgs A) {
  ScaleReach r;
  r.radius = radius;
  r.r2 = radius * radius, r.coef = ff_poly6_coef(radius);
  r.reach = ff_query_reach(radius, A.cell);
  r.z0 = ff_cell_coord(pz - r.reach, A.geo[2], A.geo[3], A.dims[2]);
  r.z1 = ff_cell_coord(pz + r.reach, A.geo[2], A.geo[3], A.dims[2]);
  r.y0 = ff_cell_coord(py - r.reach, A.geo[1], A.geo[3], A.dims[1]);
  r.y1 = ff_cell_coord(py + r.reach, A.geo[1], A.geo[3], A.dims[1]);
  return r;
}

__kernel void control_scale(__global const float* cx, __global const float* cy, __global const float* cz,
                            __global const float* rs, __global const float* fx, __global const float* fy,
                            __global const float* fz, __global const float* fvx, __global const float* fvy,
                            __global const float* fvz, __global const uint* start, FfScaleArgs A,
                            __global float* s_out, __global float* ux_out, __global float* uy_out,
                            __global float* uz_out, __global int* bad) {
  const uint i = get_global_id(0);
  if (i >= A.nc) return;
  const float px = cx[i], py = cy[i], pz = cz[i];
  const ScaleReach r = control_scale_reach(ff_control_radius(A.radius, rs[i]), px, py, pz, A);
  const int8 iota = (int8)(0, 1, 2, 3, 4, 5, 6, 7);
  float8 sum = (float8)(0.0f), ux = sum, uy = sum, uz = sum;
  const float p3[3] = {px, py, pz}, o3[3] = {A.geo[0], A.geo[1], A.geo[2]};
  for (int z = r.z0; z <= r.z1; ++z) {
    for (int y = r.y0; y <= r.y1; ++y) {
      uint b, e;
      if (!ff_row_span(start, p3, p3, r.reach, y, z, o3, A.cell, A.geo[3], A.dims, &b, &e)) continue;
      for (uint k = b & ~7u; k < e; k += 8u) {
        const float8 dx = px - vload8(0, fx + k), dy = py - vload8(0, fy + k), dz = pz - vload8(0, fz + k);
        const int8 kk = iota + (int)k;
        const int8 in = (kk >= (int)b) & (kk < (int)e);
        const float8 w = select((float8)(0.0f), ff_poly6_8(dx * dx + dy * dy + dz * dz, r.r2, r.coef), in);
        sum += w;
        ux += w * vload8(0, fvx + k), uy += w * vload8(0, fvy + k), uz += w * vload8(0, fvz + k);
      }
    }
  }
  control_scale_store(i, ff_total8(sum), ff_total8(ux), ff_total8(uy), ff_total8(uz), A, s_out, ux_out,
                      uy_out, uz_out, bad);
}

// The same sums with 8 work-items per control particle (for GPUs, where one
// work-item per control particle leaves most of the device idle): work-item
// `lane` takes the fluid positions k = lane mod 8 in ascending k, exactly the
// lane `lane` of the float8 sums above, and the group combines the 8 lanes by
// ff_lane_sum8 in local memory. Work-groups of a multiple of 8 work-items;
// `tmp` holds 4 floats per work-item.
__kernel void control_scale_by_lane(__global const float* cx, __global const float* cy,
                                    __global const float* cz, __global const float* rs,
                                    __global const float* fx, __global const float* fy,
                                    __global const float* fz, __global const float* fvx,
                                    __global const float* fvy, __global const float* fvz,
                                    __global const uint* start, FfScaleArgs A, __global float* s_out,
                                    __global float* ux_out, __global float* uy_out, __global float* uz_out,
                                    __global int* bad, __local float* tmp) {
  const uint i = get_global_id(0) / 8u, lane = get_local_id(0) & 7u, lid = get_local_id(0);
  float sum = 0.0f, ux = 0.0f, uy = 0.0f, uz = 0.0f;
  if (i < A.nc) {
    const float px = cx[i], py = cy[i], pz = cz[i];
    const ScaleReach r = control_scale_reach(ff_control_radius(A.radius, rs[i]), px, py, pz, A);
    const float p3[3] = {px, py, pz}, o3[3] = {A.geo[0], A.geo[1], A.geo[2]};
    for (int z = r.z0; z <= r.z1; ++z) {
      for (int y = r.y0; y <= r.y1; ++y) {
        uint b, e;
        if (!ff_row_span(start, p3, p3, r.reach, y, z, o3, A.cell, A.geo[3], A.dims, &b, &e)) continue;
        for (uint k = (b & ~7u) + lane; k < e; k += 8u) {
          if (k < b) continue;
          const float dx = px - fx[k], dy = py - fy[k], dz = pz - fz[k];
          const float w = ff_poly6(dx * dx + dy * dy + dz * dz, r.r2, r.coef);
          sum += w;
          ux += w * fvx[k], uy += w * fvy[k], uz += w * fvz[k];
        }
      }
    }
  }
  tmp[4u * lid] = sum, tmp[4u * lid + 1u] = ux, tmp[4u * lid + 2u] = uy, tmp[4u * lid + 3u] = uz;
  barrier(CLK_LOCAL_MEM_FENCE);
  if (lane != 0u || i >= A.nc) return;
  float t[4];
  for (int c = 0; c < 4; ++c) {
    __local const float* v = tmp + 4u * lid + (uint)c;
    t[c] = ff_lane_sum8(v[0], v[4], v[8], v[12], v[16], v[20], v[24], v[28]);
  }
  control_scale_store(i, t[0], t[1], t[2], t[3], A, s_out, ux_out, uy_out, uz_out, bad);
}
