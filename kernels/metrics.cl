// metrics.cl - phase "metrics": per work-group partial reductions that the
// host finishes in double precision (fixed group counts, so the result is the
// same on every run): density error, kinetic energy, max speed, coverage, the
// control particles' best rigid fit (centre, then A_pq), and the voxel iou
// against the padded target grid at that frame (src/metrics/iou.cpp).
// Local sizes must be powers of two; groups stride over the input.
#pragma OPENCL FP_CONTRACT OFF
#include "ff_grid.h"
#include "ff_integrate.h"
#include "ff_lanes.h"
#include "ff_rotation.h"
#include "ff_sph.h"

// Tree reduction of `width` values per work-item in tmp[width * lid + k]: the
// group's result lands in out[width * group + k]; column k is summed, or
// maximised where bit k of max_mask is set.
void ff_group_reduce(__local float* tmp, int width, int max_mask, __global float* out) {
  const uint lid = get_local_id(0);
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint s = get_local_size(0) / 2; s > 0; s >>= 1) {
    if (lid < s)
      for (int k = 0; k < width; ++k) {
        const float a = tmp[width * lid + k], b = tmp[width * (lid + s) + k];
        tmp[width * lid + k] = ((max_mask >> k) & 1) ? fmax(a, b) : a + b;
      }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0)
    for (int k = 0; k < width; ++k) out[width * get_group_id(0) + k] = tmp[k];
}

// (sum |rho - rho0| / rho0, sum |v|^2, max |v|^2, max rho,
//  sum max(rho - rho0, 0) / rho0, max p) per group.
__kernel void metrics_fluid(__global const float* rho, __global const float* p, __global const float* vx,
                            __global const float* vy, __global const float* vz, uint n, float rho0,
                            __global float* partial, __local float* tmp) {
  float derr = 0.0f, v2sum = 0.0f, v2max = 0.0f, rho_max = 0.0f, comp = 0.0f, p_max = 0.0f;
  for (uint i = get_global_id(0); i < n; i += get_global_size(0)) {
    derr += fabs(rho[i] - rho0) / rho0;
    comp += fmax(rho[i] - rho0, 0.0f) / rho0;
    rho_max = fmax(rho_max, rho[i]);
    p_max = fmax(p_max, p[i]);
    const float v2 = ff_speed2(vx[i], vy[i], vz[i]);
    v2sum += v2;
    v2max = fmax(v2max, v2);
  }
  const uint lid = get_local_id(0);
  tmp[6 * lid + 0] = derr, tmp[6 * lid + 1] = v2sum, tmp[6 * lid + 2] = v2max, tmp[6 * lid + 3] = rho_max;
  tmp[6 * lid + 4] = comp, tmp[6 * lid + 5] = p_max;
  ff_group_reduce(tmp, 6, (1 << 2) | (1 << 3) | (1 << 5), partial);
}

// sum (1 - s_i) per group.
__kernel void metrics_coverage(__global const float* s, uint n, __global float* partial, __local float* tmp) {
  float sum = 0.0f;
  for (uint i = get_global_id(0); i < n; i += get_global_size(0)) sum += 1.0f - s[i];
  tmp[get_local_id(0)] = sum;
  ff_group_reduce(tmp, 1, 0, partial);
}

// sum of the control positions per group (for the centre of mass).
__kernel void metrics_com(__global const float* x, __global const float* y, __global const float* z, uint n,
                          __global float* partial, __local float* tmp) {
  float sx = 0.0f, sy = 0.0f, sz = 0.0f;
  for (uint i = get_global_id(0); i < n; i += get_global_size(0)) sx += x[i], sy += y[i], sz += z[i];
  const uint lid = get_local_id(0);
  tmp[3 * lid + 0] = sx, tmp[3 * lid + 1] = sy, tmp[3 * lid + 2] = sz;
  ff_group_reduce(tmp, 3, 0, partial);
}

// A_pq = sum (x - com) (x0 - rest_c)^T per group, as 3 columns of 3.
__kernel void metrics_apq(__global const float* x, __global const float* y, __global const float* z,
                          __global const float* x0, __global const float* y0, __global const float* z0,
                          uint n, float4 com, float4 rest_c, __global float* partial, __local float* tmp) {
  ff_mat3 apq = ff_mat3_zero();
  for (uint i = get_global_id(0); i < n; i += get_global_size(0))
    apq = ff_mat3_add_outer(apq, FF_F3(x[i], y[i], z[i]) - com.xyz, FF_F3(x0[i], y0[i], z0[i]) - rest_c.xyz);
  const uint lid = get_local_id(0);
  tmp[9 * lid + 0] = apq.c0.x, tmp[9 * lid + 1] = apq.c0.y, tmp[9 * lid + 2] = apq.c0.z;
  tmp[9 * lid + 3] = apq.c1.x, tmp[9 * lid + 4] = apq.c1.y, tmp[9 * lid + 5] = apq.c1.z;
  tmp[9 * lid + 6] = apq.c2.x, tmp[9 * lid + 7] = apq.c2.y, tmp[9 * lid + 8] = apq.c2.z;
  ff_group_reduce(tmp, 9, 0, partial);
}

