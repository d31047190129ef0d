// fluid_cpu.h - the OpenMP backend's fluid data and its SPH phase functions.
#pragma once
#include <vector>

#include "core/fluid_state.h"
#include "core/params.h"
#include "grid/uniform_grid.h"
#include "scene/scene.h"

namespace ff {

struct CpuFluid {
  FluidState s;                   // sorted by grid cell after buildFluidGrid
  std::vector<float> rho, p;      // density, pressure
  std::vector<float> ax, ay, az;  // accelerations of this step
  UniformGrid grid;               // cell h, over the container
  // Groups of up to 8 consecutive particles in one row of grid cells (after
  // buildFluidGrid): the neighbour loops run a group's particles as 8 lanes.
  std::vector<uint32_t> groups;
  // True while `grid` indexes the current (unsorted) positions: the metrics
  // phase builds it after integration, and the next grid phase sorts by it
  // instead of building it again.
  bool grid_current = false;
  // True from the grid phase until the particles move: the arrays are sorted
  // by `grid` and its ranges index them directly.
  bool sorted = false;
  std::vector<float> scratch;
  std::vector<uint32_t> scratch_u;
  // Velocity clamps (ff_integrate_particle) since the metrics last took them.
  long velocity_clamps = 0;
  size_t size() const { return s.size(); }
  size_t memoryBytes() const;
};

// The fluid grid (cell h) over the container box: every particle is inside it.
void buildFluidIndex(CpuFluid& f, float h, const ContainerDesc& box);

// Phase "grid": counting sort by cell of size h (unless f.grid_current), then
// reorder every array.
void buildFluidGrid(CpuFluid& f, float h, const ContainerDesc& box);

// Phase "density" (part of the WCSPH pressure solver): rho_i = sum_j m W_poly6
// + the analytic wall term, and p = k (rho - rho0). False if a value is not finite.
bool computeDensityPressure(CpuFluid& f, const FluidParams& p, const ContainerDesc& box);

// Phase "forces" starts here: a = 0 (resized to the fluid); the non-pressure
// forces (src/cpu/forces/) then add to it.
void clearAccelerations(CpuFluid& f);

// Phase "pressure" of WCSPH: adds the symmetric pressure force / rho_i and the
// wall's mirrored pressure to a. False if a value is not finite.
bool addWcsphPressure(CpuFluid& f, const FluidParams& p, const ContainerDesc& box);

// Phase "integrate": symplectic Euler, velocity limit, container. False if a
// value is not finite.
bool integrateFluid(CpuFluid& f, const FluidParams& p, const ContainerDesc& box, float dt);

}  // namespace ff
