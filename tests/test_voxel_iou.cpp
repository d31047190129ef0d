// test_voxel_iou.cpp - the metrics' voxel iou (src/metrics/iou.cpp), which
// walks runs of 8 voxels as lanes and stops a run's walk once every voxel in
// it is filled, against the definition evaluated plainly: every voxel's density
// summed over all particles in the grid's sorted order (the order, and so the
// float sums, of a walk over the 27 cells around the voxel). The counts, and
// so the iou, must be the same exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "ff_rotation.h"
#include "ff_sph.h"
#include "grid/uniform_grid.h"
#include "metrics/iou.h"
#include "target/target_shape.h"

namespace {

// The iou as docs/METRICS.md defines it, with no pruning and no early stop.
double plainIou(const ff::TargetShape& target, const ff::RigidFrame& frame, int pad,
                const std::vector<float>& x, const std::vector<float>& y, const std::vector<float>& z,
                const ff::UniformGrid& grid, float mass, float h, float threshold) {
  const ff::VoxelGrid& g = target.grid;
  const ff_mat3 r = ff_quat_to_mat3(frame.q);
  const float h2 = h * h, coef = ff_poly6_coef(h);
  long inter = 0, uni = 0;
  for (int k = -pad; k < g.nz + pad; ++k)
    for (int j = -pad; j < g.ny + pad; ++j)
      for (int i = -pad; i < g.nx + pad; ++i) {
        const bool in_target =
            i >= 0 && j >= 0 && k >= 0 && i < g.nx && j < g.ny && k < g.nz && g.inside[g.index(i, j, k)];
        const ff::Vec3 c = g.center(i, j, k);
        const ff_float3 w = ff_mat3_mul_vec(r, FF_F3(c.x() - frame.rest_c[0], c.y() - frame.rest_c[1],
                                                     c.z() - frame.rest_c[2])) +
                            FF_F3(frame.c[0], frame.c[1], frame.c[2]);
        float sum = 0.0f;
        for (uint32_t p : grid.order()) {
          const float dx = w.x - x[p], dy = w.y - y[p], dz = w.z - z[p];
          sum += ff_poly6(dx * dx + dy * dy + dz * dz, h2, coef);
        }
        const bool in_fluid = mass * sum >= threshold;
        inter += in_target && in_fluid ? 1 : 0;
        uni += in_target || in_fluid ? 1 : 0;
      }
  return uni > 0 ? double(inter) / double(uni) : 0.0;
}

TEST(VoxelIou, RunsOfEightLanesCountTheSameVoxelsAsThePlainDefinition) {
  // A ball of 19 x 17 x 13 voxels (not multiples of 8), turned and moved.
  ff::TargetShape t;
  ff::VoxelGrid& g = t.grid;
  g.voxel = 0.01f, g.nx = 19, g.ny = 17, g.nz = 13;
  g.origin = ff::Vec3(-0.095f, -0.085f, -0.065f);
  g.inside.assign(size_t(g.nx) * g.ny * g.nz, 0);
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) g.inside[g.index(i, j, k)] = g.center(i, j, k).norm() < 0.06f ? 1 : 0;
  ff::RigidFrame frame;
  const float s = std::sin(0.3f), c = std::cos(0.3f);
  frame.q = FF_Q(0.0f, s, 0.0f, c);
  frame.c[0] = 0.2f, frame.c[1] = 0.15f, frame.c[2] = 0.2f;
  // Fluid: a dense blob overlapping the shape and a sparse spray around it.
  std::mt19937 rng(11);
  std::normal_distribution<float> blob(0.0f, 0.035f);
  std::uniform_real_distribution<float> spray(0.05f, 0.35f);
  std::vector<float> x, y, z;
  for (int i = 0; i < 6000; ++i)
    x.push_back(0.21f + blob(rng)), y.push_back(0.14f + blob(rng)), z.push_back(0.2f + blob(rng));
  for (int i = 0; i < 1000; ++i) x.push_back(spray(rng)), y.push_back(spray(rng)), z.push_back(spray(rng));
  const float h = 0.02f, mass = 0.0002f, rho0 = 800.0f;
  const float lo[3] = {0.0f, 0.0f, 0.0f}, hi[3] = {0.4f, 0.4f, 0.4f};
  for (const float cell : {h, 1.7f * h}) {  // the index grid's cells: at least h
    ff::UniformGrid grid;
    grid.build(x.size(), x.data(), y.data(), z.data(), cell, lo, hi);
    for (const float fraction : {0.05f, 0.5f, 2.0f}) {
      const double ref = plainIou(t, frame, 2, x, y, z, grid, mass, h, fraction * rho0);
      const ff::IouCounts c =
          ff::voxelIou(t, frame, 2, x.data(), y.data(), z.data(), grid, mass, h, rho0, fraction);
      const double got = c.uni > 0 ? double(c.inter) / double(c.uni) : 0.0;
      EXPECT_EQ(got, ref) << "cell " << cell << ", fraction " << fraction;
      EXPECT_GT(ref, 0.0) << "cell " << cell << ", fraction " << fraction;
    }
  }
}

}  // namespace
