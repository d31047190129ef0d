// test_thin_features.cpp - adaptive control (docs/CONTROL_UNITS.md, "Thin
// features"): the local thickness of a voxelised shape (against brute force
// and slabs of known thickness), control particles whose radius follows it (a
// thin plate's below a sphere's), clusters that follow limbs (two bars one
// voxel apart are never matched as one piece), and a filled thin plate that
// its own control particles see as filled.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "control/clusters.h"
#include "control/controller.h"
#include "control/placement.h"
#include "cpu/backend_cpu.h"
#include "sim/simulation.h"
#include "target/local_thickness.h"
#include "target/target_shape.h"
#include "test_scenes.h"

namespace {

ff::VoxelGrid emptyGrid(int nx, int ny, int nz, float voxel) {
  ff::VoxelGrid g;
  g.voxel = voxel, g.nx = nx, g.ny = ny, g.nz = nz;
  g.inside.assign(size_t(nx) * ny * nz, 0);
  return g;
}

// The exact transform against a brute-force search over every outside voxel,
// on a ball joined to a bar (integer squared distances: exact in float).
TEST(ThinFeatures, DistanceTransformIsTheBruteForceDistance) {
  ff::VoxelGrid g = emptyGrid(24, 16, 14, 1.0f);
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const int di = i - 7, dj = j - 8, dk = k - 7;
        const bool ball = di * di + dj * dj + dk * dk <= 25;
        const bool bar = i >= 7 && i <= 21 && j >= 7 && j <= 8 && k >= 6 && k <= 8;
        g.inside[g.index(i, j, k)] = ball || bar;
      }
  const std::vector<float> d2 = ff::squaredDistanceToOutside(g);
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        long best = 0;
        if (g.inside[g.index(i, j, k)]) {
          best = 1L << 40;
          for (int c = 0; c < g.nz; ++c)
            for (int b = 0; b < g.ny; ++b)
              for (int a = 0; a < g.nx; ++a)
                if (!g.inside[g.index(a, b, c)])
                  best =
                      std::min(best, long(a - i) * (a - i) + long(b - j) * (b - j) + long(c - k) * (c - k));
        }
        ASSERT_EQ(d2[g.index(i, j, k)], float(best)) << i << " " << j << " " << k;
      }
}

// A slab k voxels thick is k voxels thick away from its rims for odd k, and
// k - 1 for even k (the largest ball centred on a voxel centre: the slab's
// middle lies between two of them); a cube's centre reaches the cap.
TEST(ThinFeatures, LocalThicknessOfSlabsIsTheirThickness) {
  const float voxel = 0.01f;
  for (int t = 1; t <= 5; ++t) {
    ff::VoxelGrid g = emptyGrid(20, t + 2, 20, voxel);
    for (int k = 1; k < 19; ++k)
      for (int j = 1; j <= t; ++j)
        for (int i = 1; i < 19; ++i) g.inside[g.index(i, j, k)] = 1;
    const std::vector<float> th = ff::localThickness(g, 1.0f);
    for (int k = 1 + t; k < 19 - t; ++k)
      for (int j = 1; j <= t; ++j)
        for (int i = 1 + t; i < 19 - t; ++i)
          ASSERT_NEAR(th[g.index(i, j, k)], (t % 2 ? t : t - 1) * voxel, 1e-6)
              << "slab " << t << " at " << i << " " << j << " " << k;
    EXPECT_EQ(th[g.index(0, 0, 0)], 0.0f);
  }
  ff::VoxelGrid cube = emptyGrid(22, 22, 22, voxel);
  for (int k = 1; k < 21; ++k)
    for (int j = 1; j < 21; ++j)
      for (int i = 1; i < 21; ++i) cube.inside[cube.index(i, j, k)] = 1;
  const float cap = 0.06f;
  const std::vector<float> th = ff::localThickness(cube, cap);
  EXPECT_FLOAT_EQ(th[cube.index(10, 10, 10)], cap);
  for (size_t c = 0; c < th.size(); ++c) {
    if (!cube.inside[c]) continue;
    EXPECT_GE(th[c], voxel);
    EXPECT_LE(th[c], cap);
  }
}

