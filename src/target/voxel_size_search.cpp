// voxel_size_search.cpp - the control_count -> voxel size search.
#include "target/voxel_size_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/error.h"

namespace ff {

namespace {
// Shifts break the symmetry of centred grids (a centred sphere gains or
// loses voxels 8 or 48 at a time).
const Vec3 kShifts[] = {Vec3(0.0f, 0.0f, 0.0f), Vec3(0.31f, 0.17f, 0.43f), Vec3(-0.23f, 0.37f, -0.11f),
                        Vec3(0.13f, -0.41f, 0.29f), Vec3(0.5f, 0.5f, 0.5f)};
}  // namespace

VoxelGrid searchVoxelSize(int count, double tolerance, double volume, const Voxelizer& voxelize,
                          const std::string& context) {
  const double wanted = double(count);
  const double band = tolerance * wanted;
  // Within the band, keep refining (a few cheap voxelisations) until this close.
  const double aim = std::max(1.0, 0.005 * wanted);
  VoxelGrid best;
  double best_error = std::numeric_limits<double>::infinity();
  double best_voxel = 0.0;
  double start = std::cbrt(volume / wanted);
  for (const Vec3& shift : kShifts) {
    double voxel = start;
    double over = 0.0;   // a voxel size giving more voxels than wanted (0: none yet)
    double under = 0.0;  // ... fewer than wanted (0: none yet)
    for (int iteration = 0; iteration < 40; ++iteration) {
      VoxelGrid grid = voxelize(float(voxel), shift);
      const double got = double(grid.countInside());
      const double error = std::abs(got - wanted);
      if (error < best_error) {
        best_error = error;
        best_voxel = voxel;
        best = std::move(grid);
      }
      if (best_error <= aim) return best;
      (got > wanted ? over : under) = voxel;
      // Model: count ~ volume / voxel^3; bisection once bracketed and the model stalls.
      double next = got > 0.0 ? voxel * std::cbrt(got / wanted) : 0.5 * voxel;
      if (over > 0.0 && under > 0.0) {
        const bool inside_bracket = (next - over) * (next - under) < 0.0;
        if (!inside_bracket || iteration >= 6) next = 0.5 * (over + under);
        if (std::abs(over - under) <= 1e-6 * voxel) break;  // the count jumps across the aim here
      }
      if (float(next) == float(voxel)) break;
      voxel = next;
    }
    if (best_error <= band) return best;
    start = best_voxel;
  }
  std::ostringstream msg;
  msg << context << ": could not find a voxel size giving " << count << " inside voxels (within "
      << tolerance * 100.0 << "%); the closest was " << long(best.countInside()) << " at voxel size "
      << best_voxel;
  throw Error(msg.str());
}

VoxelGrid searchVoxelVolume(float voxel, double volume, double tolerance, const Voxelizer& voxelize) {
  const double lo = double(voxel) / 1.25, hi = double(voxel) * 1.25;
  VoxelGrid best;
  double best_error = std::numeric_limits<double>::infinity();
  for (const Vec3& shift : kShifts) {
    double v = voxel;
    for (int iteration = 0; iteration < 6; ++iteration) {
      VoxelGrid grid = voxelize(float(v), shift);
      const double count = double(grid.countInside());
      const double held = count * double(grid.voxel) * grid.voxel * grid.voxel;
      const double error = std::abs(held - volume) / volume;
      if (error < best_error) best_error = error, best = std::move(grid);
      if (best_error <= tolerance || count == 0.0) break;
      const double next = std::clamp(std::cbrt(volume / count), lo, hi);
      if (float(next) == float(v)) break;
      v = next;
    }
    if (best_error <= tolerance) break;
  }
  return best;
}

}  // namespace ff
