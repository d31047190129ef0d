// thin_target.h - a target with a known thin part and its thin voxels found
// by brute force from the definition (docs/METRICS.md), for the filled_thin
// tests (test_fluid_shares.cpp, the backends' radius edits).
//
// The shape: a block 9 voxels wide with a rod one voxel thick and 8 long
// standing on it, in a grid of 13 x 21 x 13 voxels (a border of outside
// voxels). A voxel v's local thickness is the largest 2 R_c over the inside
// voxel centres c whose ball reaches v's centre, R_c = c's distance to the
// nearest outside voxel centre less half a voxel; v is thin when that is
// below the radius.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/params.h"
#include "sim/backend.h"
#include "target/target_shape.h"
#include "test_scenes.h"

namespace fftest {

inline bool thinTargetBlock(int i, int j, int k) {
  return i >= 2 && i <= 10 && j >= 2 && j <= 10 && k >= 2 && k <= 10;
}
inline bool thinTargetRod(int i, int j, int k) {
  return i == 6 && k == 6 && j >= 11 && j <= 18;
}

// The block and rod in voxels of `voxel` metres, origin at 0.
inline ff::TargetShape thinTarget(float voxel) {
  ff::TargetShape t;
  ff::VoxelGrid& g = t.grid;
  g.voxel = voxel, g.nx = 13, g.ny = 21, g.nz = 13;
  g.origin = ff::Vec3(0.0f, 0.0f, 0.0f);
  g.inside.assign(size_t(g.nx) * g.ny * g.nz, 0);
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        g.inside[g.index(i, j, k)] = thinTargetBlock(i, j, k) || thinTargetRod(i, j, k) ? 1 : 0;
  return t;
}

// The thin voxels of g below `radius` (metres), by brute force.
inline std::vector<uint8_t> bruteThinVoxels(const ff::VoxelGrid& g, float radius) {
  std::vector<int> in;
  std::vector<double> ball;
  for (size_t c = 0; c < g.inside.size(); ++c) {
    if (!g.inside[c]) continue;
    const int ci = int(c % size_t(g.nx)), cj = int((c / size_t(g.nx)) % size_t(g.ny)),
              ck = int(c / (size_t(g.nx) * size_t(g.ny)));
    double d2 = 1e30;
    for (int k = 0; k < g.nz; ++k)
      for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i)
          if (!g.inside[g.index(i, j, k)])
            d2 = std::min(d2, double((i - ci) * (i - ci) + (j - cj) * (j - cj) + (k - ck) * (k - ck)));
    in.push_back(int(c)), ball.push_back(std::sqrt(d2) - 0.5);
  }
  std::vector<uint8_t> thin(g.inside.size(), 0);
  for (size_t a = 0; a < in.size(); ++a) {
    const int v = in[a], vi = v % g.nx, vj = (v / g.nx) % g.ny, vk = v / (g.nx * g.ny);
    double thick = 0.0;
    for (size_t b = 0; b < in.size(); ++b) {
      const int c = in[b], ci = c % g.nx, cj = (c / g.nx) % g.ny, ck = c / (g.nx * g.ny);
      const double r2 = double((vi - ci) * (vi - ci) + (vj - cj) * (vj - cj) + (vk - ck) * (vk - ck));
      if (r2 <= ball[b] * ball[b]) thick = std::max(thick, 2.0 * ball[b]);
    }
    thin[size_t(v)] = thick * g.voxel < radius ? 1 : 0;
  }
  return thin;
}

// filled_thin follows the control radius on backend b (issue: the thin voxels
// were found once per target, from the radius at setMetricsTarget): the
// target above in voxels of 1 cm, a particle at the centre of each voxel of
// the block and of the rod's lowest two (h = 0.9 voxel and
// rho0 = m / voxel^3, so a voxel holds fluid exactly where a particle sits, as
// in test_fluid_shares.cpp), control particles at rest on every inside voxel
// (the best-fit frame is the identity). The radius is edited with setParams
// after the target is set; filled_thin must be the share of the brute-force
// thin voxels at the new radius that hold a particle.
inline void expectFilledThinFollowsTheRadius(ff::Backend& b) {
  const float voxel = 0.01f, mass = 0.0002f;
  const ff::TargetShape t = thinTarget(voxel);
  const ff::VoxelGrid& g = t.grid;
  ff::FluidState fluid;
  std::vector<uint8_t> holds(g.inside.size(), 0);
  ff::ControlSet set;
  double c[3] = {0.0, 0.0, 0.0};
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const ff::Vec3 p = g.center(i, j, k);
        if (thinTargetBlock(i, j, k) || (thinTargetRod(i, j, k) && j <= 12)) {
          fluid.push(p.x(), p.y(), p.z(), 0.0f, 0.0f, 0.0f);
          holds[g.index(i, j, k)] = 1;
        }
        if (!g.inside[g.index(i, j, k)]) continue;
        set.x.push_back(p.x()), set.y.push_back(p.y()), set.z.push_back(p.z());
        c[0] += p.x(), c[1] += p.y(), c[2] += p.z();
      }
  const size_t nc = set.x.size();
  set.x0 = set.x, set.y0 = set.y, set.z0 = set.z;
  set.vx.assign(nc, 0.0f), set.vy = set.vx, set.vz = set.vx;
  set.rest_cx = float(c[0] / double(nc)), set.rest_cy = float(c[1] / double(nc)),
  set.rest_cz = float(c[2] / double(nc));
  set.particle_volume = voxel * voxel * voxel;
  setOneCluster(set);

  // The share of the brute-force thin voxels at `radius` that hold a particle.
  auto expected = [&](float radius) {
    const std::vector<uint8_t> thin = bruteThinVoxels(g, radius);
    long count = 0, filled = 0;
    for (size_t v = 0; v < thin.size(); ++v) count += thin[v], filled += thin[v] && holds[v] ? 1 : 0;
    EXPECT_GT(count, 0);
    return count > 0 ? double(filled) / double(count) : 1.0;
  };
  const float r_small = 1.5f * voxel, r_large = 3.06f * voxel;
  const double small = expected(r_small), large = expected(r_large);
  ASSERT_GT(std::fabs(small - large), 0.05) << "the two radii must give different answers";

  ff::Params params = ff::presetParams("paper");
  params.fluid.smoothing_radius = 0.9f * voxel, params.fluid.particle_mass = mass;
  params.fluid.rest_density = mass / (voxel * voxel * voxel);
  params.control.radius = r_small;
  ff::ContainerDesc box;
  box.min = ff::Vec3(-0.05f, -0.05f, -0.05f), box.max = ff::Vec3(0.2f, 0.3f, 0.2f);
  b.init(params, box, fluid);
  b.setControl(set);
  b.setMetricsTarget(&t);
  EXPECT_NEAR(b.computeMetrics().filled_thin, small, 1e-12) << "radius 1.5 voxels, set with the target";
  params.control.radius = r_large;
  b.setParams(params);
  EXPECT_NEAR(b.computeMetrics().filled_thin, large, 1e-12) << "radius 3.06 voxels, edited after the target";
  params.control.radius = r_small;
  b.setParams(params);
  EXPECT_NEAR(b.computeMetrics().filled_thin, small, 1e-12) << "radius 1.5 voxels again";
}

}  // namespace fftest