// Placement: a thin plate's control particles get radii below a sphere's (the
// sphere's are the control radius almost everywhere), every radius lies in
// [min_radius, radius]; with adaptive control off every scale is 1.
TEST(ThinFeatures, AThinPlateGetsSmallerRadiiThanABlob) {
  ff::ControlParams cp;  // radius 0.03
  const double volume = 8e-4;
  const float spacing = 0.0063f;
  auto place = [&](const ff::TargetSpec& spec, bool on) {
    const ff::TargetShape t = ff::buildTarget(spec, volume, 0.01f);
    ff::ControlParams c = cp;
    c.adaptive = on ? 1 : 0;
    const ff::AdaptiveControl a = ff::adaptiveControl(c, t.grid.voxel, spacing);
    EXPECT_GE(a.min_radius, 1.5f * t.grid.voxel - 1e-6f);
    EXPECT_GE(a.min_radius, 2.0f * spacing - 1e-6f);
    const ff::Vec3 lo(0, 0, 0), hi(0.2f, 0.2f, 0.2f);
    ff::ControlSet s = ff::placeControlParticles(t, lo, hi, ff::ShapeMatchParams(), ff::Vec3(-1, -1, -1),
                                                 ff::Vec3(1, 1, 1), a);
    EXPECT_EQ(s.radius_scale.size(), s.size());
    for (float r : s.radius_scale) {
      EXPECT_LE(r, 1.0f);
      EXPECT_GE(r * cp.radius, a.min_radius * (1.0f - 1e-6f));
    }
    std::vector<float> v = s.radius_scale;
    std::sort(v.begin(), v.end());
    return v;
  };
  ff::TargetSpec plate = fftest::target(ff::TargetKind::Box, 800);
  plate.box_size = ff::Vec3(1.0f, 0.08f, 1.0f);
  const ff::TargetSpec sphere = fftest::target(ff::TargetKind::Sphere, 800);
  const std::vector<float> p = place(plate, true), s = place(sphere, true);
  const float p_median = p[p.size() / 2], s_median = s[s.size() / 2];
  // The plate is (V / 0.08)^(1/3) * 0.08 = 1.7 cm thick: radii of about that, under 0.03.
  EXPECT_LT(p_median, 0.75f);
  EXPECT_EQ(s_median, 1.0f);
  EXPECT_GT(std::count(s.begin(), s.end(), 1.0f), long(s.size()) * 9 / 10);
  const std::vector<float> off = place(plate, false);
  EXPECT_EQ(off.front(), 1.0f);
}

// Two parallel bars one voxel apart pass through the same cluster cubes: with
// connected clusters no cluster holds both, and every particle is in one.
TEST(ThinFeatures, ClustersFollowLimbs) {
  std::vector<int> vi, vj, vk;
  ff::ControlSet s;
  std::vector<int> bar;
  for (int b = 0; b < 2; ++b)
    for (int i = 0; i < 10; ++i)
      for (int k = 0; k < 2; ++k) {
        vi.push_back(i), vj.push_back(2 * b), vk.push_back(k), bar.push_back(b);
        s.x0.push_back(0.01f * i), s.y0.push_back(0.02f * b), s.z0.push_back(0.01f * k);
      }
  s.x = s.x0, s.y = s.y0, s.z = s.z0;
  s.vx.assign(s.x.size(), 0.0f), s.vy = s.vx, s.vz = s.vx;
  auto mixed = [&](bool connected) {
    ff::buildClusters(s, vi, vj, vk, 2, 2, connected);
    const ff::Clusters& cl = s.clusters;
    for (size_t p = 0; p < s.size(); ++p) EXPECT_GE(cl.of_start[p + 1] - cl.of_start[p], 1u);
    size_t count = 0;
    for (size_t c = 0; c < cl.count(); ++c) {
      bool has[2] = {false, false};
      for (uint32_t k = cl.start[c]; k < cl.start[c + 1]; ++k) has[bar[cl.members[k]]] = true;
      count += has[0] && has[1];
    }
    return count;
  };
  EXPECT_GT(mixed(false), 0u) << "the cube clusters should hold both bars (else the test shows nothing)";
  EXPECT_EQ(mixed(true), 0u) << "a connected cluster holds both bars";
}

