// fluid_shares.h - where the fluid lies relative to the target and to the
// control particles: the counts behind the metrics `captured`, `stray` and the
// iou's fluid outside the target's padded grid (docs/METRICS.md).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/metrics.h"
#include "metrics/iou.h"
#include "target/target_shape.h"

namespace ff {

struct FluidShares {
  long controlled = 0;  // controlled fluid particles
  long captured = 0;    // ... whose position lies in a target voxel at the frame
  long stray = 0;       // ... that no control particle reached (reached[i] == 0)
  long far = 0;         // fluid particles (all of them) outside the target grid padded by `pad` voxels
};

// Counts over the n fluid particles (x, y, z, id). controlled_by_id[id] != 0
// marks the controlled fluid (null: all of it); reached[i] != 0 where particle
// i had a control particle within the control radius (null: none had).
FluidShares fluidShares(const TargetShape& target, const RigidFrame& frame, int pad, const float* x,
                        const float* y, const float* z, const uint32_t* id, size_t n,
                        const uint8_t* controlled_by_id, const uint8_t* reached);

// Sets m.iou, m.filled, m.captured, m.stray and m.filled_thin from the voxel
// counts of the padded grid, the fluid shares, the target's voxel count, the
// rest volume of one fluid particle in voxels (the far fluid counts by its
// volume) and the target's thin voxel count (0: filled_thin is 1).
void setShapeMetrics(StepMetrics& m, const IouCounts& c, const FluidShares& s, long target_voxels,
                     double particle_voxels, long thin_voxels);

// The rest volume of one fluid particle, in voxels of the target's grid.
inline double particleVoxels(float rest_volume, const TargetShape& target) {
  const double v = target.grid.voxel;
  return double(rest_volume) / (v * v * v);
}

// The number of voxels inside the target.
long targetVoxelCount(const TargetShape& target);

// The metrics' thin voxels of the target (thinVoxels below the control
// radius `radius`) and their count.
struct ThinVoxels {
  std::vector<uint8_t> thin;  // per voxel of the target's grid, grid index order
  long count = 0;
};
ThinVoxels metricsThinVoxels(const TargetShape& target, float radius);

}  // namespace ff
