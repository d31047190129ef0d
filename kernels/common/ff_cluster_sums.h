/* ff_cluster_sums.h - a shape-matching cluster's sums (centre of mass, the
 * A_pq matrix of Mueller et al. 2005, the mean velocity) in 8 lanes, shared by
 * the OpenMP backend (src/control/shape_matching.cpp) and the kernels
 * (kernels/shape_matching.cl).
 *
 * The lane order: member k of cluster [b, e) (counted from b) adds to lane
 * (k - b) mod 8, each lane sums its members in ascending k, and the 8 lane
 * sums combine by ff_lane_sum8. The GPU kernel gives each lane its own
 * work-item (ff_cluster_lane_*) and combines in local memory; the OpenMP
 * backend and the CPU kernel run the 8 lanes one after another
 * (ff_cluster_*_of); all of them round alike, so the results agree bit for
 * bit. */
#ifndef FF_CLUSTER_SUMS_H
#define FF_CLUSTER_SUMS_H
#include "ff_compat.h"
#include "ff_control.h"
#include "ff_rotation.h"

#define FF_CLUSTER_LANES 8

/* Lane `lane`'s sum of (a, b, c)[members[k]] over k = first + lane, first + lane + 8, ... < end. */
FF_FN ff_float3 ff_cluster_lane_sum3(FF_GLOBAL const float* a, FF_GLOBAL const float* b,
                                     FF_GLOBAL const float* c, FF_GLOBAL const uint* members, uint first,
                                     uint end, uint lane) {
  ff_float3 s = FF_F3(0.0f, 0.0f, 0.0f);
  for (uint k = first + lane; k < end; k += FF_CLUSTER_LANES) {
    const uint p = members[k];
    s += FF_F3(a[p], b[p], c[p]);
  }
  return s;
}

/* Entry k of a rest configuration at blend weight w (ff_blend_rest): from
 * (fx, fy, fz)[k] (the start configuration) to (tx, ty, tz)[k] (the
 * reference). The start arrays are read only while w < 1, so they may be
 * empty (null) with no blend. Control particles' rest positions and their
 * clusters' rest centres both go through it, on both backends. */
FF_FN ff_float3 ff_blend_rest_at(FF_GLOBAL const float* fx, FF_GLOBAL const float* fy,
                                 FF_GLOBAL const float* fz, FF_GLOBAL const float* tx,
                                 FF_GLOBAL const float* ty, FF_GLOBAL const float* tz, uint k, float w) {
  const ff_float3 t = FF_F3(tx[k], ty[k], tz[k]);
  return w < 1.0f ? ff_blend_rest(FF_F3(fx[k], fy[k], fz[k]), t, w) : t;
}

/* Lane `lane`'s part of A_pq = sum_p (x_p - com) (x0_p - rc)^T, with the rest
 * positions x0_p at blend weight w between the start configuration (bx, by,
 * bz) and the reference (x0, y0, z0) (ff_blend_rest; w = 1: the reference). */
FF_FN ff_mat3 ff_cluster_lane_apq_blend(FF_GLOBAL const float* x, FF_GLOBAL const float* y,
                                        FF_GLOBAL const float* z, FF_GLOBAL const float* x0,
                                        FF_GLOBAL const float* y0, FF_GLOBAL const float* z0,
                                        FF_GLOBAL const float* bx, FF_GLOBAL const float* by,
                                        FF_GLOBAL const float* bz, float w, FF_GLOBAL const uint* members,
                                        uint first, uint end, uint lane, ff_float3 com, ff_float3 rc) {
  ff_mat3 m = ff_mat3_zero();
  for (uint k = first + lane; k < end; k += FF_CLUSTER_LANES) {
    const uint p = members[k];
    const ff_float3 r = ff_blend_rest_at(bx, by, bz, x0, y0, z0, p, w);
    m = ff_mat3_add_outer(m, FF_F3(x[p], y[p], z[p]) - com, r - rc);
  }
  return m;
}

