// backend_opencl.h - the OpenCL backend: every phase as kernels on one device
// (kernels/*.cl, built at start from the sources embedded in the binary).
// The particle data stays on the device for the whole run; it crosses to the
// host only for readFluid / readControl / readDensity, the metrics' partial
// sums and, once per step, the record of the first non-finite phase (one int).
// The grids span the container, so building one reads nothing back.
//
// Each phase mirrors the OpenMP backend's arithmetic and summation order
// (src/cpu/, src/control/, src/metrics/), with the shared formulas of
// kernels/common/, so both give the same numbers up to rounding.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "ff_rotation.h"
#include "host/cl_context.h"
#include "host/cl_kernel.h"
#include "host/device_grid.h"
#include "metrics/fluid_shares.h"
#include "metrics/iou.h"
#include "sim/backend.h"
#include "sim/nonfinite_log.h"

namespace ff {

class ClDfsphSolver;
class ClForce;
struct ClFluidRefs;

class OpenClBackend : public Backend {
 public:
  // device_index: position in listClDevices() order; < 0: the first GPU, else
  // the first device. Throws ff::Error (no platform, bad index, build log).
  explicit OpenClBackend(int device_index = -1);
  ~OpenClBackend() override;
  std::string name() const override { return "opencl"; }
  std::string device() const override;

  void init(const Params& params, const ContainerDesc& box, const FluidState& fluid) override;
  void setParams(const Params& params) override;
  void setControl(ControlSet set) override;
  void setMetricsTarget(const TargetShape* target) override;
  void setControlledFluid(std::vector<uint8_t> by_id) override;

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
  void setProfiling(bool on) override;
  std::vector<StageTime> takeStageMs() override;
  std::vector<std::string> forceNames() const override;
  HostSyncs hostSyncs() const override { return clHostSyncs(); }
  size_t memoryBytes() const override;

  void readFluid(FluidState& out) override;
  void readDensity(std::vector<float>& rho, std::vector<float>& pressure) override;
  void readControl(ControlSet& set, ControlFields& fields) override;

  // For tests and tools.
  const ClDeviceInfo& deviceInfo() const;
  void readAccel(std::vector<float>& ax, std::vector<float>& ay, std::vector<float>& az);
  void readGoals(std::vector<float>& gx, std::vector<float>& gy, std::vector<float>& gz);
  void readClusterRotations(std::vector<ff_quat>& q);
  // Cell h over the fluid (sorts it); control radius / FF_CONTROL_GRID_DIVISIONS over the control particles.
  enum class GridKind { Fluid, Control };
  struct GridSnapshot {
    GridGeom geom;
    std::vector<uint32_t> start, order;
  };
  GridSnapshot readGrid(GridKind kind);
  // The recapture's field of targets of the last control forces phase that
  // built it, i.e. that read it (sorted positions in the control grid's
  // order; empty if it never ran).
  std::vector<uint32_t> readRecaptureField();
  double shapeMatchingClock() const { return clock_; }
  // How the neighbour phases (density, forces, control forces) map particles
  // to work-items: one each (Scalar: for GPUs, which want many work-items) or
  // 8 as float8 lanes (Lanes: for CPU devices, which then vectorise as the
  // OpenMP backend). Auto (the default) picks by device type. The grid's
  // prefix scan follows (serial chunks with Lanes, work-group scans with
  // Scalar). The results are the same bit for bit.
  enum class KernelVariant { Auto, Scalar, Lanes };
  void setKernelVariant(KernelVariant v);
  bool usesLanes() const { return lanes_; }
  // The DFSPH solver when params.fluid.solver is "dfsph" (else null), for tests.
  const ClDfsphSolver* dfsph() const { return dfsph_.get(); }
  // Appends a non-pressure force after the registered ones (makeClForces),
  // e.g. a test's own force.
  void addForce(std::unique_ptr<ClForce> force);

  struct Impl;  // device buffers and kernels (host/backend_opencl_impl.h; the forces use them)
  const ClContext& context() const;

 private:
  int beginPhase(Phase p);  // returns the phase's non-finite tag
  void endPhase();          // waits for the phase's kernels when profiling
  void runShapeMatchStep(int tag);
  void uploadControl();
  // Runs f(force, context) for each force of phase `of`; while profiling,
  // times each as a stage of phase `timed_in`.
  template <class F>
  void runForces(Phase of, Phase timed_in, int tag, F&& f);

  ClFluidRefs fluidRefs();

  std::unique_ptr<Impl> d_;
  std::vector<std::unique_ptr<ClForce>> forces_;  // the non-pressure forces, in order
  std::vector<StageTime> stages_;                 // the forces' times (while profiling) since takeStageMs
  std::unique_ptr<ClDfsphSolver> dfsph_;          // params.fluid.solver "dfsph" (null: WCSPH)
  Params params_;
  ContainerDesc box_;
  size_t n_ = 0;        // fluid particles
  ControlSet control_;  // rest shape and clusters; positions and velocities live on the device
  size_t nc_ = 0, nclusters_ = 0;
  double clock_ = 0.0;  // shape-matching time not yet consumed
  const TargetShape* target_ = nullptr;
  long target_voxels_ = 0;
  long thin_voxels_ = 0;      // the target's thin voxels (metric filled_thin)
  float thin_radius_ = 0.0f;  // the control radius thin_voxels_ (bit 2 of `inside`) was found for
  bool masked_ = false;       // setControlledFluid gave a mask (else all the fluid is controlled)
  RigidFrame frame_;
  // The fluid h-grid: Stale after the positions change; Index when built over
  // the current positions without reordering (by the metrics, reused by the
  // next buildGrid); Sorted after buildGrid reordered the arrays by it.
  enum class GridState { Stale, Index, Sorted } grid_state_ = GridState::Stale;
  NonFiniteLog log_;
  bool profiling_ = false;
  bool lanes_ = false;  // the float8-lane kernels (KernelVariant)
};

}  // namespace ff