// Voxel iou: (|target & fluid|, |target | fluid|) per group. Voxel v of the
// target grid padded by tdims.w voxels is placed in the world by the rotation
// (columns rot0..rot2), x_world = R (centre - rest_c) + frame_c. The fluid
// (any order) is found through an index grid with cell size >= h.
// Target voxel (i, j, k)'s class: 0 outside (and outside the unpadded grid),
// bit 1 inside the target, bit 2 a thin voxel (filled_thin).
inline int ff_voxel_in_target(__global const uchar* inside, int4 tdims, int i, int j, int k) {
  return (i >= 0 && j >= 0 && k >= 0 && i < tdims.x && j < tdims.y && k < tdims.z)
             ? (int)inside[(uint)i + (uint)tdims.x * ((uint)j + (uint)tdims.y * (uint)k)]
             : 0;
}

// World position of the centre of voxel (i, j, k).
inline ff_float3 ff_voxel_world(float4 torigin, ff_mat3 r, float4 frame_c, float4 rest_c, int i, int j,
                                int k) {
  const float cx = torigin.x + torigin.w * ((float)i + 0.5f), cy = torigin.y + torigin.w * ((float)j + 0.5f),
              cz = torigin.z + torigin.w * ((float)k + 0.5f);
  return ff_mat3_mul_vec(r, FF_F3(cx - rest_c.x, cy - rest_c.y, cz - rest_c.z)) +
         FF_F3(frame_c.x, frame_c.y, frame_c.z);
}

// Sums the work-group's (intersection, union, thin intersection) voxel counts
// into partial[3 g .. 3 g + 2].
void reduce_iou_counts(uint inter, uint uni, uint inter_thin, __global uint* partial, __local uint* tmp) {
  const uint lid = get_local_id(0);
  tmp[3 * lid] = inter, tmp[3 * lid + 1] = uni, tmp[3 * lid + 2] = inter_thin;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint s = get_local_size(0) / 2; s > 0; s >>= 1) {
    if (lid < s)
      for (int c = 0; c < 3; ++c) tmp[3 * lid + c] += tmp[3 * (lid + s) + c];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0)
    for (int c = 0; c < 3; ++c) partial[3 * get_group_id(0) + c] = tmp[c];
}

__kernel void metrics_iou(__global const uchar* inside, int4 tdims /* nx, ny, nz, pad */,
                          float4 torigin /* origin xyz, voxel */, float4 rot0, float4 rot1, float4 rot2,
                          float4 frame_c, float4 rest_c, __global const float* x, __global const float* y,
                          __global const float* z, __global const uint* order, __global const uint* start,
                          float4 geo, int4 dims, float h, float mass, float threshold, __global uint* partial,
                          __local uint* tmp) {
  const int pad = tdims.w, nx = tdims.x + 2 * pad, ny = tdims.y + 2 * pad, nz = tdims.z + 2 * pad;
  const uint total = (uint)nx * (uint)ny * (uint)nz;
  const float h2 = h * h, coef = ff_poly6_coef(h);
  ff_mat3 r;
  r.c0 = rot0.xyz, r.c1 = rot1.xyz, r.c2 = rot2.xyz;
  uint inter = 0, uni = 0, inter_thin = 0;
  for (uint v = get_global_id(0); v < total; v += get_global_size(0)) {
    const int i = (int)(v % (uint)nx) - pad, j = (int)((v / (uint)nx) % (uint)ny) - pad,
              k = (int)(v / ((uint)nx * (uint)ny)) - pad;
    const int in_target = ff_voxel_in_target(inside, tdims, i, j, k);
    const ff_float3 w = ff_voxel_world(torigin, r, frame_c, rest_c, i, j, k);
    uint b[9], e[9];
    ff_grid_ranges(start, ff_cell_coord(w.x, geo.x, geo.w, dims.x), ff_cell_coord(w.y, geo.y, geo.w, dims.y),
                   ff_cell_coord(w.z, geo.z, geo.w, dims.z), dims.x, dims.y, dims.z, b, e);
    // The sum only grows: once it reaches the threshold the rest cannot change
    // the answer (as src/metrics/iou.cpp).
    float sum = 0.0f;
    for (int rr = 0; rr < 9 && !(mass * sum >= threshold); ++rr)
      for (uint kk = b[rr]; kk < e[rr]; ++kk) {
        const uint p = order[kk];
        const float dx = w.x - x[p], dy = w.y - y[p], dz = w.z - z[p];
        sum += ff_poly6(dx * dx + dy * dy + dz * dz, h2, coef);
      }
    const int in_fluid = mass * sum >= threshold;
    inter += (in_target && in_fluid) ? 1u : 0u;
    inter_thin += ((in_target & 2) && in_fluid) ? 1u : 0u;
    uni += (in_target || in_fluid) ? 1u : 0u;
  }
  reduce_iou_counts(inter, uni, inter_thin, partial, tmp);
}

