// metrics.cl - phase "metrics": per work-group partial reductions that the
// host finishes in double precision (fixed group counts, so the result is the
// same on every run): density error, kinetic energy, max speed, coverage, the
// control particles' best rigid fit (centre, then A_pq), and the voxel iou
// against the padded target grid at that frame (src/metrics/iou.cpp).
// Local sizes must be powers of two; groups stride over the input.
#pragma OPENCL FP_CONTRACT OFF
#include "ff_grid.h"
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

// (sum |rho - rho0| / rho0, sum |v|^2, max |v|^2, max rho) per group.
__kernel void metrics_fluid(__global const float* rho, __global const float* vx, __global const float* vy,
                            __global const float* vz, uint n, float rho0, __global float* partial,
                            __local float* tmp) {
  float derr = 0.0f, v2sum = 0.0f, v2max = 0.0f, rho_max = 0.0f;
  for (uint i = get_global_id(0); i < n; i += get_global_size(0)) {
    derr += fabs(rho[i] - rho0) / rho0;
    rho_max = fmax(rho_max, rho[i]);
    const float v2 = vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i];
    v2sum += v2;
    v2max = fmax(v2max, v2);
  }
  const uint lid = get_local_id(0);
  tmp[4 * lid + 0] = derr, tmp[4 * lid + 1] = v2sum, tmp[4 * lid + 2] = v2max, tmp[4 * lid + 3] = rho_max;
  ff_group_reduce(tmp, 4, (1 << 2) | (1 << 3), partial);
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
  uint inter = 0, uni = 0;
  for (uint v = get_global_id(0); v < total; v += get_global_size(0)) {
    const int i = (int)(v % (uint)nx) - pad, j = (int)((v / (uint)nx) % (uint)ny) - pad,
              k = (int)(v / ((uint)nx * (uint)ny)) - pad;
    const int in_target = i >= 0 && j >= 0 && k >= 0 && i < tdims.x && j < tdims.y && k < tdims.z &&
                          inside[(uint)i + (uint)tdims.x * ((uint)j + (uint)tdims.y * (uint)k)];
    const float cx = torigin.x + torigin.w * ((float)i + 0.5f),
                cy = torigin.y + torigin.w * ((float)j + 0.5f),
                cz = torigin.z + torigin.w * ((float)k + 0.5f);
    const ff_float3 w = ff_mat3_mul_vec(r, FF_F3(cx - rest_c.x, cy - rest_c.y, cz - rest_c.z)) +
                        FF_F3(frame_c.x, frame_c.y, frame_c.z);
    uint b[9], e[9];
    ff_grid_ranges(start, ff_cell_coord(w.x, geo.x, geo.w, dims.x), ff_cell_coord(w.y, geo.y, geo.w, dims.y),
                   ff_cell_coord(w.z, geo.z, geo.w, dims.z), dims.x, dims.y, dims.z, b, e);
    float sum = 0.0f;
    for (int rr = 0; rr < 9; ++rr)
      for (uint kk = b[rr]; kk < e[rr]; ++kk) {
        const uint p = order[kk];
        const float dx = w.x - x[p], dy = w.y - y[p], dz = w.z - z[p];
        sum += ff_poly6(dx * dx + dy * dy + dz * dz, h2, coef);
      }
    const int in_fluid = mass * sum >= threshold;
    inter += (in_target && in_fluid) ? 1u : 0u;
    uni += (in_target || in_fluid) ? 1u : 0u;
  }
  const uint lid = get_local_id(0);
  tmp[2 * lid] = inter, tmp[2 * lid + 1] = uni;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint s = get_local_size(0) / 2; s > 0; s >>= 1) {
    if (lid < s) tmp[2 * lid] += tmp[2 * (lid + s)], tmp[2 * lid + 1] += tmp[2 * (lid + s) + 1];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0) partial[2 * get_group_id(0)] = tmp[0], partial[2 * get_group_id(0) + 1] = tmp[1];
}
