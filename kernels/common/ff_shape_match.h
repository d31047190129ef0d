/* ff_shape_match.h - one shape-matching step (paper eq. 7-9; Mueller et al.
 * 2005), its per-cluster and per-particle bodies written once for the
 * OpenMP backend (Controller::shapeMatchStep, src/control/shape_matching.cpp)
 * and the kernels (kernels/shape_matching.cl). Its scalars travel in
 * FfShapeMatchArgs (src/control/shape_match_args.h fills it).
 *
 * A step: each cluster's frame (centre of mass and rotation, ff_sm_frame)
 * and mean velocity; each control particle's goal (eq. 8, ff_sm_goal) and
 * velocity after the damping, the fluid feedback and eq. 7 (ff_sm_velocity);
 * the anchor (ff_anchor.h); the integration with the container clamp
 * (ff_sm_move). */
#ifndef FF_SHAPE_MATCH_H
#define FF_SHAPE_MATCH_H
#include "ff_cluster_sums.h"
#include "ff_compat.h"
#include "ff_control.h"
#include "ff_rotation.h"

/* A shape-matching step's scalars, one struct of 4-byte fields (C++ and
 * OpenCL C lay it out alike). */
typedef struct {
  float box_lo[4], box_hi[4]; /* the container clamp (the 4th unused); +-inf: none */
  float w;                    /* the rest-shape blend's weight this step (ff_blend_weight) */
  float h, alpha;             /* the step and eq. 7's stiffness */
  float feedback, damping;    /* the fluid feedback's and the damping's relaxation */
  float g;                    /* gravity's magnitude (the standing anchor's tilt rate) */
  uint n, nclusters;          /* control particles and clusters */
  int iterations;             /* ff_extract_rotation's iterations */
  int anchor, tag;            /* the anchor's mode where it acts (ff_anchor.h), else 0; the check tag */
} FfShapeMatchArgs;

/* The rest data of a control set at blend weight w (ff_blend_rest_at): the
 * particles' reference (x0) and start (bx0) positions and the clusters'
 * reference (rest_c) and start (from_c) centres. Start arrays are read only
 * while w < 1. */
#define FF_SM_REST_PARAMS                                                                             \
  FF_GLOBAL const float *x0, FF_GLOBAL const float *y0, FF_GLOBAL const float *z0,                    \
      FF_GLOBAL const float *bx0, FF_GLOBAL const float *by0, FF_GLOBAL const float *bz0,             \
      FF_GLOBAL const float *rest_cx, FF_GLOBAL const float *rest_cy, FF_GLOBAL const float *rest_cz, \
      FF_GLOBAL const float *from_cx, FF_GLOBAL const float *from_cy, FF_GLOBAL const float *from_cz

/* Cluster c's frame: returns its centre of mass and sets *q (warm start in,
 * rotation out) to the rotation of its A_pq (eq. 7-8), the members
 * cl_members[cl_start[c] .. cl_start[c + 1]), summed in the lane order of
 * ff_cluster_sums.h. */
FF_FN ff_float3 ff_sm_frame(FF_GLOBAL const float* x, FF_GLOBAL const float* y, FF_GLOBAL const float* z,
                            FF_SM_REST_PARAMS, FF_GLOBAL const uint* cl_start,
                            FF_GLOBAL const uint* cl_members, uint c, float w, int iterations, ff_quat* q) {
  const uint b = cl_start[c], e = cl_start[c + 1];
  const ff_float3 com = ff_cluster_mean3_of(x, y, z, cl_members, b, e);
  const ff_float3 rc = ff_blend_rest_at(from_cx, from_cy, from_cz, rest_cx, rest_cy, rest_cz, c, w);
  const ff_mat3 apq =
      ff_cluster_apq_blend_of(x, y, z, x0, y0, z0, bx0, by0, bz0, w, cl_members, b, e, com, rc);
  *q = ff_extract_rotation(apq, *q, iterations);
  return com;
}

/* One cluster's term of a goal (eq. 8): R (p0 - c0) + com, for the
 * particle's rest position p0, the cluster's rotation R, rest centre c0 and
 * centre of mass com. */
FF_FN ff_float3 ff_sm_goal_term(ff_mat3 r, ff_float3 p0, ff_float3 c0, ff_float3 com) {
  return ff_mat3_mul_vec(r, p0 - c0) + com;
}

/* The mean of a goal's n terms summed in g (0 where n is 0). */
FF_FN ff_float3 ff_sm_goal_mean(ff_float3 g, uint n) {
  const float inv = n > 0 ? 1.0f / (float)n : 0.0f;
  return FF_F3(g.x * inv, g.y * inv, g.z * inv);
}

/* Control particle i's goal (eq. 8): the mean over its clusters
 * of[of_start[i] .. of_start[i + 1]) of R_c (x0_i - c0_c) + c_c, with the
 * clusters' rotations q and centres of mass com. */
