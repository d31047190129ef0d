// pressure_solver.h - the OpenMP backend's pressure solvers, chosen by name
// (params.fluid.solver). Each owns its per-particle arrays. A solver computes
// the density phase (it may need more than rho there) and the pressure phase,
// which adds the pressure accelerations to f.ax/ay/az after every other
// acceleration of the substep, so an incompressible solver sees them.
#pragma once
#include <memory>
#include <string>

#include "core/stage_time.h"
#include "core/state_io.h"
#include "cpu/fluid_cpu.h"
#include "cpu/neighbour_cache.h"

namespace ff {

// What the solves of the substeps since the last take() did.
struct SolverStats {
  long iterations = 0;  // over every solve
  long capped = 0;      // solves that stopped at max_iterations
};

class PressureSolver {
 public:
  virtual ~PressureSolver() = default;
  virtual std::string name() const = 0;
  // Phase "density": rho (and what the solver keeps per particle) from the
  // current positions. False if a value is not finite.
  virtual bool computeDensity(CpuFluid& f, const FluidParams& p, const ContainerDesc& box) = 0;
  // Phase "pressure" for a substep of dt: adds the pressure accelerations to
  // f.ax/ay/az and sets f.p. False if a value is not finite.
  virtual bool solve(CpuFluid& f, const FluidParams& p, const ContainerDesc& box, float dt) = 0;
  // The grid phase reordered the particles by `order` (new k = old order[k]).
  virtual void reorder(const std::vector<uint32_t>& order) { (void)order; }
  virtual size_t memoryBytes() const { return 0; }
  // The neighbour lists the density phase built for the particles' current
  // order (null if it built none, or the grid phase reordered since). The
  // backend passes them on only while the particles have not moved since
  // (CpuFluid::sorted).
  virtual const NeighbourCache* neighbours() const { return nullptr; }
  // The state a resumed run needs to stay bit-identical (warm starts); `n`
  // is the fluid's particle count.
  virtual void saveState(StateWriter& w) const { (void)w; }
  virtual void loadState(StateReader& r, size_t n) { (void)r, (void)n; }
  SolverStats take() {
    SolverStats s = stats_;
    stats_ = SolverStats();
    return s;
  }
  // The named stages' times since the last call (Backend::takeStageMs).
  std::vector<StageTime> takeStages() {
    std::vector<StageTime> s;
    s.swap(stages_);
    return s;
  }

 protected:
  SolverStats stats_;
  std::vector<StageTime> stages_;
};

// Weakly compressible SPH with p = k (rho - rho0) (Mueller et al. 2003).
class WcsphSolver : public PressureSolver {
 public:
  std::string name() const override { return "wcsph"; }
  bool computeDensity(CpuFluid& f, const FluidParams& p, const ContainerDesc& box) override {
    return computeDensityPressure(f, p, box);
  }
  bool solve(CpuFluid& f, const FluidParams& p, const ContainerDesc& box, float) override {
    return addWcsphPressure(f, p, box);
  }
};

// The OpenMP implementation of a solver.
std::unique_ptr<PressureSolver> makeCpuPressureSolver(PressureSolverKind kind);

}  // namespace ff
