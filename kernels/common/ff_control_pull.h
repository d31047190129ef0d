// ff_control_pull.h - the control's acceleration on one fluid particle, from
// its sums over the control particles within reach: the recapture's pull
// where it acts (ff_recapture_accel towards ff_recapture_aim), then eq. 4's
// attraction and eq. 6's velocity force (implicit), scaled by the pull mode,
// less the gravity the control carries. The per-particle body of
// Controller::addForces (src/control/controller.cpp) and of the kernels in
// control_forces.cl, written once; the scalars travel in FfControlArgs.
#ifndef FF_CONTROL_PULL_H
#define FF_CONTROL_PULL_H
#include "ff_compat.h"
#include "ff_control.h"
#include "ff_recapture_field.h"

/* The control forces' scalars, one struct of 4-byte fields (C++ and OpenCL C
 * lay it out alike; src/control/control_args.h fills it). */
typedef struct {
  float g[4];                           /* gravity (the 4th unused) */
  float cp_volume, full_at, wa, wv;     /* V_c, ff_control_full_coverage, the pull's weights */
  float gc, unit_scale, dt, radius;     /* gravity carried, 1 or 1 / m, the step, the control radius */
  float rspeed, rrate, cell, fcell_inv; /* recapture speed and rate, control grid cell, 1 / field cell */
  float r2, coef;                       /* eq. 4 and 6's kernel: radius^2 and its poly6 coefficient */
  float fo[4];                          /* the recapture field's origin (the 4th unused) */
  int fm[4];                            /* the recapture field's cells per axis (the 4th unused) */
  int pull_mode, recapture, use_mask,
      tag; /* ff_pull_scale's mode; recapture on; a controlled mask; check tag */
} FfControlArgs;

/* The recapture as it stands this step: its centre, fade and whether it aims
 * at the centre (Controller::addForces; control_recapture_centre). */
typedef struct {
  float centre[3], fade;
  int at_centre;
} FfRecaptureNow;

/* Fluid particle at x with velocity v and density rho (read by
 * FF_PULL_PER_DENSITY only), whose acceleration is a, and its sums over the
 * control particles: fa = sum ff_attraction_term, wsum = sum W, vs = sum W v_i.
 * recaptured: the recapture acts on it (on, and the particle is controlled);
 * seeds, sx, sy, sz: the recapture's field and the control particles in their
 * grid's order. Returns a with the control's acceleration added; *changed
 * tells whether anything was added (the caller checks the sum is finite). */
FF_FN ff_float3 ff_control_fluid_accel(FfControlArgs P, FfRecaptureNow R, ff_float3 a, ff_float3 fa,
                                       float wsum, ff_float3 vs, ff_float3 x, ff_float3 v, float rho,
                                       int recaptured, FF_GLOBAL const uint* seeds, FF_GLOBAL const float* sx,
                                       FF_GLOBAL const float* sy, FF_GLOBAL const float* sz, int* changed) {
  const ff_float3 g = FF_F3(P.g[0], P.g[1], P.g[2]);
  *changed = 0;
  if (recaptured) {
    const float k = ff_recapture_strength(wsum, P.cp_volume, P.full_at, R.fade);
    ff_float3 c;
    if (k > 0.0f && ff_recapture_aim(R.at_centre, FF_F3(R.centre[0], R.centre[1], R.centre[2]), seeds, sx, sy,
                                     sz, x.x, x.y, x.z, P.fm, P.fo, P.fcell_inv, &c)) {
      a = a + ff_recapture_accel(x, v, c, g, P.rspeed, P.rrate, P.radius, P.dt, k,
                                 ff_recapture_weightless(wsum, P.cp_volume, P.full_at, R.fade));
      *changed = 1;
    }
  }
  if (wsum <= 0.0f) return a;
  const float scale = ff_pull_scale(P.pull_mode, wsum, P.cp_volume, rho, P.unit_scale);
  const float kv = P.wv * wsum * scale;
  fa = fa * (P.wa * scale);
  /* Gravity carried by the control (all of it inside the shape). */
  const float held = P.gc * ff_control_held(wsum, P.cp_volume, P.full_at);
  fa = fa - g * held;
  *changed = 1;
  return FF_F3(a.x + (fa.x + ff_velocity_force_implicit(P.wv * vs.x * scale, kv, v.x, P.dt)),
               a.y + (fa.y + ff_velocity_force_implicit(P.wv * vs.y * scale, kv, v.y, P.dt)),
               a.z + (fa.z + ff_velocity_force_implicit(P.wv * vs.z * scale, kv, v.z, P.dt)));
}

#endif /* FF_CONTROL_PULL_H */
