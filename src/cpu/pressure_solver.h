// pressure_solver.h - the pressure solver sits behind this interface, so that
// an iterative solver (DFSPH, PBF) can replace WCSPH without touching the
// control code or the other phases.
#pragma once
#include <memory>
#include <string>

#include "cpu/fluid_cpu.h"

namespace ff {

class PressureSolver {
 public:
  virtual ~PressureSolver() = default;
  virtual std::string name() const = 0;
  // Density (and pressure) from the current positions. False if a value is not finite.
  virtual bool computeDensity(CpuFluid& f, const FluidParams& p, const ContainerDesc& box) = 0;
  // Sets the accelerations for a step of length dt: pressure, viscosity and
  // gravity. False if a value is not finite.
  virtual bool computeForces(CpuFluid& f, const FluidParams& p, const ContainerDesc& box, float dt) = 0;
};

// Weakly compressible SPH with p = k (rho - rho0) (Mueller et al. 2003).
class WcsphSolver : public PressureSolver {
 public:
  std::string name() const override { return "wcsph"; }
  bool computeDensity(CpuFluid& f, const FluidParams& p, const ContainerDesc& box) override {
    return computeDensityPressure(f, p, box);
  }
  bool computeForces(CpuFluid& f, const FluidParams& p, const ContainerDesc& box, float) override {
    return computeWcsphForces(f, p, box);
  }
};

}  // namespace ff
