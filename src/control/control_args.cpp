#include "control/control_args.h"

#include "ff_sph.h"

namespace ff {

FfControlArgs controlArgs(const ControlParams& cp, const float gravity[3], float particle_mass,
                          float cp_volume, float dt, float cell, const RecaptureFieldGeom& field, bool masked,
                          int tag) {
  FfControlArgs a{};
  for (int d = 0; d < 3; ++d) a.g[d] = gravity[d], a.fo[d] = field.o[d], a.fm[d] = field.m[d];
  const float r = cp.radius;
  a.cp_volume = cp_volume;
  a.r2 = r * r, a.coef = ff_poly6_coef(r);
  a.full_at = ff_control_full_coverage(cp_volume, r, a.coef);
  a.wa = cp.pullAttraction(gravity), a.wv = cp.pullVelocity(gravity);
  a.gc = cp.gravity_compensation;
  a.unit_scale = cp.units == ControlForceUnits::Force ? 1.0f / particle_mass : 1.0f;
  a.dt = dt, a.radius = r, a.cell = cell;
  a.rspeed = cp.recaptureSpeed(gravity), a.rrate = cp.recaptureRate(gravity);
  a.fcell_inv = field.inv_fcell;
  a.pull_mode = cp.pullMode();
  a.recapture = cp.recapture > 0.0f ? 1 : 0;
  a.use_mask = masked ? 1 : 0;
  a.tag = tag;
  return a;
}

}  // namespace ff