// The share of a poly6 kernel of radius h (its integral over a plane at
// height z is 315 (h^2 - z^2)^4 / (256 h^9)) between the heights z0 < z1
// relative to its centre: Simpson's rule, an independent computation of
// eq. 5's continuum sum over a slab.
double slabShare(double z0, double z1, double h) {
  z0 = std::max(z0, -h), z1 = std::min(z1, h);
  if (z1 <= z0) return 0.0;
  const int n = 2000;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double z = z0 + (z1 - z0) * i / n, q = h * h - z * z;
    const double f = 315.0 * q * q * q * q / (256.0 * std::pow(h, 9));
    sum += f * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
  }
  return sum * ((z1 - z0) / n) / 3.0;
}

// Clusters of a share of the shape's length (placement.h, clusterSize): a
// long thin bar 60 voxels tall gets clusters 2 round(60 / 15) + 1 = 9 voxels
// wide, a cube 15 voxels wide the default 5 (half-width 2), both measured
// here as the widest span of a cluster's members along any axis, in voxels
// of the rest lattice; each control particle still belongs to at most 27
// clusters (3 lattice points per axis), so shape matching costs as much.
TEST(ThinFeatures, ALongShapeGetsClustersOfAShareOfItsLength) {
  auto widest = [](const ff::TargetSpec& spec, int* extent, size_t* most_per_particle) {
    const ff::TargetShape t = ff::buildTarget(spec, 8e-4, 0.01f);
    const ff::ControlSet s =
        ff::placeControlParticles(t, ff::Vec3(0, 0, 0), ff::Vec3(0.2f, 0.6f, 0.2f), ff::ShapeMatchParams(),
                                  ff::Vec3(-1, -1, -1), ff::Vec3(1, 1, 1));
    const float v = t.grid.voxel;
    const std::vector<float>* axes[3] = {&s.x0, &s.y0, &s.z0};
    *extent = 0;
    for (const std::vector<float>* a : axes) {
      const auto [mn, mx] = std::minmax_element(a->begin(), a->end());
      *extent = std::max(*extent, int(std::lround((*mx - *mn) / v)) + 1);
    }
    int span = 0;
    const ff::Clusters& c = s.clusters;
    for (size_t k = 0; k < c.count(); ++k)
      for (const std::vector<float>* a : axes) {
        float lo = 1e30f, hi = -1e30f;
        for (uint32_t m = c.start[k]; m < c.start[k + 1]; ++m)
          lo = std::min(lo, (*a)[c.members[m]]), hi = std::max(hi, (*a)[c.members[m]]);
        span = std::max(span, int(std::lround((hi - lo) / v)) + 1);
      }
    *most_per_particle = 0;
    for (size_t i = 0; i < s.size(); ++i)
      *most_per_particle = std::max(*most_per_particle, size_t(c.of_start[i + 1] - c.of_start[i]));
    return span;
  };
  // A bar about 5.6 voxels thick (its ridge 5 thick, a limb: one default
  // cluster across it) and one about 7.8 thick (ridge 7: two clusters across,
  // as a letter's strokes), both longer than 37 voxels, and a cube.
  ff::TargetSpec bar = fftest::target(ff::TargetKind::Box, 3000);
  bar.box_size = ff::Vec3(0.06f, 1.0f, 0.06f);
  ff::TargetSpec stroke = fftest::target(ff::TargetKind::Box, 3000);
  stroke.box_size = ff::Vec3(0.16f, 1.0f, 0.16f);
  const ff::TargetSpec cube = fftest::target(ff::TargetKind::Box, 3000);
  int bar_extent = 0, stroke_extent = 0, cube_extent = 0;
  size_t bar_most = 0, stroke_most = 0, cube_most = 0;
  const int bar_span = widest(bar, &bar_extent, &bar_most),
            stroke_span = widest(stroke, &stroke_extent, &stroke_most),
            cube_span = widest(cube, &cube_extent, &cube_most);
  std::printf(
      "  bar %d voxels long: clusters %d voxels wide; thick bar %d: %d wide; cube %d voxels: %d wide; at "
      "most %zu, %zu and %zu clusters per particle\n",
      bar_extent, bar_span, stroke_extent, stroke_span, cube_extent, cube_span, bar_most, stroke_most,
      cube_most);
  ASSERT_GE(bar_extent, 45);
  ASSERT_GE(stroke_extent, 45);
  EXPECT_EQ(bar_span, 2 * int(std::lround(bar_extent / 15.0)) + 1);
  EXPECT_EQ(stroke_span, 5);
  EXPECT_EQ(cube_span, 5);
  EXPECT_LE(bar_most, 27u);
  EXPECT_LE(cube_most, 27u);
}

