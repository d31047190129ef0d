// controller.h - the separable fluid controller: control particles (eq. 4-6)
// driven by cluster shape matching (eq. 7-9), with fluid feedback.
//
// It knows nothing of SPH: it reads spans of fluid positions and velocities
// and returns accelerations, so any particle fluid can embed it (the paper's
// "easy to embed" claim). The OpenMP backend uses it for its control phases.
#pragma once
#include <cstddef>
#include <vector>

#include "control/control_set.h"
#include "core/params.h"
#include "cpu/uniform_grid.h"
#include "ff_rotation.h"

namespace ff {

struct FluidView {
  size_t n = 0;
  const float *x = nullptr, *y = nullptr, *z = nullptr;
  const float *vx = nullptr, *vy = nullptr, *vz = nullptr;
  float volume = 0.0f;         // V_e of eq. 5: the rest volume of one particle
  const float* rho = nullptr;  // per-particle density; only read with ControlForceUnits::ForceDensity
  float rest_density = 1.0f;   // used instead of rho when rho is null
  float mass = 1.0f;           // particle mass; only read with ControlForceUnits::Force
  float gravity[3] = {0.0f, 0.0f, 0.0f};  // the host solver's gravity (for gravity compensation)
};

class Controller {
 public:
  void setParams(const ControlParams& cp, const ShapeMatchParams& sm) { cp_ = cp, sm_ = sm; }
  // Control particles are kept inside this box (the container), if set.
  void setBounds(const float lo[3], const float hi[3]);
  // New control particles (a new target or region). Restarts the shape-matching clock.
  void reset(ControlSet set);
  void clear() { reset(ControlSet()); }
  bool active() const { return set_.size() > 0; }

  // Phase "control scale": s_i (eq. 5) and the fluid velocity around each
  // control particle, for the feedback.
  void computeScale(const FluidView& f);
  // Phase "control forces": adds the accelerations of eq. 4 and eq. 6 to a*.
  // Eq. 6 is integrated implicitly over dt (see ff_velocity_force_implicit).
  void addForces(const FluidView& f, float dt, float* ax, float* ay, float* az);
  // Phase "shape matching": advances the control particles' own clock by dt and
  // runs the shape-matching steps that fall due. Returns how many ran.
  int advance(float dt);
  // One shape-matching step of sm.time_step: feedback, eq. 7-9, integration.
  void shapeMatchStep();

  // All three phases for one fluid step; for embedding in another solver.
  void step(const FluidView& f, float dt, float* ax, float* ay, float* az);

  const ControlSet& set() const { return set_; }
  const ControlFields& fields() const { return fields_; }
  const std::vector<ff_quat>& clusterRotations() const { return q_; }
  const std::vector<float>& goalX() const { return gx_; }
  const std::vector<float>& goalY() const { return gy_; }
  const std::vector<float>& goalZ() const { return gz_; }
  double clock() const { return clock_; }

 private:
  ControlParams cp_;
  ShapeMatchParams sm_;
  ControlSet set_;
  ControlFields fields_;
  bool bounded_ = false;
  float lo_[3] = {0, 0, 0}, hi_[3] = {0, 0, 0};
  double clock_ = 0.0;  // time not yet consumed by shape-matching steps
  UniformGrid cp_grid_, fluid_grid_;
  std::vector<float> sx_, sy_, sz_, ss_, svx_, svy_, svz_;  // control particles in cp_grid_ order
  std::vector<ff_quat> q_;
  std::vector<float> cx_, cy_, cz_, gx_, gy_, gz_, cvx_, cvy_, cvz_;
};

}  // namespace ff