/* The 8 lane sums combined (ff_lane_sum8), component by component. */
FF_FN ff_float3 ff_lanes_total3(const ff_float3 v[FF_CLUSTER_LANES]) {
  return FF_F3(ff_lane_sum8(v[0].x, v[1].x, v[2].x, v[3].x, v[4].x, v[5].x, v[6].x, v[7].x),
               ff_lane_sum8(v[0].y, v[1].y, v[2].y, v[3].y, v[4].y, v[5].y, v[6].y, v[7].y),
               ff_lane_sum8(v[0].z, v[1].z, v[2].z, v[3].z, v[4].z, v[5].z, v[6].z, v[7].z));
}
FF_FN ff_mat3 ff_lanes_total_mat3(const ff_mat3 m[FF_CLUSTER_LANES]) {
  ff_float3 c[FF_CLUSTER_LANES];
  ff_mat3 t;
  for (int l = 0; l < FF_CLUSTER_LANES; ++l) c[l] = m[l].c0;
  t.c0 = ff_lanes_total3(c);
  for (int l = 0; l < FF_CLUSTER_LANES; ++l) c[l] = m[l].c1;
  t.c1 = ff_lanes_total3(c);
  for (int l = 0; l < FF_CLUSTER_LANES; ++l) c[l] = m[l].c2;
  t.c2 = ff_lanes_total3(c);
  return t;
}

/* The mean of `count` values from their 8 lane sums. */
FF_FN ff_float3 ff_lanes_mean3(const ff_float3 v[FF_CLUSTER_LANES], uint count) {
  const float inv = 1.0f / (float)count;
  const ff_float3 s = ff_lanes_total3(v);
  return FF_F3(s.x * inv, s.y * inv, s.z * inv);
}

/* The whole cluster [first, end), its lanes one after another: the mean of (a, b, c) over the members. */
FF_FN ff_float3 ff_cluster_mean3_of(FF_GLOBAL const float* a, FF_GLOBAL const float* b,
                                    FF_GLOBAL const float* c, FF_GLOBAL const uint* members, uint first,
                                    uint end) {
  ff_float3 v[FF_CLUSTER_LANES];
  for (uint l = 0; l < FF_CLUSTER_LANES; ++l) v[l] = ff_cluster_lane_sum3(a, b, c, members, first, end, l);
  return ff_lanes_mean3(v, end - first);
}

/* The whole cluster's A_pq, its lanes one after another (rest positions at
 * blend weight w, as ff_cluster_lane_apq_blend). */
FF_FN ff_mat3 ff_cluster_apq_blend_of(FF_GLOBAL const float* x, FF_GLOBAL const float* y,
                                      FF_GLOBAL const float* z, FF_GLOBAL const float* x0,
                                      FF_GLOBAL const float* y0, FF_GLOBAL const float* z0,
                                      FF_GLOBAL const float* bx, FF_GLOBAL const float* by,
                                      FF_GLOBAL const float* bz, float w, FF_GLOBAL const uint* members,
                                      uint first, uint end, ff_float3 com, ff_float3 rc) {
  ff_mat3 m[FF_CLUSTER_LANES];
  for (uint l = 0; l < FF_CLUSTER_LANES; ++l)
    m[l] = ff_cluster_lane_apq_blend(x, y, z, x0, y0, z0, bx, by, bz, w, members, first, end, l, com, rc);
  return ff_lanes_total_mat3(m);
}

/* The whole cluster's A_pq, its lanes one after another. */
FF_FN ff_mat3 ff_cluster_apq_of(FF_GLOBAL const float* x, FF_GLOBAL const float* y, FF_GLOBAL const float* z,
                                FF_GLOBAL const float* x0, FF_GLOBAL const float* y0,
                                FF_GLOBAL const float* z0, FF_GLOBAL const uint* members, uint first,
                                uint end, ff_float3 com, ff_float3 rc) {
  return ff_cluster_apq_blend_of(x, y, z, x0, y0, z0, x0, y0, z0, 1.0f, members, first, end, com, rc);
}

#endif /* FF_CLUSTER_SUMS_H */
