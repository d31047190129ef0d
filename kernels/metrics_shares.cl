// metrics_shares.cl - phase "metrics": where the fluid lies relative to the
// target and to the control particles, as per-work-group counts that the host
// adds up (src/metrics/fluid_shares.cpp does the same on the CPU):
// (controlled, captured, stray, far) per group.
#pragma OPENCL FP_CONTRACT OFF
#include "ff_metrics.h"

// Fluid particle i (position x, y, z, identity id) at the target's frame
// (rotation columns rot0..rot2, x_world = R (x_rest - rest_c) + frame_c) in the
// target grid tdims (nx, ny, nz, pad) at torigin (origin xyz, voxel):
// - far: outside the padded grid (every particle counts);
// - controlled: controlled[id] != 0, or every particle when use_mask is 0;
// - captured: controlled and in a voxel inside the target;
// - stray: controlled and reached[i] == 0 (no control particle within the
//   control radius in the last control-forces phase).
__kernel void metrics_shares(__global const float* x, __global const float* y, __global const float* z,
                             __global const uint* id, uint n, __global const uchar* controlled, int use_mask,
                             __global const uchar* reached, __global const uchar* inside,
                             int4 tdims /* nx, ny, nz, pad */, float4 torigin /* origin xyz, voxel */,
                             float4 rot0, float4 rot1, float4 rot2, float4 frame_c, float4 rest_c,
                             __global uint* partial, __local uint* tmp) {
  ff_mat3 r;
  r.c0 = rot0.xyz, r.c1 = rot1.xyz, r.c2 = rot2.xyz;
  uint ctrl = 0, captured = 0, stray = 0, far = 0;
  for (uint i = get_global_id(0); i < n; i += get_global_size(0)) {
    const ff_voxel v =
        ff_target_voxel_of(r, frame_c.xyz, rest_c.xyz, torigin.xyz, torigin.w, FF_F3(x[i], y[i], z[i]));
    far += ff_voxel_in_padded(v, tdims.x, tdims.y, tdims.z, tdims.w) ? 0u : 1u;
    if (use_mask && !controlled[id[i]]) continue;
    ++ctrl;
    const int k = ff_voxel_index(v, tdims.x, tdims.y, tdims.z);
    captured += (k >= 0 && inside[k]) ? 1u : 0u;
    stray += reached[i] ? 0u : 1u;
  }
  const uint lid = get_local_id(0);
  tmp[4 * lid] = ctrl, tmp[4 * lid + 1] = captured, tmp[4 * lid + 2] = stray, tmp[4 * lid + 3] = far;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint s = get_local_size(0) / 2; s > 0; s >>= 1) {
    if (lid < s)
      for (int c = 0; c < 4; ++c) tmp[4 * lid + c] += tmp[4 * (lid + s) + c];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0)
    for (int c = 0; c < 4; ++c) partial[4 * get_group_id(0) + c] = tmp[c];
}
