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

/* A control particle's density scale s (eq. 5) and u_bar, the
 * kernel-weighted mean velocity of the fluid around it (for the fluid
 * feedback), from its lane-combined sums w = sum W and wv = sum W v over
 * fluid particles of rest volume `volume`. Where the kernel is only partly
 * filled the missing part counts as still air (so the feedback also damps).
 * Returns s; *u receives u_bar. The per-particle body of
 * Controller::computeScale and kernels/control_scale.cl. */
FF_FN float ff_control_scale_of(float w, ff_float3 wv, float volume, ff_float3* u) {
  const float rho_hat = volume * w;
  const float norm = w > 0.0f ? volume / FF_FMAX(rho_hat, 1.0f) : 0.0f;
  *u = FF_F3(wv.x * norm, wv.y * norm, wv.z * norm);
  return ff_control_scale(rho_hat);
}

/* The control-scale kernels' scalars (kernels/control_scale.cl), 4-byte
 * fields: the fluid grid's origin and cell (geo, as DeviceGrid's float4) and
 * cells per axis (dims, the 4th unused), its query cell, the control radius,
 * a fluid particle's rest volume, the control particles and the check tag. */
typedef struct {
  float geo[4];
  int dims[4];
  float cell, radius, volume;
  uint nc;
  int tag;
} FfScaleArgs;

/* Adaptive control (docs/CONTROL_UNITS.md, "Thin features"): a control
 * particle's own radius, the control radius times its scale (at most 1: the
 * target's local thickness around it). Eq. 5's fluid sum around it runs
 * within its own radius, with the poly6 kernel of it, so that a filled thin
 * part reads filled; eq. 4 and 6 (and the carried gravity and the recapture,
 * which read their sums) weigh every control particle within the control
 * radius, so that no fluid falls out of reach where the radii are small. */
FF_FN float ff_control_radius(float radius, float scale) {
  return radius * scale;
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
  /* full_at is 0 when the kernel does not reach one spacing out (a radius of
   * at most one control spacing): then any fluid in reach is carried whole,
   * the limit of the quotient as full_at -> 0+. */
  return full_at > 0.0f ? FF_FMIN(1.0f, wsum * v_c / full_at) : (wsum > 0.0f ? 1.0f : 0.0f);
}

/* The coverage one control-particle spacing (cbrt(v_c)) outside a flat surface
 * of the shape, for control radius r with poly6 coefficient coef: 0 (exactly)
 * where the radius is at most one spacing. ff_poly6_wall_fraction takes it as
 * the difference of two terms of size r^9 that cancel as the spacing nears r:
 * in float its relative error is 1e-7 at r = 2 spacings, 2e-6 at 1.53, 4e-3
 * at 1.1, and from 1.02 spacings down its result is rounding noise of either
 * sign (+-1e-7; -5.5e-8 at the water bunny's 0.765 spacings, where the exact
 * value is 0: ff_control_held, coverage / full_at, then was down to -9.4e7
 * for the fluid in reach, whose accelerations reached 1.3e9 m/s^2;
 * docs/CONTROL_UNITS.md, "Radius in control spacings"). Within a third of r
 * of the kernel's edge (r <= 1.5 spacings) it is therefore taken from its
 * expansion in t = (r - spacing) / r, (315 / 256) t^5 (16/5 - 16 t / 3 +
 * 24 t^2 / 7 - t^3 + t^4 / 9), whose terms do not cancel there (relative
 * error <= 2e-6 down to 1.01 spacings); at larger radii as before. */
