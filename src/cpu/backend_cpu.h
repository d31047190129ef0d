// backend_cpu.h - the OpenMP reference backend: every phase on the host.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "control/controller.h"
#include "cpu/fluid_cpu.h"
#include "cpu/forces/cpu_force.h"
#include "cpu/pressure_solver.h"
#include "metrics/fluid_shares.h"
#include "metrics/iou.h"
#include "sim/backend.h"
#include "sim/nonfinite_log.h"

namespace ff {

class CpuBackend : public Backend {
 public:
  explicit CpuBackend(int threads = 0);  // 0: OpenMP's default
  std::string name() const override { return "cpu"; }
  std::string device() const override;

  void init(const Params& params, const ContainerDesc& box, const FluidState& fluid) override;
  void setParams(const Params& params) override;
  void setControl(ControlSet set) override;
  void setMetricsTarget(const TargetShape* target) override;
  void setControlledFluid(std::vector<uint8_t> by_id) override { controlled_by_id_ = std::move(by_id); }

  void buildGrid() override;
  void computeDensity() override;
  void computeForces(float dt) override;
  void computeControlScale() override;
  void applyControlForces(float dt) override;
  void solvePressure(float dt) override;
  void integrate(float dt) override;
  int shapeMatching(float dt) override;
  using Backend::computeMetrics;
  StepMetrics computeMetrics(bool with_shape) override;
  Phase firstNonFinite(int* substep = nullptr) override;
  size_t memoryBytes() const override;
  std::vector<StageTime> takeStageMs() override;
  std::vector<std::string> forceNames() const override;

  void saveState(StateWriter& w) const override;
  void loadState(StateReader& r) override;
  bool writesCheckpoints() const override { return true; }

  void readFluid(FluidState& out) override { out = fluid_.s; }
  void readDensity(std::vector<float>& rho, std::vector<float>& p) override {
    rho = fluid_.rho, p = fluid_.p;
  }
  void readControl(ControlSet& set, ControlFields& fields) override {
    set = controller_.set(), fields = controller_.fields();
  }

  // Direct access for tests and tools.
  CpuFluid& fluid() { return fluid_; }
  Controller& controller() { return controller_; }
  PressureSolver& solver() { return *solver_; }
  // Appends a non-pressure force after the registered ones (makeCpuForces),
  // e.g. a test's own force.
  void addForce(std::unique_ptr<CpuForce> force) { forces_.push_back(std::move(force)); }

 private:
  FluidView view() const;
  // Runs f(force, context) for each force of phase `of`, timing each as a
  // stage of phase `timed_in`. False if one of them returned false.
  template <class F>
  bool runForces(Phase of, Phase timed_in, F&& f);
  int threads_;
  Params params_;
  ContainerDesc box_;
  CpuFluid fluid_;
  std::unique_ptr<PressureSolver> solver_;
  std::vector<std::unique_ptr<CpuForce>> forces_;  // the non-pressure forces, in order
  std::vector<StageTime> stages_;                  // the forces' times since takeStageMs
  Controller controller_;
  const TargetShape* target_ = nullptr;
  long target_voxels_ = 0;
  ThinVoxels thin_;           // the target's thin voxels (metric filled_thin)
  float thin_radius_ = 0.0f;  // the control radius thin_ was found for
  std::vector<uint8_t> controlled_by_id_;
  RigidFrame frame_;
  NonFiniteLog log_;
};

}  // namespace ff
