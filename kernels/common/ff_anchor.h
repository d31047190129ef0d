/* ff_anchor.h - the shape stays where it was placed (issue 10, item 6;
 * docs/CONTROL_UNITS.md, "Anchor"), shared by the OpenMP backend
 * (Controller::shapeMatchStep) and the kernels (kernels/shape_matching.cl).
 *
 * Cluster shape matching (eq. 7-9) pulls every cluster towards its own
 * rigid fit, so it has no restoring force for the rigid motion of the whole
 * control set, and the controlled fluid carries no weight (the control holds
 * its gravity): the set and its fluid together are weightless and undamped
 * along the vertical. Whatever lifts them (the floor clamp of a shape placed
 * partly under the floor, its elastic rebound from the floor, the fluid
 * feedback from fluid rising through it) leaves them climbing, and a torque
 * from the floor clamp leaves them tipped. The anchor gives those rigid modes
 * the restoring force they lack: each shape-matching step, after eq. 7 and
 * before the integration, the set's rigid velocity along "up" (against
 * gravity) and its rigid rotation about the horizontal axes (their least-
 * squares fits to the particles' velocities) are replaced by the velocities
 * that take the fraction alpha (eq. 7's stiffness) of the set's height above
 * its anchor and of its tilt off its rest orientation's up axis away in this
 * step. Deformation, horizontal motion and turning about "up" stay as the
 * paper has them.
 *
 * The sums run over the control particles in 8 lanes (particle k in lane
 * k mod 8), combined by ff_lane_sum8, on both backends in the same order. */
#ifndef FF_ANCHOR_H
#define FF_ANCHOR_H
#include "ff_cluster_sums.h"
#include "ff_compat.h"
#include "ff_rotation.h"

/* params.shape_matching.anchor: 0 off; FF_ANCHOR_HOLD holds the set at the
 * height and up axis it was placed with, both ways, at eq. 7's rate (it makes
 * thin shapes form slowly and throws the runner over: docs/CONTROL_UNITS.md,
 * "Anchor"); FF_ANCHOR_STAND keeps it from rising above the height at which
 * its rigid rest shape stands on the floor (it may sink below, and rises to it
 * as it forms) and from tipping, at the rate a body of its height tips under
 * gravity. */
#define FF_ANCHOR_HOLD 1
#define FF_ANCHOR_STAND 2

