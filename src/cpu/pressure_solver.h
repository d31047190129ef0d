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
  // Density (and pressure) from the current positions.
  virtual void computeDensity(CpuFluid& f, const FluidParams& p, const ContainerDesc& box) = 0;
  // Adds the pressure acceleration for a step of length dt.
  virtual void addPressure(CpuFluid& f, const FluidParams& p, const ContainerDesc& box, float dt) = 0;
};

// Weakly compressible SPH with p = k (rho - rho0) (Mueller et al. 2003).
class WcsphSolver : public PressureSolver {
 public:
  std::string name() const override { return "wcsph"; }
  void computeDensity(CpuFluid& f, const FluidParams& p, const ContainerDesc& box) override {
    computeDensityPressure(f, p, box);
  }
  void addPressure(CpuFluid& f, const FluidParams& p, const ContainerDesc& box, float) override {
    addPressureAccel(f, p, box);
  }
};

}  // namespace ff