// thinRidgeVoxels on voxel shapes of known thickness: a bar 4 x 4 voxels
// across and 40 long has its ridge in its 2 x 2 middle voxels, 2 deep (3
// thick), all along it but its last voxel at each end (1 deep), so 4 per
// voxel of length over 38; a bar 8 x 8 across (ridge 4 deep: 7 thick) and
// a T of two such strokes have none, although the voxels along their edges
// are thin (3, localThickness): they lie off the ridge; two balls 15 voxels
// wide joined by a bar 3 across have the bar's middle line, at least its
// length between the balls less a ball's radius at each end.
TEST(ThinFeatures, TheRidgeTellsLimbsFromStrokes) {
  auto grid = [](int n, auto inside) {
    ff::VoxelGrid g = emptyGrid(n, n, n, 0.01f);
    for (int k = 1; k < n - 1; ++k)
      for (int j = 1; j < n - 1; ++j)
        for (int i = 1; i < n - 1; ++i) g.inside[g.index(i, j, k)] = inside(i, j, k) ? 1 : 0;
    return g;
  };
  auto in = [](int v, int lo, int n) { return v >= lo && v < lo + n; };
  const ff::VoxelGrid limb =
      grid(50, [&](int i, int j, int k) { return in(i, 20, 4) && in(k, 20, 4) && in(j, 5, 40); });
  const ff::VoxelGrid stroke =
      grid(50, [&](int i, int j, int k) { return in(i, 20, 8) && in(k, 20, 8) && in(j, 5, 40); });
  const ff::VoxelGrid letter = grid(50, [&](int i, int j, int k) {
    return in(k, 20, 8) && ((in(i, 20, 8) && in(j, 5, 40)) || (in(i, 4, 40) && in(j, 37, 8)));
  });
  const ff::VoxelGrid dumbbell = grid(70, [&](int i, int j, int k) {
    auto ball = [&](int cx) {
      const float dx = float(i) + 0.5f - float(cx), dy = float(j) - 29.5f, dz = float(k) - 29.5f;
      return dx * dx + dy * dy + dz * dz <= 7.5f * 7.5f;
    };
    return ball(12) || ball(58) || (in(j, 28, 3) && in(k, 28, 3) && in(i, 12, 46));
  });
  const long n_limb = ff::thinRidgeVoxels(limb, 5.0f), n_stroke = ff::thinRidgeVoxels(stroke, 5.0f),
             n_letter = ff::thinRidgeVoxels(letter, 5.0f), n_dumbbell = ff::thinRidgeVoxels(dumbbell, 5.0f);
  std::printf("  thin ridge voxels: limb %ld, stroke %ld, letter %ld, dumbbell %ld\n", n_limb, n_stroke,
              n_letter, n_dumbbell);
  EXPECT_EQ(n_limb, 4 * 38);
  EXPECT_EQ(n_stroke, 0);
  EXPECT_EQ(n_letter, 0);
  EXPECT_GE(n_dumbbell, 46 - 2 * 15);
  // The edges are thin: the count is not one of thin voxels.
  const std::vector<float> t = ff::localThickness(stroke, 1.0f);
  EXPECT_NEAR(t[stroke.index(20, 20, 20)] / stroke.voxel, 3.0f, 1e-4f);
}

