// fluid_cpu.h - the OpenMP backend's fluid data and its SPH phase functions.
#pragma once
#include <vector>

#include "core/fluid_state.h"
#include "core/params.h"
#include "cpu/uniform_grid.h"
#include "scene/scene.h"

namespace ff {

struct CpuFluid {
  FluidState s;                   // sorted by grid cell after buildFluidGrid
  std::vector<float> rho, p;      // density, pressure
  std::vector<float> ax, ay, az;  // accelerations of this step
  UniformGrid grid;               // cell size h
  // True while `grid` indexes the current (unsorted) positions: the metrics
  // phase builds it after integration, and the next grid phase sorts by it
  // instead of building it again.
  bool grid_current = false;
  std::vector<float> scratch;
  std::vector<uint32_t> scratch_u;
  size_t size() const { return s.size(); }
};

// Phase "grid": counting sort by cell of size h (unless f.grid_current), then
// reorder every array.
void buildFluidGrid(CpuFluid& f, float h);

// Phase "density" (part of the WCSPH pressure solver): rho_i = sum_j m W_poly6
// + the analytic wall term, and p = k (rho - rho0).
void computeDensityPressure(CpuFluid& f, const FluidParams& p, const ContainerDesc& box);

// Pressure acceleration: symmetric pressure force / rho_i, plus the wall's.
void addPressureAccel(CpuFluid& f, const FluidParams& p, const ContainerDesc& box);

// Viscosity acceleration (Laplacian of the viscosity kernel) and gravity.
void addViscosityGravity(CpuFluid& f, const FluidParams& p);

// Phase "integrate": symplectic Euler, velocity limit, container.
void integrateFluid(CpuFluid& f, const FluidParams& p, const ContainerDesc& box, float dt);

}  // namespace ff
