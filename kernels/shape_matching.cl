// shape_matching.cl - phase "shape matching", one step of the shape-matching
// clock (Controller::shapeMatchStep): per cluster the centre of mass, the
// rotation (ff_extract_rotation, warm-started from the cluster's quaternion
// kept on the device) and the mean velocity, summed in the lane order of
// ff_cluster_sums.h; per control particle the goal (eq. 8), the damping and
// fluid feedback, eq. 7, the anchor (ff_anchor.h), integration and the container clamp. Mirrors
// src/control/shape_matching.cpp and controller.cpp.
#pragma OPENCL FP_CONTRACT OFF
#include "ff_anchor.h"
#include "ff_check.h"
#include "ff_cluster_sums.h"
#include "ff_control.h"
#include "ff_rotation.h"
#include "ff_shape_match.h"

// One work-item per cluster (the lanes kernels, for CPU devices): the lanes of
// the cluster sums one after another, as the OpenMP backend runs them.
__kernel void sm_cluster_frames(__global const float* x, __global const float* y, __global const float* z,
                                __global const float* vx, __global const float* vy, __global const float* vz,
                                FF_SM_REST_PARAMS, __global const uint* cl_start,
                                __global const uint* cl_members, FfShapeMatchArgs A, __global float4* q,
                                __global float* com_x, __global float* com_y, __global float* com_z,
                                __global float* cv_x, __global float* cv_y, __global float* cv_z) {
  const uint c = get_global_id(0);
  if (c >= A.nclusters) return;
  ff_quat qc = q[c];
  const ff_float3 com = ff_sm_frame(x, y, z, x0, y0, z0, bx0, by0, bz0, rest_cx, rest_cy, rest_cz, from_cx,
                                    from_cy, from_cz, cl_start, cl_members, c, A.w, A.iterations, &qc);
  q[c] = qc;
  com_x[c] = com.x, com_y[c] = com.y, com_z[c] = com.z;
  // clusterVelocities: the mean velocity of the members, before this step moves them.
  const ff_float3 cv = ff_cluster_mean3_of(vx, vy, vz, cl_members, cl_start[c], cl_start[c + 1]);
  cv_x[c] = cv.x, cv_y[c] = cv.y, cv_z[c] = cv.z;
}

// The same frames with 8 work-items per cluster (the scalar kernels, for GPUs,
// where one work-item per cluster leaves most of the device idle): work-item
// `lane` sums the members k = lane mod 8 (counted from the cluster's start),
// the group combines the 8 lanes in local memory by ff_lane_sum8, every lane
// takes the centre of mass from them, and lane 0 extracts the rotation. Work-
// groups of a multiple of 8 work-items; `tmp` holds 15 floats per work-item.
__kernel void sm_cluster_frames_by_lane(__global const float* x, __global const float* y,
                                        __global const float* z, __global const float* vx,
                                        __global const float* vy, __global const float* vz, FF_SM_REST_PARAMS,
                                        __global const uint* cl_start, __global const uint* cl_members,
                                        FfShapeMatchArgs A, __global float4* q, __global float* com_x,
                                        __global float* com_y, __global float* com_z, __global float* cv_x,
                                        __global float* cv_y, __global float* cv_z, __local float* tmp) {
  const uint c = get_global_id(0) / 8u, lane = get_local_id(0) & 7u, lid = get_local_id(0);
  const uint nc = A.nclusters;
  const float w = A.w;
  // The group's first lane of this cluster; positions sums at tmp[3 * lid],
  // A_pq and velocity sums at tmp[3 * size + 12 * lid].
  const uint l0 = lid - lane, size = get_local_size(0);
  __local float* pos = tmp;
  __local float* rest = tmp + 3u * size;
  const uint b = c < nc ? cl_start[c] : 0u, e = c < nc ? cl_start[c + 1] : 0u;
  const ff_float3 ps = ff_cluster_lane_sum3(x, y, z, cl_members, b, e, lane);
  pos[3u * lid] = ps.x, pos[3u * lid + 1u] = ps.y, pos[3u * lid + 2u] = ps.z;
  barrier(CLK_LOCAL_MEM_FENCE);
  ff_float3 lanes[8];
  for (uint l = 0; l < 8u; ++l) {
    __local const float* v = pos + 3u * (l0 + l);
    lanes[l] = FF_F3(v[0], v[1], v[2]);
  }
  const ff_float3 com = c < nc ? ff_lanes_mean3(lanes, e - b) : FF_F3(0.0f, 0.0f, 0.0f);
  const ff_float3 rc =
      c < nc ? ff_blend_rest_at(from_cx, from_cy, from_cz, rest_cx, rest_cy, rest_cz, c, w) : com;
  const ff_mat3 a =
      ff_cluster_lane_apq_blend(x, y, z, x0, y0, z0, bx0, by0, bz0, w, cl_members, b, e, lane, com, rc);
  const ff_float3 vs = ff_cluster_lane_sum3(vx, vy, vz, cl_members, b, e, lane);
  const float mine[12] = {a.c0.x, a.c0.y, a.c0.z, a.c1.x, a.c1.y, a.c1.z,
                          a.c2.x, a.c2.y, a.c2.z, vs.x,   vs.y,   vs.z};
  for (uint k = 0; k < 12u; ++k) rest[12u * lid + k] = mine[k];
  barrier(CLK_LOCAL_MEM_FENCE);
  if (lane != 0u || c >= nc) return;
  ff_mat3 m[8];
  for (uint l = 0; l < 8u; ++l) {
    __local const float* v = rest + 12u * (lid + l);
    m[l].c0 = FF_F3(v[0], v[1], v[2]), m[l].c1 = FF_F3(v[3], v[4], v[5]), m[l].c2 = FF_F3(v[6], v[7], v[8]);
    lanes[l] = FF_F3(v[9], v[10], v[11]);
  }
  q[c] = ff_extract_rotation(ff_lanes_total_mat3(m), q[c], A.iterations);
  com_x[c] = com.x, com_y[c] = com.y, com_z[c] = com.z;
  const ff_float3 cv = ff_lanes_mean3(lanes, e - b);
  cv_x[c] = cv.x, cv_y[c] = cv.y, cv_z[c] = cv.z;
}