// Eq. 5 on a thin plate filled with fluid at rest (a lattice over the plate's
// voxels): with one radius (3 cm, wider than the plate is thick) the control
// particles in the plate's middle read it as partly empty, s = 1 - the
// kernel's share inside the slab; with adaptive control their own radius
// (the smallest allowed, 1.5 voxels, here) fits the plate better and they
// read it as nearly filled. Both against the
// continuum share, within 0.08 (the lattice of 2.5 to 5 spacings per radius
// sums the kernel to a few percent).
TEST(ThinFeatures, AFilledThinPlateReadsAsFilled) {
  const double volume = 8e-4;
  ff::TargetSpec spec = fftest::target(ff::TargetKind::Box, 800);
  spec.box_size = ff::Vec3(1.0f, 0.12f, 1.0f);
  const ff::TargetShape t = ff::buildTarget(spec, volume, 0.01f);
  const ff::Vec3 lo = t.boundsMin(), hi = t.boundsMax();
  // The fluid: a lattice filling the plate's voxels' extent.
  const float spacing = 0.0063f;
  std::vector<float> x, y, z;
  for (float pz = lo.z() + 0.5f * spacing; pz < hi.z(); pz += spacing)
    for (float py = lo.y() + 0.5f * spacing; py < hi.y(); py += spacing)
      for (float px = lo.x() + 0.5f * spacing; px < hi.x(); px += spacing)
        x.push_back(px), y.push_back(py), z.push_back(pz);
  const std::vector<float> zero(x.size(), 0.0f);
  int layers = 0;
  for (float py = lo.y() + 0.5f * spacing; py < hi.y(); py += spacing) ++layers;
  const double half = 0.5 * layers * spacing;  // the fluid slab's half thickness (around mid)
  ff::FluidView f;
  f.n = x.size();
  f.x = x.data(), f.y = y.data(), f.z = z.data(), f.vx = zero.data(), f.vy = zero.data(), f.vz = zero.data();
  f.volume = spacing * spacing * spacing;
  const float mid = lo.y() + float(half), rim = 0.035f;
  auto middle = [&](bool on, double* expected) {
    ff::ControlParams cp;
    cp.adaptive = on ? 1 : 0;
    const ff::AdaptiveControl a = ff::adaptiveControl(cp, t.grid.voxel, spacing);
    ff::Controller c;
    c.setParams(cp, ff::ShapeMatchParams());
    // Placed onto the reference particles' own bounds: every control particle at its rest position.
    ff::Vec3 rlo = t.reference[0], rhi = t.reference[0];
    for (const ff::Vec3& r : t.reference) rlo = rlo.cwiseMin(r), rhi = rhi.cwiseMax(r);
    c.reset(ff::placeControlParticles(t, rlo, rhi, ff::ShapeMatchParams(), ff::Vec3(-1, -1, -1),
                                      ff::Vec3(1, 1, 1), a));
    EXPECT_TRUE(c.computeScale(f));
    const ff::ControlSet& set = c.set();
    double sum = 0.0, want = 0.0;
    int count = 0;
    for (size_t i = 0; i < set.size(); ++i) {
      // The middle layer, away from the plate's rims.
      if (std::fabs(set.y[i] - mid) > 0.5f * t.grid.voxel + 1e-4f) continue;
      if (set.x[i] < lo.x() + rim || set.x[i] > hi.x() - rim || set.z[i] < lo.z() + rim ||
          set.z[i] > hi.z() - rim)
        continue;
      const double h = double(cp.radius) * set.radius_scale[i];
      const double dy = double(set.y[i]) - mid;
      sum += c.fields().s[i], want += 1.0 - std::min(1.0, slabShare(-half - dy, half - dy, h));
      ++count;
    }
    EXPECT_GT(count, 20);
    *expected = want / std::max(count, 1);
    return sum / std::max(count, 1);
  };
  double want_off = 0.0, want_on = 0.0;
  const double off = middle(false, &want_off), on = middle(true, &want_on);
  std::printf(
      "  plate %d fluid layers: mean s in its middle %.3f (expected %.3f) with one radius, %.3f (%.3f) "
      "with adaptive control\n",
      layers, off, want_off, on, want_on);
  EXPECT_NEAR(off, want_off, 0.08);
  EXPECT_NEAR(on, want_on, 0.08);
  EXPECT_GT(off, 0.25) << "one radius should read the filled plate as partly empty";
  // The continuum shares differ by a factor 2.6 (0.37 against 0.15 for this
  // plate): adaptive control must read it at least twice as full.
  EXPECT_LT(on, 0.5 * off) << "adaptive control should read the filled plate as (nearly) filled";
}

}  // namespace