// The same counts for CPU devices: runs of 8 voxels along x as float8 lanes,
// the fluid within h of their bounding box walked in ascending sorted order
// (ff_lanes.h: each lane's sum is metrics_iou's bit for bit), until every
// lane has reached the threshold. cell: the index grid's cell size.
__kernel void metrics_iou_lanes(__global const uchar* inside, int4 tdims /* nx, ny, nz, pad */,
                                float4 torigin /* origin xyz, voxel */, float4 rot0, float4 rot1, float4 rot2,
                                float4 frame_c, float4 rest_c, __global const float* x,
                                __global const float* y, __global const float* z, __global const uint* order,
                                __global const uint* start, float4 geo, int4 dims, float cell, float h,
                                float mass, float threshold, __global uint* partial, __local uint* tmp) {
  const int pad = tdims.w, nx = tdims.x + 2 * pad, ny = tdims.y + 2 * pad, nz = tdims.z + 2 * pad;
  const int runs = (nx + 7) / 8;
  const uint total = (uint)runs * (uint)ny * (uint)nz;
  const float h2 = h * h, coef = ff_poly6_coef(h), reach = ff_query_reach(h, cell);
  const float o[3] = {geo.x, geo.y, geo.z};
  const int nn[3] = {dims.x, dims.y, dims.z};
  ff_mat3 r;
  r.c0 = rot0.xyz, r.c1 = rot1.xyz, r.c2 = rot2.xyz;
  uint inter = 0, uni = 0, inter_thin = 0;
  for (uint v = get_global_id(0); v < total; v += get_global_size(0)) {
    const int i0 = (int)(v % (uint)runs) * 8, j = (int)((v / (uint)runs) % (uint)ny) - pad,
              k = (int)(v / ((uint)runs * (uint)ny)) - pad;
    const int n = nx - i0 < 8 ? nx - i0 : 8;
    float wx[8], wy[8], wz[8];
    int in_target[8];
    for (int l = 0; l < 8; ++l) {
      const ff_float3 w = ff_voxel_world(torigin, r, frame_c, rest_c, i0 + l - pad, j, k);
      in_target[l] = l >= n ? 0 : ff_voxel_in_target(inside, tdims, i0 + l - pad, j, k);
      wx[l] = l < n ? w.x : FF_LANE_FAR, wy[l] = l < n ? w.y : FF_LANE_FAR, wz[l] = l < n ? w.z : FF_LANE_FAR;
    }
    const int8 valid = (int8)(0, 1, 2, 3, 4, 5, 6, 7) < n;
    const float8 cx = vload8(0, wx), cy = vload8(0, wy), cz = vload8(0, wz);
    const float lo[3] = {ff_lanes_min(cx, valid), ff_lanes_min(cy, valid), ff_lanes_min(cz, valid)};
    const float hi[3] = {ff_lanes_max(cx, valid), ff_lanes_max(cy, valid), ff_lanes_max(cz, valid)};
    const int z0 = ff_cell_coord(lo[2] - reach, o[2], geo.w, nn[2]),
              z1 = ff_cell_coord(hi[2] + reach, o[2], geo.w, nn[2]);
    const int y0 = ff_cell_coord(lo[1] - reach, o[1], geo.w, nn[1]),
              y1 = ff_cell_coord(hi[1] + reach, o[1], geo.w, nn[1]);
    float8 sum = (float8)(0.0f);
    // The sums only grow: once every lane has reached the threshold the rest cannot change the answer.
    int8 filled = (mass * sum >= threshold) | ~valid;
    for (int cz0 = z0; cz0 <= z1 && !all(filled); ++cz0)
      for (int cy0 = y0; cy0 <= y1 && !all(filled); ++cy0) {
        uint b, e;
        if (!ff_row_span(start, lo, hi, reach, cy0, cz0, o, cell, geo.w, nn, &b, &e)) continue;
        for (uint kk = b; kk < e; ++kk) {
          const uint p = order[kk];
          const float8 dx = cx - x[p], dy = cy - y[p], dz = cz - z[p];
          sum += ff_poly6_8(dx * dx + dy * dy + dz * dz, h2, coef);
        }
        filled = (mass * sum >= threshold) | ~valid;
      }
    float sums[8];
    vstore8(sum, 0, sums);
    for (int l = 0; l < n; ++l) {
      const int in_fluid = mass * sums[l] >= threshold;
      inter += (in_target[l] && in_fluid) ? 1u : 0u;
      inter_thin += ((in_target[l] & 2) && in_fluid) ? 1u : 0u;
      uni += (in_target[l] || in_fluid) ? 1u : 0u;
    }
  }
  reduce_iou_counts(inter, uni, inter_thin, partial, tmp);
}
