// control.cpp - the control plug-in of the OpenMP backend: the Controller's
// density scale (eq. 5, in phase control_scale) and its forces on the fluid
// (eq. 4 and 6 and the gravity it carries, in phase control_forces), while
// control particles are active.
#include <memory>

#include "cpu/forces/cpu_force.h"

namespace ff {

namespace {

class CpuControl : public CpuForce {
 public:
  const char* name() const override { return "control"; }
  Phase phase() const override { return Phase::ControlForces; }
  bool prepare(CpuForceContext& c) override {
    return !c.controller.active() || c.controller.computeScale(c.view);
  }
  bool apply(CpuForceContext& c, float dt) override {
    CpuFluid& f = c.fluid;
    return !c.controller.active() ||
           c.controller.addForces(c.view, dt, f.ax.data(), f.ay.data(), f.az.data());
  }
};

}  // namespace

std::unique_ptr<CpuForce> makeCpuControl() {
  return std::make_unique<CpuControl>();
}

}  // namespace ff
