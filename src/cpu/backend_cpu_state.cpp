// backend_cpu_state.cpp - the OpenMP backend's part of a checkpoint.
#include "cpu/backend_cpu.h"

namespace ff {

void CpuBackend::saveState(StateWriter& w) const {
  w.tag("CPUB");
  const FluidState& s = fluid_.s;
  for (const auto* a : {&s.x, &s.y, &s.z, &s.vx, &s.vy, &s.vz}) w.vec(*a);
  w.vec(s.id);
  w.str(solver_->name());
  solver_->saveState(w);
  controller_.saveState(w);
  w.pod(frame_);
}

void CpuBackend::loadState(StateReader& r) {
  r.tag("CPUB");
  FluidState s;
  for (auto* a : {&s.x, &s.y, &s.z, &s.vx, &s.vy, &s.vz}) r.vec(*a);
  r.vec(s.id);
  const size_t n = s.x.size();
  bool ok = n == fluid_.size();
  for (const auto* a : {&s.y, &s.z, &s.vx, &s.vy, &s.vz}) ok = ok && a->size() == n;
  ok = ok && s.id.size() == n;
  r.check(ok, "it holds " + std::to_string(n) + " fluid particles where the scene has " +
                  std::to_string(fluid_.size()));
  const std::string solver = r.str();
  r.check(solver == solver_->name(), "it was written with the pressure solver '" + solver +
                                         "', this run uses '" + solver_->name() + "'");
  solver_->loadState(r, n);
  controller_.loadState(r);
  const RigidFrame frame = r.pod<RigidFrame>();
  fluid_.s = std::move(s);
  // The grid is rebuilt from the positions by the next grid phase, exactly
  // as the metrics phase would have built it.
  fluid_.grid_current = false;
  fluid_.sorted = false;
  frame_ = frame;
}

}  // namespace ff
