// shape_matching.cl - phase "shape matching", one step of the shape-matching
// clock (Controller::shapeMatchStep): per cluster the centre of mass, the
// rotation (ff_extract_rotation, warm-started from the cluster's quaternion
// kept on the device) and the mean velocity; per control particle the goal
// (eq. 8), the damping and fluid feedback, eq. 7, integration and the
// container clamp. Mirrors src/control/shape_matching.cpp and controller.cpp.
#pragma OPENCL FP_CONTRACT OFF
#include "ff_check.h"
#include "ff_control.h"
#include "ff_rotation.h"

__kernel void sm_cluster_frames(__global const float* x, __global const float* y, __global const float* z,
                                __global const float* vx, __global const float* vy, __global const float* vz,
                                __global const float* x0, __global const float* y0, __global const float* z0,
                                __global const uint* cl_start, __global const uint* cl_members,
                                __global const float* rest_cx, __global const float* rest_cy,
                                __global const float* rest_cz, uint nc, int iterations, __global float4* q,
                                __global float* com_x, __global float* com_y, __global float* com_z,
                                __global float* cv_x, __global float* cv_y, __global float* cv_z) {
  const uint c = get_global_id(0);
  if (c >= nc) return;
  const uint b = cl_start[c], e = cl_start[c + 1];
  float mx = 0.0f, my = 0.0f, mz = 0.0f;
  for (uint k = b; k < e; ++k) {
    const uint p = cl_members[k];
    mx += x[p], my += y[p], mz += z[p];
  }
  const float inv = 1.0f / (float)(e - b);
  const ff_float3 com = FF_F3(mx * inv, my * inv, mz * inv);
  const ff_float3 rc = FF_F3(rest_cx[c], rest_cy[c], rest_cz[c]);
  ff_mat3 apq = ff_mat3_zero();
  for (uint k = b; k < e; ++k) {
    const uint p = cl_members[k];
    const ff_float3 pp = FF_F3(x[p], y[p], z[p]) - com;
    const ff_float3 qq = FF_F3(x0[p], y0[p], z0[p]) - rc;
    apq = ff_mat3_add_outer(apq, pp, qq);
  }
  q[c] = ff_extract_rotation(apq, q[c], iterations);
  com_x[c] = com.x, com_y[c] = com.y, com_z[c] = com.z;
  // clusterVelocities: the mean velocity of the members, before this step moves them.
  float sx = 0.0f, sy = 0.0f, sz = 0.0f;
  for (uint k = b; k < e; ++k) {
    const uint p = cl_members[k];
    sx += vx[p], sy += vy[p], sz += vz[p];
  }
  cv_x[c] = sx * inv, cv_y[c] = sy * inv, cv_z[c] = sz * inv;
}

// Goals (kept for reading back), then the velocity update and integration.
__kernel void sm_particles(__global float* x, __global float* y, __global float* z, __global float* vx,
                           __global float* vy, __global float* vz, __global const float* x0,
                           __global const float* y0, __global const float* z0, uint n,
                           __global const uint* of_start, __global const uint* of,
                           __global const float* rest_cx, __global const float* rest_cy,
                           __global const float* rest_cz, __global const float4* q,
                           __global const float* com_x, __global const float* com_y,
                           __global const float* com_z, __global const float* cv_x,
                           __global const float* cv_y, __global const float* cv_z, __global const float* ux,
                           __global const float* uy, __global const float* uz, float h, float alpha,
                           float feedback, float damping, float4 box_lo, float4 box_hi, __global float* gx,
                           __global float* gy, __global float* gz, __global int* bad, int tag) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const uint b = of_start[i], e = of_start[i + 1];
  // clusterGoals (eq. 8): the mean over the particle's clusters of R_c (x0 - c0_c) + c_c.
  ff_float3 g = FF_F3(0.0f, 0.0f, 0.0f);
  const ff_float3 p0 = FF_F3(x0[i], y0[i], z0[i]);
  for (uint k = b; k < e; ++k) {
    const uint c = of[k];
    const ff_mat3 r = ff_quat_to_mat3(q[c]);
    g += ff_mat3_mul_vec(r, p0 - FF_F3(rest_cx[c], rest_cy[c], rest_cz[c])) +
         FF_F3(com_x[c], com_y[c], com_z[c]);
  }
  const float ginv = e > b ? 1.0f / (float)(e - b) : 0.0f;
  const ff_float3 goal = FF_F3(g.x * ginv, g.y * ginv, g.z * ginv);
  gx[i] = goal.x, gy[i] = goal.y, gz[i] = goal.z;

  ff_float3 v = FF_F3(vx[i], vy[i], vz[i]);
  const ff_float3 p = FF_F3(x[i], y[i], z[i]);
  ff_float3 vc = FF_F3(0.0f, 0.0f, 0.0f);
  for (uint k = b; k < e; ++k) {
    const uint c = of[k];
    vc += FF_F3(cv_x[c], cv_y[c], cv_z[c]);
  }
  vc = vc * (1.0f / (float)(e - b));
  v = ff_feedback_velocity(v, vc, damping);  // towards the clusters' motion
  v = ff_feedback_velocity(v, FF_F3(ux[i], uy[i], uz[i]), feedback);
  v += ff_shape_match_dv(goal, p, alpha, h);
  ff_float3 np = p + v * h;
  float c3[3] = {np.x, np.y, np.z}, v3[3] = {v.x, v.y, v.z};
  const float lo[3] = {box_lo.x, box_lo.y, box_lo.z}, hi[3] = {box_hi.x, box_hi.y, box_hi.z};
  for (int d = 0; d < 3; ++d) {
    if (c3[d] < lo[d]) c3[d] = lo[d], v3[d] = 0.0f;
    if (c3[d] > hi[d]) c3[d] = hi[d], v3[d] = 0.0f;
  }
  x[i] = c3[0], y[i] = c3[1], z[i] = c3[2];
  vx[i] = v3[0], vy[i] = v3[1], vz[i] = v3[2];
  int ok = 1;
  for (int d = 0; d < 3; ++d) ok = ok && isfinite(c3[d]) && isfinite(v3[d]);
  if (!ok) ff_report_nonfinite(bad, tag);
}
