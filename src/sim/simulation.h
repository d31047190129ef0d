// simulation.h - one run: a scene, a backend, the target schedule, the step
// loop with its per-phase timings, and target changes at any moment.
#pragma once
#include <array>
#include <memory>
#include <string>

#include "core/metrics.h"
#include "core/state_io.h"
#include "scene/scene.h"
#include "sim/backend.h"
#include "target/target_shape.h"

namespace ff {

class Simulation {
 public:
  Simulation(SceneDesc scene, std::unique_ptr<Backend> backend);

  // Resumes a saved run: `scene` as saved (readSceneState), then the rest of
  // the state that saveState() wrote. Throws ff::Error naming r.source().
  Simulation(SceneDesc scene, std::unique_ptr<Backend> backend, StateReader& r);
  // Everything a step depends on beyond the scene: step, time, the last
  // metrics (they set the next step's substeps), the schedule position, the
  // current target and region, and the backend's state.
  void saveState(StateWriter& w) const;

  // One fluid time step (and the shape-matching steps that fall due in it).
  // Throws ff::Error naming the step and the phase if a value becomes NaN/Inf.
  void step();

  // Changes the target now: new control particles from the current fluid
  // region, nothing precomputed beyond voxelising the shape (cached). With a
  // target active and the recapture on, the controlled fluid stays the same
  // particles and the new shape holds all of them.
  void setTarget(const TargetSpec& spec) { makeTarget(spec, false); }
  // Switches control off.
  void clearTarget();
  // Changes the controlled region; the current target is regenerated in it.
  void setRegion(const RegionDesc& region);
  // Changes parameters live. A change of the clusters
  // (ShapeMatchParams::sameClusters) or of adaptive control
  // (ControlParams::samePlacement) re-places the control particles over the
  // current fluid, as a change to the same target does.
  void setParams(const Params& params);

  const SceneDesc& scene() const { return scene_; }
  Backend& backend() { return *backend_; }
  const StepMetrics& metrics() const { return metrics_; }
  long stepCount() const { return step_; }
  // The fluid's simulated time (s): whole frame steps, ahead of them by less
  // than a substep where substeps carry over the frame (fluid.substep_carry).
  double time() const { return time_; }
  // The frame clock (s): the frame steps taken, time() less the lead.
  double frameTime() const { return time_ - lead_; }
  const TargetShape* target() const { return target_; }
  size_t targetCacheSize() const { return cache_.size(); }
  size_t targetVoxelisations() const { return cache_.voxelisations(); }
  long controlledCount() const { return controlled_; }

  // Profiling: every phase waits for its work, so phaseMs() times each phase.
  // Off (the default): an OpenCL phase only enqueues its kernels, and the
  // device time is counted in the phase that next waits for results (the
  // metrics phase: the total stays right, the split does not).
  void setProfiling(bool on) { backend_->setProfiling(on); }

  // Metrics every k-th step (k >= 1; 1, the default: every step), and in the
  // next step after requestMetrics(). Steps without metrics read nothing back
  // from an OpenCL device: no iou, and the NaN/Inf check waits for the next
  // step with metrics (it then names the phase and the range of steps). The
  // CFL substep count uses the latest metrics.
  void setMetricsEvery(int k) { metrics_every_ = k < 1 ? 1 : k; }
  void requestMetrics() { metrics_requested_ = true; }
  // Whether the last step computed metrics() (else they are from an earlier step).
  bool metricsFresh() const { return metrics_fresh_; }
  // With `on`, a step computes the metrics that measure the fluid against the
  // target (StepMetrics::copyShapeMetrics lists them) only after
  // requestMetrics(); the others keep the values of the last step that
  // computed them. The physics is the same: the substeps and the NaN check
  // read only the fluid's metrics (Backend::computeMetrics). Off (the
  // default): every step with metrics computes them all.
  void setShapeMetricsOnRequest(bool on) { shape_on_request_ = on; }

  // Accumulated milliseconds per phase and the number of steps they cover.
  const std::array<double, size_t(Phase::Count)>& phaseMs() const { return phase_ms_; }
  // Milliseconds per phase of the last step alone (all its substeps).
  const std::array<double, size_t(Phase::Count)>& lastStepMs() const { return last_step_ms_; }
  // The named stages inside phases (Backend::takeStageMs), accumulated and of the last step.
  const std::vector<StageTime>& stageMs() const { return stage_ms_; }
  const std::vector<StageTime>& lastStepStageMs() const { return last_stage_ms_; }

  // The fluid of a scene, block by block, on cubic lattices.
  static FluidState makeFluid(const SceneDesc& scene);

 private:
  // setTarget; with `reselect`, the controlled fluid is chosen again from the region.
  void makeTarget(const TargetSpec& spec, bool reselect);
  // params with the control radius of control particles `voxel` apart
  // (ControlParams::radiusFor); params as they are for voxel 0 (no target).
  static Params withControlRadius(Params params, float voxel);
  // The rest volume of all the scene's fluid (its particles times m / rho0).
  double sceneFluidVolume() const;
  void applySchedule();
  template <class F>
  void timed(Phase p, F&& f);
  // Throws ff::Error naming the phase (and substep) that first wrote a NaN or Inf.
  void check(long step, double time, int substeps);
  int metrics_every_ = 1;
  bool metrics_requested_ = false, metrics_fresh_ = false;
  bool shape_on_request_ = false;
  long unchecked_from_ = 0;  // the first step not yet checked for NaN/Inf

  SceneDesc scene_;
  std::unique_ptr<Backend> backend_;
  TargetCache cache_;
  const TargetShape* target_ = nullptr;
  TargetSpec target_spec_;
  bool has_target_ = false;
  size_t next_schedule_ = 0;
  double target_volume_ = 0.0;  // the rest volume the current target was scaled to
  long step_ = 0;
  long controlled_ = 0;
  std::vector<uint8_t> controlled_by_id_;  // the controlled fluid by particle id (empty: all of it)
  double time_ = 0.0;                      // the fluid's clock (s)
  double lead_ = 0.0;                      // how far it runs ahead of the frame clock (fluid.substep_carry)
  StepMetrics metrics_;
  std::array<double, size_t(Phase::Count)> phase_ms_{};
  std::array<double, size_t(Phase::Count)> last_step_ms_{};
  std::vector<StageTime> stage_ms_, last_stage_ms_;
};

}  // namespace ff
