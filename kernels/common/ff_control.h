// ff_control.h - control-particle and shape-matching formulas of Yoshino &
// Tsuruno (eq. 4-9), shared by the OpenMP backend and the OpenCL kernels.
#ifndef FF_CONTROL_H
#define FF_CONTROL_H
#include "ff_compat.h"
#include "ff_sph.h"

/* Eq. 5: density scale of a control particle from rho_hat = sum_e V_e W. */
FF_FN float ff_control_scale(float rho_hat) {
  return 1.0f - FF_FMIN(1.0f, rho_hat);
}

/* The control particles' grid has cells of radius / FF_CONTROL_GRID_DIVISIONS
 * (queries prune it to the sphere, ff_row_cells), over the container. */
#define FF_CONTROL_GRID_DIVISIONS 2

/* A sum over the fluid around a control particle runs in 8 lanes: the fluid
 * particle at sorted position k adds to lane k mod 8 (in ascending k), and the
 * lanes combine in this fixed order. Both backends load 8 consecutive fluid
 * particles at a time this way (the OpenMP backend with 8-lane vectors, the
 * kernels with float8), so the sums agree bit for bit. */
FF_FN float ff_lane_sum8(float a0, float a1, float a2, float a3, float a4, float a5, float a6, float a7) {
  return ((a0 + a4) + (a2 + a6)) + ((a1 + a5) + (a3 + a7));
}

/* Share of a fluid particle's weight that the control carries. wsum * v_c is
 * the part of the particle's neighbourhood filled by control particles of rest
 * volume v_c (wsum = sum_i W(|p_i - x_e|)): 1 deep inside the shape, 1/2 on its
 * surface. full_at is that value one control-particle spacing outside a flat
 * surface (ff_control_full_coverage): the control carries all the weight of
 * fluid inside the shape and up to one spacing outside it (the voxelisation's
 * own uncertainty), fading to none at the edge of its reach. */
FF_FN float ff_control_held(float wsum, float v_c, float full_at) {
  return FF_FMIN(1.0f, wsum * v_c / full_at);
}

/* The coverage one control-particle spacing (cbrt(v_c)) outside a flat surface
 * of the shape, for control radius r with poly6 coefficient coef. */
FF_FN float ff_control_full_coverage(float v_c, float r, float coef) {
  return ff_poly6_wall_fraction(FF_CBRT(v_c), r, coef);
}

/* Eq. 4, one control particle's term: w_a s_i (p_i - x_e)/|p_i - x_e| W, as
 * d * ff_attraction_factor(r, s, w) with d = p_i - x_e, r = |d|. */
#define FF_ATTRACTION_FACTOR_DEF(T, name)          \
  FF_FN T name(T r, float s, T w) {                \
    return r > 1e-12f ? s * w / r : FF_ZERO_OF(T); \
  }
FF_GENERIC(FF_ATTRACTION_FACTOR_DEF, ff_attraction_factor)
FF_FN ff_float3 ff_attraction_term(ff_float3 d, float r, float s, float w) {
  return d * ff_attraction_factor(r, s, w);
}

/* Eq. 6 integrated implicitly. Eq. 6 is a linear relaxation of v_e towards the
 * control velocities: f_v = w_v (sum_i W_i v_i - (sum_i W_i) v_e) = V - K v_e with
 * V = w_v sum_i W_i v_i and K = w_v sum_i W_i. Backward Euler over dt gives the
 * acceleration (V - K v_e) / (1 + dt K): identical to eq. 6 as dt K -> 0 and never
 * overshooting, whatever the number of control particles in range. */
FF_FN float ff_velocity_force_implicit(float vsum, float k, float v, float dt) {
  return (vsum - k * v) / (1.0f + dt * k);
}

/* Fluid feedback: the control particle's velocity relaxes towards u_bar, the
 * kernel-weighted mean fluid velocity around it (zero where no fluid is). */
FF_FN ff_float3 ff_feedback_velocity(ff_float3 v, ff_float3 u_bar, float coef) {
  return v + (u_bar - v) * coef;
}

/* Eq. 7: velocity change towards the goal, with stiffness alpha and the shape
 * matching time step dt. */
FF_FN ff_float3 ff_shape_match_dv(ff_float3 goal, ff_float3 x, float alpha, float dt) {
  return (goal - x) * (alpha / dt);
}

#endif /* FF_CONTROL_H */
