// backend.h - the phase interface. A backend owns the particle data (on the
// host for the OpenMP backend, on the device for OpenCL) and runs each phase
// of a step on it. Simulation calls the phases in order and times them.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "control/control_set.h"
#include "core/fluid_state.h"
#include "core/metrics.h"
#include "core/params.h"
#include "core/stage_time.h"
#include "core/state_io.h"
#include "scene/scene.h"

namespace ff {

enum class Phase : int {
  Grid = 0,       // neighbour grid by counting sort + reorder by cell
  Density,        // density and pressure
  Forces,         // non-pressure forces (plug-ins): gravity, viscosity
  ControlScale,   // the forces' preparation: the control's s_i and the fluid velocity around it
  ControlForces,  // the control's plug-in: attraction and velocity forces on the fluid
  Pressure,       // the pressure solver named by params.fluid.solver (sees all the above)
  Integrate,      // fluid integration (symplectic Euler, container)
  ShapeMatching,  // clusters, goals, control-particle integration
  Metrics,        // iou, coverage, max speed, density error
  Count
};
const char* phaseName(Phase p);

class Backend {
 public:
  virtual ~Backend() = default;
  virtual std::string name() const = 0;    // "cpu", "opencl"
  virtual std::string device() const = 0;  // e.g. "OpenMP, 2 threads, avx512"

  virtual void init(const Params& params, const ContainerDesc& box, const FluidState& fluid) = 0;
  virtual void setParams(const Params& params) = 0;
  // New control particles (an empty set switches control off).
  virtual void setControl(ControlSet set) = 0;
  // The target whose voxels the iou metric compares against (null: no iou).
  virtual void setMetricsTarget(const TargetShape* target) = 0;
  // The fluid the control shapes, for the metrics captured and stray: a flag
  // per particle id (empty: all the fluid).
  virtual void setControlledFluid(std::vector<uint8_t> by_id) = 0;

  virtual void buildGrid() = 0;
  virtual void computeDensity() = 0;
  // The non-pressure forces, plug-ins that each backend registers in one list
  // (src/cpu/forces/cpu_forces.cpp, host/forces/cl_forces.cpp): gravity,
  // viscosity, control. computeForces sets a = 0, then every force of phase
  // Forces adds its acceleration over a substep of dt (0: the accelerations
  // only, as the phase tests ask; no default, since a default argument on a
  // virtual function binds by the static type) in the list's order; computeControlScale
  // and applyControlForces run the preparation (the control's density scale)
  // and then the accelerations of the forces of phase ControlForces (the control).
  virtual void computeForces(float dt) = 0;
  virtual void computeControlScale() = 0;
  virtual void applyControlForces(float dt) = 0;
  // The registered non-pressure forces' names, in the order they run.
  virtual std::vector<std::string> forceNames() const = 0;
  // The pressure solve for a substep of dt: adds the pressure accelerations to
  // a, after every other acceleration, so an incompressible solver sees them.
  virtual void solvePressure(float dt) = 0;
  virtual void integrate(float dt) = 0;
  virtual int shapeMatching(float dt) = 0;
  // The metrics of the current state. Without `with_shape`, the columns that
  // measure the fluid against the target (StepMetrics::copyShapeMetrics lists
  // them) are left 0 and not computed: the step's substeps and NaN check need
  // only the fluid's. The best rigid fit is still advanced (it is
  // warm-started from the last step's), so the next step with them gives the
  // same values as if every step had computed them.
  virtual StepMetrics computeMetrics(bool with_shape) = 0;
  StepMetrics computeMetrics() { return computeMetrics(true); }

  // The first phase, since the last call, that wrote a NaN or Inf (Phase::Count
  // when none did), and the substep it ran in (0-based, counted in `substep`
  // when not null); clears the record. The phases check their own outputs as
  // they write them; the OpenCL backend reads this back once per call (one int),
  // so Simulation asks once per step.
  virtual Phase firstNonFinite(int* substep = nullptr) = 0;

  // Profiling: when on, every phase waits for its work to finish,
  // so that timing a phase call measures the phase. When off, an OpenCL phase
  // only enqueues its kernels and the device's time is counted by whichever
  // later call waits for results (the metrics phase, which reads its sums back).
  // The OpenMP backend always runs a phase to completion. Off by default
  // (flowform bench and `run --profile` switch it on).
  virtual void setProfiling(bool on) { (void)on; }
  // The named stages timed inside phases since the last call: each
  // non-pressure force and a pressure solver's stages (on OpenCL only while
  // profiling).
  virtual std::vector<StageTime> takeStageMs() { return {}; }

  // Host synchronisations so far: blocking reads of device memory and waits
  // for the device's queue to finish (the OpenMP backend has none).
  struct HostSyncs {
    long reads = 0, waits = 0;
  };
  virtual HostSyncs hostSyncs() const { return {}; }

  // Bytes the backend holds for the run: every particle array, grid, control
  // and metrics buffer (capacity, on the host for the OpenMP backend, on the
  // device for OpenCL), not code or the OpenCL runtime's own memory.
  virtual size_t memoryBytes() const = 0;

  // Checkpoints: everything of the backend that a step depends on and that
  // init() and the scene do not give again (particles in their current order,
  // control particles, the shape-matching clock, warm starts such as cluster
  // rotations, and a pressure solver's per-particle state). loadState() comes
  // after init() with the same scene and restores the state bit for bit. The
  // default refuses with a clear ff::Error (a backend that cannot yet).
  virtual void saveState(StateWriter& w) const;
  virtual void loadState(StateReader& r);
  // Whether saveState() works (false: it throws), so that a run can say so
  // before it starts rather than at its first checkpoint or at SIGTERM.
  virtual bool writesCheckpoints() const { return false; }

  // Copies of the state, in the backend's current (cell-sorted) order.
  virtual void readFluid(FluidState& out) = 0;
  virtual void readDensity(std::vector<float>& rho, std::vector<float>& pressure) = 0;
  virtual void readControl(ControlSet& set, ControlFields& fields) = 0;
};

}  // namespace ff