// Goals (kept for reading back), then the velocities after damping, feedback
// and eq. 7 (Controller::shapeMatchStep's first loop).
__kernel void sm_velocities(__global const float* x, __global const float* y, __global const float* z,
                            __global float* vx, __global float* vy, __global float* vz, FF_SM_REST_PARAMS,
                            __global const uint* of_start, __global const uint* of, __global const float4* q,
                            __global const float* com_x, __global const float* com_y,
                            __global const float* com_z, __global const float* cv_x,
                            __global const float* cv_y, __global const float* cv_z, __global const float* ux,
                            __global const float* uy, __global const float* uz, FfShapeMatchArgs A,
                            __global float* gx, __global float* gy, __global float* gz) {
  const uint i = get_global_id(0);
  if (i >= A.n) return;
  const ff_float3 goal = ff_sm_goal(x0, y0, z0, bx0, by0, bz0, rest_cx, rest_cy, rest_cz, from_cx, from_cy,
                                    from_cz, of_start, of, q, com_x, com_y, com_z, i, A.w);
  gx[i] = goal.x, gy[i] = goal.y, gz[i] = goal.z;
  const ff_float3 v = ff_sm_velocity(FF_F3(vx[i], vy[i], vz[i]), FF_F3(x[i], y[i], z[i]), goal,
                                     FF_F3(ux[i], uy[i], uz[i]), of_start, of, cv_x, cv_y, cv_z, i, A);
  vx[i] = v.x, vy[i] = v.y, vz[i] = v.z;
}

// The anchor's correction (ff_anchor.h), one work-item over the whole set:
// out = dv, dw, com (9 floats); the mode and gravity's magnitude come in A.
__kernel void sm_anchor(__global const float* x, __global const float* y, __global const float* z,
                        __global const float* vx, __global const float* vy, __global const float* vz,
                        __global const float* x0, __global const float* y0, __global const float* z0,
                        float4 rest_c, float4 anchor, float4 up, FfShapeMatchArgs A, __global const float4* q,
                        __global float* out) {
  if (get_global_id(0) != 0) return;
  const ff_quat qw = A.nclusters > 0u ? q[0] : FF_Q(0.0f, 0.0f, 0.0f, 1.0f);
  const ff_anchor_fix f =
      ff_anchor_correction(x, y, z, vx, vy, vz, x0, y0, z0, A.n, FF_F3(rest_c.x, rest_c.y, rest_c.z),
                           FF_F3(anchor.x, anchor.y, anchor.z), FF_F3(up.x, up.y, up.z), A.anchor, A.g,
                           A.alpha, A.h, qw, A.iterations);
  out[0] = f.dv.x, out[1] = f.dv.y, out[2] = f.dv.z, out[3] = f.dw.x, out[4] = f.dw.y, out[5] = f.dw.z;
  out[6] = f.com.x, out[7] = f.com.y, out[8] = f.com.z;
}

// The anchor's correction (A.anchor != 0: from fix), integration and the container clamp.
__kernel void sm_integrate(__global float* x, __global float* y, __global float* z, __global float* vx,
                           __global float* vy, __global float* vz, FfShapeMatchArgs A,
                           __global const float* fix, __global int* bad) {
  const uint i = get_global_id(0);
  if (i >= A.n) return;
  ff_float3 v = FF_F3(vx[i], vy[i], vz[i]);
  const ff_float3 p = FF_F3(x[i], y[i], z[i]);
  if (A.anchor)
    v = ff_anchor_velocity(v, p, FF_F3(fix[0], fix[1], fix[2]), FF_F3(fix[3], fix[4], fix[5]),
                           FF_F3(fix[6], fix[7], fix[8]));
  int ok = 1;
  const ff_float3 np = ff_sm_move(p, &v, A, &ok);
  x[i] = np.x, y[i] = np.y, z[i] = np.z;
  vx[i] = v.x, vy[i] = v.y, vz[i] = v.z;
  if (!ok) ff_report_nonfinite(bad, A.tag);
}
