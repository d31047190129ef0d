// voxel_size_search.cpp - the control_count -> voxel size search.
#include "target/voxel_size_search.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "core/error.h"

namespace ff {

VoxelGrid searchVoxelSize(int count, double tolerance, double volume, const Voxelizer& voxelize,
                          const std::string& context) {
  const double wanted = double(count);
  const double band = tolerance * wanted;
  // Shifts break the symmetry of centred grids (a centred sphere gains or
  // loses voxels 8 or 48 at a time).
  const Vec3 shifts[] = {Vec3(0.0f, 0.0f, 0.0f), Vec3(0.31f, 0.17f, 0.43f), Vec3(-0.23f, 0.37f, -0.11f),
                         Vec3(0.13f, -0.41f, 0.29f), Vec3(0.5f, 0.5f, 0.5f)};
  long best_count = -1;
  double best_voxel = 0.0;
  double start = std::cbrt(volume / wanted);
  for (const Vec3& shift : shifts) {
    double voxel = start;
    double over = 0.0;   // a voxel size giving more voxels than wanted (0: none yet)
    double under = 0.0;  // ... fewer than wanted (0: none yet)
    for (int iteration = 0; iteration < 60; ++iteration) {
      VoxelGrid grid = voxelize(float(voxel), shift);
      const long got = long(grid.countInside());
      if (best_count < 0 || std::abs(double(got) - wanted) < std::abs(double(best_count) - wanted)) {
        best_count = got;
        best_voxel = voxel;
      }
      if (std::abs(double(got) - wanted) <= band) return grid;
      (double(got) > wanted ? over : under) = voxel;
      double next = got > 0 ? voxel * std::cbrt(double(got) / wanted) : 0.5 * voxel;
      if (over > 0.0 && under > 0.0) {
        const bool inside_bracket = (next - over) * (next - under) < 0.0;
        if (!inside_bracket || iteration >= 6) next = 0.5 * (over + under);
        if (std::abs(over - under) <= 1e-6 * voxel) break;  // a jump across the whole band
      }
      if (float(next) == float(voxel)) break;
      voxel = next;
    }
    start = best_voxel;
  }
  std::ostringstream msg;
  msg << context << ": could not find a voxel size giving " << count << " inside voxels (within "
      << tolerance * 100.0 << "%); the closest was " << best_count << " at voxel size " << best_voxel;
  throw Error(msg.str());
}

}  // namespace ff
