// params.cpp - parameter presets and range checks.
#include "core/params.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace ff {

float FluidParams::restSpacing() const {
  return std::cbrt(particle_mass / rest_density);
}

int FluidParams::substepsFor(double max_density, double max_speed) const {
  (void)max_density;  // the sound speed of p = k (rho - rho0) does not depend on density
  const double c = std::sqrt(std::max(0.0, double(gas_constant)));
  const double dt_cfl = double(cfl) * double(smoothing_radius) / (c + max_speed + 1e-12);
  const double n = std::ceil(double(time_step) / dt_cfl - 1e-9);
  return int(std::clamp(n, 1.0, double(std::max(1, max_substeps))));
}

Params presetParams(const std::string& name) {
  // The paper's appendix values; params.h holds them as the defaults.
  if (name == "paper") return Params{};
  // The engine's recommended set; same as paper until measurements say otherwise.
  if (name == "default") return Params{};
  throw Error("unknown parameter preset '" + name + "' (known: paper, default)");
}

namespace {

std::string formatValue(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// Throws "WHERE: FIELD: must be REQUIREMENT (got V)" unless `ok`; a value that
// passes the range test but is infinite is reported as "must be finite".
void check(const std::string& where, const char* field, double v, bool ok, const char* requirement) {
  std::string problem;
  if (!ok)
    problem = std::string("must be ") + requirement;
  else if (!std::isfinite(v))
    problem = "must be finite";
  else
    return;
  std::string prefix = where.empty() ? std::string() : where + ": ";
  throw Error(prefix + field + ": " + problem + " (got " + formatValue(v) + ")");
}

void positive(const std::string& w, const char* f, double v) {
  check(w, f, v, v > 0, "> 0");
}
void nonNegative(const std::string& w, const char* f, double v) {
  check(w, f, v, v >= 0, ">= 0");
}
void unitInterval(const std::string& w, const char* f, double v) {
  check(w, f, v, v >= 0 && v <= 1, "in [0, 1]");
}
void atLeastOne(const std::string& w, const char* f, int v) {
  check(w, f, v, v >= 1, ">= 1");
}

}  // namespace

void validateParams(const Params& p, const std::string& where) {
  const FluidParams& f = p.fluid;
  positive(where, "params.fluid.particle_mass", f.particle_mass);
  positive(where, "params.fluid.particle_radius", f.particle_radius);
  positive(where, "params.fluid.smoothing_radius", f.smoothing_radius);
  positive(where, "params.fluid.rest_density", f.rest_density);
  nonNegative(where, "params.fluid.gas_constant", f.gas_constant);
  nonNegative(where, "params.fluid.viscosity", f.viscosity);
  check(where, "params.fluid.time_step", f.time_step, f.time_step > 0 && f.time_step <= 0.1f, "in (0, 0.1]");
  static const char* kGravity[3] = {"params.fluid.gravity[0]", "params.fluid.gravity[1]",
                                    "params.fluid.gravity[2]"};
  for (int i = 0; i < 3; ++i) check(where, kGravity[i], f.gravity[i], std::isfinite(f.gravity[i]), "finite");
  check(where, "params.fluid.max_step_fraction", f.max_step_fraction,
        f.max_step_fraction > 0 && f.max_step_fraction <= 1, "in (0, 1]");
  check(where, "params.fluid.cfl", f.cfl, f.cfl > 0 && f.cfl <= 1, "in (0, 1]");
  if (f.max_substeps < 1 || f.max_substeps > 1000)
    throw Error((where.empty() ? std::string() : where + ": ") +
                "params.fluid.max_substeps: must be in [1, 1000] (got " + std::to_string(f.max_substeps) +
                ")");

  const ControlParams& c = p.control;
  positive(where, "params.control.radius", c.radius);
  nonNegative(where, "params.control.attraction", c.attraction);
  nonNegative(where, "params.control.velocity", c.velocity);
  unitInterval(where, "params.control.feedback", c.feedback);
  unitInterval(where, "params.control.gravity_compensation", c.gravity_compensation);
  if (c.units != ControlForceUnits::Acceleration && c.units != ControlForceUnits::ForceDensity &&
      c.units != ControlForceUnits::Force)
    throw Error((where.empty() ? std::string() : where + ": ") +
                "params.control.units: must be acceleration, force_density or force");

  const ShapeMatchParams& s = p.shape;
  unitInterval(where, "params.shape_matching.stiffness", s.stiffness);
  positive(where, "params.shape_matching.time_step", s.time_step);
  atLeastOne(where, "params.shape_matching.cluster_stride", s.cluster_stride);
  atLeastOne(where, "params.shape_matching.cluster_half_width", s.cluster_half_width);
  atLeastOne(where, "params.shape_matching.rotation_iterations", s.rotation_iterations);
  unitInterval(where, "params.shape_matching.damping", s.damping);
}

}  // namespace ff