FF_FN ff_float3 ff_sm_goal(FF_SM_REST_PARAMS, FF_GLOBAL const uint* of_start, FF_GLOBAL const uint* of,
                           FF_GLOBAL const ff_quat* q, FF_GLOBAL const float* com_x,
                           FF_GLOBAL const float* com_y, FF_GLOBAL const float* com_z, uint i, float w) {
  const uint b = of_start[i], e = of_start[i + 1];
  ff_float3 g = FF_F3(0.0f, 0.0f, 0.0f);
  const ff_float3 p0 = ff_blend_rest_at(bx0, by0, bz0, x0, y0, z0, i, w);
  for (uint k = b; k < e; ++k) {
    const uint c = of[k];
    g += ff_sm_goal_term(ff_quat_to_mat3(q[c]), p0,
                         ff_blend_rest_at(from_cx, from_cy, from_cz, rest_cx, rest_cy, rest_cz, c, w),
                         FF_F3(com_x[c], com_y[c], com_z[c]));
  }
  return ff_sm_goal_mean(g, e - b);
}

/* The same goal from each cluster's rotation as a matrix (rot) and rest
 * centre at this step's blend weight (rest_c), made once per cluster (the
 * OpenMP backend's clusterGoals): the same terms, so the same bits. */
FF_FN ff_float3 ff_sm_goal_framed(FF_GLOBAL const float* x0, FF_GLOBAL const float* y0,
                                  FF_GLOBAL const float* z0, FF_GLOBAL const float* bx0,
                                  FF_GLOBAL const float* by0, FF_GLOBAL const float* bz0,
                                  FF_GLOBAL const uint* of_start, FF_GLOBAL const uint* of,
                                  FF_GLOBAL const ff_mat3* rot, FF_GLOBAL const ff_float3* rest_c,
                                  FF_GLOBAL const float* com_x, FF_GLOBAL const float* com_y,
                                  FF_GLOBAL const float* com_z, uint i, float w) {
  const uint b = of_start[i], e = of_start[i + 1];
  ff_float3 g = FF_F3(0.0f, 0.0f, 0.0f);
  const ff_float3 p0 = ff_blend_rest_at(bx0, by0, bz0, x0, y0, z0, i, w);
  for (uint k = b; k < e; ++k) {
    const uint c = of[k];
    g += ff_sm_goal_term(rot[c], p0, rest_c[c], FF_F3(com_x[c], com_y[c], com_z[c]));
  }
  return ff_sm_goal_mean(g, e - b);
}

/* Control particle i's velocity v after this step's damping (towards the
 * mean velocity cv of its clusters), the fluid feedback (towards u, the
 * kernel-weighted mean velocity of the fluid around it) and eq. 7 (towards
 * its goal from its position p). */
FF_FN ff_float3 ff_sm_velocity(ff_float3 v, ff_float3 p, ff_float3 goal, ff_float3 u,
                               FF_GLOBAL const uint* of_start, FF_GLOBAL const uint* of,
                               FF_GLOBAL const float* cv_x, FF_GLOBAL const float* cv_y,
                               FF_GLOBAL const float* cv_z, uint i, FfShapeMatchArgs A) {
  const uint b = of_start[i], e = of_start[i + 1];
  ff_float3 vc = FF_F3(0.0f, 0.0f, 0.0f);
  for (uint k = b; k < e; ++k) {
    const uint c = of[k];
    vc += FF_F3(cv_x[c], cv_y[c], cv_z[c]);
  }
  vc = vc * (1.0f / (float)(e - b));
  v = ff_feedback_velocity(v, vc, A.damping);
  v = ff_feedback_velocity(v, u, A.feedback);
  return v + ff_shape_match_dv(goal, p, A.alpha, A.h);
}

/* Moves a control particle from p by its velocity *v over the step; a
 * coordinate past the container stops there and its velocity component is
 * zeroed. Returns the new position; *finite is 0 if it or *v is not finite. */
FF_FN ff_float3 ff_sm_move(ff_float3 p, ff_float3* v, FfShapeMatchArgs A, int* finite) {
  const ff_float3 np = p + *v * A.h;
  float c3[3] = {np.x, np.y, np.z}, v3[3] = {(*v).x, (*v).y, (*v).z};
  int ok = 1;
  for (int d = 0; d < 3; ++d) {
    if (c3[d] < A.box_lo[d]) c3[d] = A.box_lo[d], v3[d] = 0.0f;
    if (c3[d] > A.box_hi[d]) c3[d] = A.box_hi[d], v3[d] = 0.0f;
    ok = ok && FF_ISFINITE(c3[d]) && FF_ISFINITE(v3[d]);
  }
  *finite = ok;
  *v = FF_F3(v3[0], v3[1], v3[2]);
  return FF_F3(c3[0], c3[1], c3[2]);
}

#endif /* FF_SHAPE_MATCH_H */
