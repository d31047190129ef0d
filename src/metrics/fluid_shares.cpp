#include "metrics/fluid_shares.h"

#include "ff_metrics.h"
#include "parallel/parallel_grain.h"
#include "target/local_thickness.h"

namespace ff {

FluidShares fluidShares(const TargetShape& target, const RigidFrame& frame, int pad, const float* x,
                        const float* y, const float* z, const uint32_t* id, size_t n,
                        const uint8_t* controlled_by_id, const uint8_t* reached) {
  const VoxelGrid& g = target.grid;
  const ff_mat3 r = ff_quat_to_mat3(frame.q);
  const ff_float3 c = FF_F3(frame.c[0], frame.c[1], frame.c[2]);
  const ff_float3 rest_c = FF_F3(frame.rest_c[0], frame.rest_c[1], frame.rest_c[2]);
  const ff_float3 o = FF_F3(g.origin.x(), g.origin.y(), g.origin.z());
  long controlled = 0, captured = 0, stray = 0, far = 0;
#pragma omp parallel for schedule(static) reduction(+ : controlled, captured, stray, far) \
    if (long(n) > kParallelLightLoop)
  for (long i = 0; i < long(n); ++i) {
    const ff_voxel v = ff_target_voxel_of(r, c, rest_c, o, g.voxel, FF_F3(x[i], y[i], z[i]));
    far += ff_voxel_in_padded(v, g.nx, g.ny, g.nz, pad) ? 0 : 1;
    if (controlled_by_id && !controlled_by_id[id[i]]) continue;
    ++controlled;
    const int k = ff_voxel_index(v, g.nx, g.ny, g.nz);
    captured += k >= 0 && g.inside[size_t(k)] ? 1 : 0;
    stray += reached && reached[i] ? 0 : 1;
  }
  FluidShares s;
  s.controlled = controlled, s.captured = captured, s.stray = stray, s.far = far;
  return s;
}

void setShapeMetrics(StepMetrics& m, const IouCounts& c, const FluidShares& s, long target_voxels,
                     double particle_voxels, long thin_voxels) {
  const double uni = double(c.uni) + double(s.far) * particle_voxels;
  m.iou = uni > 0.0 ? double(c.inter) / uni : 0.0;
  m.filled = target_voxels > 0 ? double(c.inter) / double(target_voxels) : 0.0;
  m.captured = s.controlled > 0 ? double(s.captured) / double(s.controlled) : 0.0;
  m.stray = s.controlled > 0 ? double(s.stray) / double(s.controlled) : 0.0;
  m.filled_thin = thin_voxels > 0 ? double(c.inter_thin) / double(thin_voxels) : 1.0;
}

long targetVoxelCount(const TargetShape& target) {
  long k = 0;
  for (uint8_t v : target.grid.inside) k += v ? 1 : 0;
  return k;
}

ThinVoxels metricsThinVoxels(const TargetShape& target, float radius) {
  ThinVoxels t;
  t.thin = thinVoxels(target.grid, radius);
  for (uint8_t v : t.thin) t.count += v ? 1 : 0;
  return t;
}

}  // namespace ff