/* Gravity's magnitude. */
FF_FN float ff_anchor_g(const float g[3]) {
  return FF_SQRT(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
}

/* "Up", against gravity g: 1 with the unit vector in *up, or 0 without
 * gravity (no anchor then). */
FF_FN int ff_anchor_up(const float g[3], ff_float3* up) {
  const float gl = ff_anchor_g(g);
  if (!(gl > 0.0f)) return 0;
  *up = FF_F3(-g[0] / gl, -g[1] / gl, -g[2] / gl);
  return 1;
}

/* Two unit vectors e1, e2 with (e1, e2, up) right-handed and orthonormal. */
FF_FN void ff_anchor_basis(ff_float3 up, ff_float3* e1, ff_float3* e2) {
  const ff_float3 a = FF_FABS(up.x) < 0.9f ? FF_F3(1.0f, 0.0f, 0.0f) : FF_F3(0.0f, 0.0f, 1.0f);
  const ff_float3 c = FF_CROSS(up, a);
  *e1 = c * (1.0f / ff_length(c));
  *e2 = FF_CROSS(up, *e1);
}

/* The control set's centre of mass, its positions in 8 lanes. */
FF_FN ff_float3 ff_anchor_com(FF_GLOBAL const float* x, FF_GLOBAL const float* y, FF_GLOBAL const float* z,
                              uint n) {
  ff_float3 v[FF_CLUSTER_LANES];
  for (uint l = 0; l < FF_CLUSTER_LANES; ++l) {
    ff_float3 s = FF_F3(0.0f, 0.0f, 0.0f);
    for (uint k = l; k < n; k += FF_CLUSTER_LANES) s += FF_F3(x[k], y[k], z[k]);
    v[l] = s;
  }
  return ff_lanes_mean3(v, n);
}

/* The correction of the set's rigid velocity (ff_anchor_fix, applied by
 * ff_anchor_velocity): dv, the change of its velocity along up; dw, the
 * change of its angular velocity about the horizontal axes; com, the centre
 * about which dw turns. */
typedef struct {
  ff_float3 dv, dw, com;
} ff_anchor_fix;

#define FF_ANCHOR_SUMS 15

/* The rate (1/s) at which FF_ANCHOR_STAND rights a tilt: sqrt(g / l), that
 * at which an inverted pendulum of length l (the rest centre's height above
 * the rest shape's lowest particle) tips under gravity g, so that the anchor
 * rights a shape as fast as its weight would tip it and no faster (eq. 7's
 * rate, 60/s, turns the whole set while its limbs are off their fit). 0 for
 * l <= 0 or no gravity. */
FF_FN float ff_anchor_tilt_rate(float g, float l) {
  return g > 0.0f && l > 0.0f ? FF_SQRT(g / l) : 0.0f;
}

/* The anchor's correction for control particles at x with velocities v
 * (after eq. 7, before the integration) and rest positions x0 (rest centre
 * rc), anchored at `anchor` (where the placement's rigid rest shape stands in
 * the container, along up), with eq. 7's stiffness alpha and time step h,
 * in `mode` (FF_ANCHOR_HOLD or FF_ANCHOR_STAND) under gravity of magnitude g.
 * The whole set's best-fit rotation R (A_pq of all particles, warm-started
 * from q_warm) carries the rest "up" to R up; its tilt is undone by the
 * angular velocity k (R up x up) (the sine of the tilt about its axis:
 * k h of the tilt per step while it is small), k = alpha / h (HOLD) or
 * ff_anchor_tilt_rate (STAND). HOLD sets the rigid velocity along up to
 * -alpha / h times the height above the anchor; STAND does so only above it. */
FF_FN ff_anchor_fix ff_anchor_correction(FF_GLOBAL const float* x, FF_GLOBAL const float* y,
                                         FF_GLOBAL const float* z, FF_GLOBAL const float* vx,
                                         FF_GLOBAL const float* vy, FF_GLOBAL const float* vz,
                                         FF_GLOBAL const float* x0, FF_GLOBAL const float* y0,
                                         FF_GLOBAL const float* z0, uint n, ff_float3 rc, ff_float3 anchor,
                                         ff_float3 up, int mode, float g, float alpha, float h,
                                         ff_quat q_warm, int iterations) {
  ff_anchor_fix fix;
  fix.dv = FF_F3(0.0f, 0.0f, 0.0f);
  fix.dw = fix.dv;
  fix.com = fix.dv;
  if (n == 0u) return fix;
  ff_float3 e1, e2;
  ff_anchor_basis(up, &e1, &e2);
  const ff_float3 com = ff_anchor_com(x, y, z, n);
  fix.com = com;
  /* Per lane: A_pq (9), the velocity along up (1), the horizontal block of
   * the inertia about com in the (e1, e2) basis (3: G11, G22, G12) and the
   * angular momentum about e1 and e2 (2). */
  float lanes[FF_ANCHOR_SUMS][FF_CLUSTER_LANES];
  float low = 0.0f; /* the lowest rest position along up, from rc (exact in any order) */
  for (uint l = 0; l < FF_CLUSTER_LANES; ++l) {
    ff_mat3 a = ff_mat3_zero();
    float vu = 0.0f, g11 = 0.0f, g22 = 0.0f, g12 = 0.0f, b1 = 0.0f, b2 = 0.0f;
    for (uint k = l; k < n; k += FF_CLUSTER_LANES) {
      const ff_float3 r = FF_F3(x[k], y[k], z[k]) - com, v = FF_F3(vx[k], vy[k], vz[k]);
      const ff_float3 r0 = FF_F3(x0[k], y0[k], z0[k]) - rc;
      a = ff_mat3_add_outer(a, r, r0);
      low = FF_FMIN(low, FF_DOT(r0, up));
      const float r1 = FF_DOT(r, e1), r2 = FF_DOT(r, e2), ru = FF_DOT(r, up);
      const float v1 = FF_DOT(v, e1), v2 = FF_DOT(v, e2), vup = FF_DOT(v, up);
      vu += vup;
      g11 += r2 * r2 + ru * ru, g22 += r1 * r1 + ru * ru, g12 -= r1 * r2;
      b1 += r2 * vup - ru * v2, b2 += ru * v1 - r1 * vup;
    }
    const float mine[FF_ANCHOR_SUMS] = {a.c0.x, a.c0.y, a.c0.z, a.c1.x, a.c1.y, a.c1.z, a.c2.x, a.c2.y,
                                        a.c2.z, vu,     g11,    g22,    g12,    b1,     b2};
    for (int s = 0; s < FF_ANCHOR_SUMS; ++s) lanes[s][l] = mine[s];
  }
  float t[FF_ANCHOR_SUMS];
  for (int s = 0; s < FF_ANCHOR_SUMS; ++s)
    t[s] = ff_lane_sum8(lanes[s][0], lanes[s][1], lanes[s][2], lanes[s][3], lanes[s][4], lanes[s][5],
                        lanes[s][6], lanes[s][7]);
  ff_mat3 apq;
  apq.c0 = FF_F3(t[0], t[1], t[2]), apq.c1 = FF_F3(t[3], t[4], t[5]), apq.c2 = FF_F3(t[6], t[7], t[8]);
  const float rate = alpha / h;
  /* Height: the rigid velocity along up becomes -rate (com - anchor).up. */
  const float height = FF_DOT(com - anchor, up);
  if (mode != FF_ANCHOR_STAND || height > 0.0f) fix.dv = up * (-rate * height - t[9] * (1.0f / (float)n));
  const float turn = mode == FF_ANCHOR_STAND ? ff_anchor_tilt_rate(g, -low) : rate;
  /* Tilt: the least-squares angular velocity about e1, e2 (G w = b) becomes
   * rate (R up x up). */
  const ff_quat q = ff_extract_rotation(apq, q_warm, iterations);
  const ff_float3 tilt = FF_CROSS(ff_mat3_mul_vec(ff_quat_to_mat3(q), up), up);
  const float det = t[10] * t[11] - t[12] * t[12];
  if (det > 0.0f) {
    const float w1 = (t[11] * t[13] - t[12] * t[14]) / det, w2 = (t[10] * t[14] - t[12] * t[13]) / det;
    fix.dw = e1 * (turn * FF_DOT(tilt, e1) - w1) + e2 * (turn * FF_DOT(tilt, e2) - w2);
  }
  return fix;
}

/* The velocity v of a control particle at x with the anchor's correction. */
FF_FN ff_float3 ff_anchor_velocity(ff_float3 v, ff_float3 x, ff_float3 dv, ff_float3 dw, ff_float3 com) {
  return v + dv + FF_CROSS(dw, x - com);
}

#endif /* FF_ANCHOR_H */