FF_FN float ff_control_full_coverage(float v_c, float r, float coef) {
  const float d = FF_CBRT(v_c);
  if (d < r * (2.0f / 3.0f)) return ff_poly6_wall_fraction(d, r, coef);
  const float t = FF_FMAX(0.0f, (r - d) / r), t2 = t * t;
  const float poly =
      ((16.0f / 5.0f) - (16.0f / 3.0f) * t) + ((24.0f / 7.0f) * t2 - t2 * t) + t2 * t2 * (1.0f / 9.0f);
  return (315.0f / 256.0f) * (t2 * t2 * t) * poly;
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

/* How eq. 4 and eq. 6's sums become accelerations (the "scale mode" both
 * backends pass): as the paper writes them, times unit_scale (1, or 1 / m for
 * the force reading); divided by the density (the force-density reading); or
 * normalised by the local control weight (params.control.normalise,
 * docs/CONTROL_UNITS.md, "Normalised pull"). Normalised, the sums are divided
 * by wsum = sum_i W_i, as Thuerey's implementation divides by the total
 * weight, but never by less than the weight of a half-filled neighbourhood,
 * 1 / (2 v_c) for control particles of rest volume v_c (a flat surface of the
 * shape): inside the shape the attraction is the weighted mean of eq. 4's
 * terms and the velocity force relaxes at a fixed rate, whatever the control
 * particles' spacing; outside, both fade to 0 at the edge of reach, as the
 * paper's do. A control set of any density then pulls alike. */
#define FF_PULL_UNITS 0
#define FF_PULL_PER_DENSITY 1
#define FF_PULL_NORMALISED 2
FF_FN float ff_pull_scale(int mode, float wsum, float v_c, float rho, float unit_scale) {
  return mode == FF_PULL_NORMALISED    ? 1.0f / FF_FMAX(wsum, 0.5f / v_c)
         : mode == FF_PULL_PER_DENSITY ? 1.0f / rho
                                       : unit_scale;
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

/* Rest-shape blend at a target change (docs/CONTROL_UNITS.md, "Rest-shape
 * blend"): each control particle's rest position moves from its start
 * configuration (where placement put it: the new shape spread over the fluid
 * as it stands) to the new target's reference over the blend time T, by the
 * smoothstep w = s^2 (3 - 2 s) of s = t / T. The shape-matching goals then
 * move continuously, at most 1.5 / T times the distance a rest position
 * travels per second. w is 1 (the reference alone) once t >= T or with no
 * blend (T <= 0). */
FF_FN float ff_blend_weight(float t, float blend_time) {
  if (!(blend_time > 0.0f) || t >= blend_time) return 1.0f;
  const float s = FF_FMAX(0.0f, t / blend_time);
  return s * s * (3.0f - 2.0f * s);
}

/* The rest position at blend weight w, from the start configuration `from`
 * to the reference `rest`: exactly `rest` at w = 1. */
FF_FN ff_float3 ff_blend_rest(ff_float3 from, ff_float3 rest, float w) {
  return w >= 1.0f ? rest : from + (rest - from) * w;
}

/* Recapture: fluid out of the control's reach is brought back into the
 * unfilled parts of the target from anywhere in the container
 * (docs/CONTROL_UNITS.md, "Recapture").
 *
 * How much a control particle of density scale s counts as unfilled: 0 while
 * its kernel is at least half filled (a filled surface particle sits at
 * s = 1/2), rising to 1 when it is empty. */
FF_FN float ff_recapture_weight(float s) {
  return FF_FMAX(0.0f, 2.0f * s - 1.0f);
}

/* The weight of a control particle in the recapture's centre: its unfilled
 * weight, plus a little so that a filled shape still has a centre (its
 * centroid). */
FF_FN float ff_recapture_centre_weight(float s) {
  return ff_recapture_weight(s) + 0.01f;
}

/* The recapture's fade from the unfilled weight u = sum_i
 * ff_recapture_weight(s_i) of nc control particles: 1 while at least a
 * tenth of the shape is unfilled, falling linearly to 0 as it fills, so that
 * a filled shape draws no more of the fluid within its reach into itself.
 * The fade scales only the recapture of fluid partly within reach: fluid
 * wholly out of reach is drawn back while the recapture is on however full
 * the shape reads (ff_recapture_strength), since SPH density fills a voxel at
 * half the rest density and a shape reads full (fade 0) while part of its
 * fluid still lies out of reach (7% of Fig. 12's box, on the floor). */
FF_FN float ff_recapture_fade(float u, float nc) {
  return nc > 0.0f ? FF_FMIN(1.0f, u / (0.1f * nc)) : 0.0f;
}

/* How strongly the recapture acts on a fluid particle, from the fade: by the
 * share of it that is out of the control's reach (1 where no control particle
 * is within the radius, 0 where the control carries its whole weight:
 * ff_control_held without the compensation factor). Fluid wholly out of reach
 * is drawn back at least at half strength however full the shape is (fade 0
 * included): it then gathers at the shape, where eq. 4-5 take in only what
 * has room. */
FF_FN float ff_recapture_strength(float wsum, float v_c, float full_at, float fade) {
  const float share = 1.0f - ff_control_held(wsum, v_c, full_at);
  return wsum > 0.0f ? share * fade : FF_FMAX(fade, 0.5f);
}

/* The share of gravity the recapture switches off: all of it for fluid wholly
 * out of reach (so a pool lifts off the floor at any strength), else as
 * ff_recapture_strength. */
FF_FN float ff_recapture_weightless(float wsum, float v_c, float full_at, float fade) {
  return wsum > 0.0f ? ff_recapture_strength(wsum, v_c, full_at, fade) : 1.0f;
}

/* The recapture acceleration of a fluid particle at x with velocity v,
 * towards the point c it aims at (the centre of the unfilled control
 * particles where that lies among them, else the nearest unfilled control
 * particle, ff_recapture_field.h): the share kg of its
 * gravity g is switched off (ff_recapture_weightless) and its velocity relaxes
 * with strength k (ff_recapture_strength; implicitly, at `rate` per second,
 * over dt) towards `speed` along c - x, slowing within `radius` of c. The dot
 * products are written out so that both compilers round them alike. */
FF_FN ff_float3 ff_recapture_accel(ff_float3 x, ff_float3 v, ff_float3 c, ff_float3 g, float speed,
                                   float rate, float radius, float dt, float k, float kg) {
  const ff_float3 d = c - x;
  const float dist = FF_SQRT((d.x * d.x + d.y * d.y) + d.z * d.z);
  const float vmag = speed * FF_FMIN(1.0f, dist / radius);
  const ff_float3 vd = dist > 1e-12f ? d * (vmag / dist) : FF_F3(0.0f, 0.0f, 0.0f);
  return (vd - v) * (k * rate / (1.0f + dt * rate)) - g * kg;
}

#endif /* FF_CONTROL_H */
