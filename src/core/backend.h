// backend.h - the phase interface. A backend owns the particle data (on the
// host for the OpenMP backend, on the device for OpenCL) and runs each phase
// of a step on it. Simulation calls the phases in order and times them.
#pragma once
#include <string>
#include <vector>

#include "control/control_set.h"
#include "core/fluid_state.h"
#include "core/metrics.h"
#include "core/params.h"
#include "scene/scene.h"

namespace ff {

enum class Phase : int {
  Grid = 0,       // neighbour grid by counting sort + reorder by cell
  Density,        // density and pressure
  Forces,         // pressure, viscosity, wall boundary, gravity
  ControlScale,   // s_i of the control particles and the fluid velocity around them
  ControlForces,  // attraction and velocity forces on the fluid
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
  virtual std::string device() const = 0;  // e.g. "OpenMP, 2 threads"

  virtual void init(const Params& params, const ContainerDesc& box, const FluidState& fluid) = 0;
  virtual void setParams(const Params& params) = 0;
  // New control particles (an empty set switches control off).
  virtual void setControl(ControlSet set) = 0;
  // The target whose voxels the iou metric compares against (null: no iou).
  virtual void setMetricsTarget(const TargetShape* target) = 0;

  virtual void buildGrid() = 0;
  virtual void computeDensity() = 0;
  virtual void computeForces() = 0;
  virtual void computeControlScale() = 0;
  virtual void applyControlForces(float dt) = 0;
  virtual void integrate(float dt) = 0;
  virtual int shapeMatching(float dt) = 0;
  virtual StepMetrics computeMetrics() = 0;

  // True when every value the phase wrote is finite.
  virtual bool finiteAfter(Phase phase) = 0;

  // Copies of the state, in the backend's current (cell-sorted) order.
  virtual void readFluid(FluidState& out) = 0;
  virtual void readDensity(std::vector<float>& rho, std::vector<float>& pressure) = 0;
  virtual void readControl(ControlSet& set, ControlFields& fields) = 0;
};

}  // namespace ff
