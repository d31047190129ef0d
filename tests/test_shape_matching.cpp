// Cluster shape matching pulls a rotated, translated and squashed point set
// back to its rigid shape.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "control/clusters.h"
#include "control/controller.h"
#include "control/placement.h"
#include "control/shape_matching.h"
#include "target/local_thickness.h"

namespace {

ff::ControlSet blockSet(int nx, int ny, int nz, float spacing, std::vector<int>& vi, std::vector<int>& vj,
                        std::vector<int>& vk) {
  ff::ControlSet s;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        s.x0.push_back((i + 0.5f) * spacing), s.y0.push_back((j + 0.5f) * spacing),
            s.z0.push_back((k + 0.5f) * spacing);
        vi.push_back(i), vj.push_back(j), vk.push_back(k);
      }
  size_t n = s.x0.size();
  s.x = s.x0, s.y = s.y0, s.z = s.z0;
  s.vx.assign(n, 0), s.vy.assign(n, 0), s.vz.assign(n, 0);
  double cx = 0, cy = 0, cz = 0;
  for (size_t p = 0; p < n; ++p) cx += s.x0[p], cy += s.y0[p], cz += s.z0[p];
  s.rest_cx = float(cx / n), s.rest_cy = float(cy / n), s.rest_cz = float(cz / n);
  return s;
}

// RMS distance between the set and the best rigid transform of its rest shape,
// computed independently with Eigen's Umeyama (SVD-based).
double rigidResidual(const ff::ControlSet& s) {
  const long n = long(s.size());
  Eigen::Matrix3Xd src(3, n), dst(3, n);
  for (long p = 0; p < n; ++p) {
    src.col(p) << s.x0[p], s.y0[p], s.z0[p];
    dst.col(p) << s.x[p], s.y[p], s.z[p];
  }
  Eigen::Matrix4d t = Eigen::umeyama(src, dst, false);
  Eigen::Matrix3Xd fit = (t.topLeftCorner<3, 3>() * src).colwise() + t.topRightCorner<3, 1>();
  return std::sqrt((fit - dst).squaredNorm() / double(n));
}

// Runs `steps` shape-matching steps of the set s in c with the default
// params and no fluid (feedback 0.1 then damps towards rest).
void shapeMatchAlone(ff::Controller& c, const ff::ControlSet& s, int steps) {
  ff::ControlParams cp;
  cp.feedback = 0.1f;
  c.setParams(cp, ff::ShapeMatchParams());
  c.reset(s);
  for (int i = 0; i < steps; ++i) c.shapeMatchStep();
}

TEST(ShapeMatching, ClustersOverlapAndCoverEveryParticle) {
  std::vector<int> vi, vj, vk;
  ff::ControlSet s = blockSet(8, 6, 5, 0.01f, vi, vj, vk);
  ff::buildClusters(s, vi, vj, vk, 2, 2);
  const auto& cl = s.clusters;
  ASSERT_GT(cl.count(), 1u);
  for (size_t p = 0; p < s.size(); ++p) EXPECT_GE(cl.of_start[p + 1] - cl.of_start[p], 1u) << p;
  EXPECT_GT(cl.members.size(), s.size());  // overlap: some particles are in several clusters
  for (size_t c = 0; c < cl.count(); ++c) EXPECT_GE(cl.start[c + 1] - cl.start[c], 4u);
}

TEST(ShapeMatching, PullsADeformedSetBackToItsRigidShape) {
  std::vector<int> vi, vj, vk;
  ff::ControlSet s = blockSet(8, 6, 5, 0.01f, vi, vj, vk);
  ff::buildClusters(s, vi, vj, vk, 2, 2);
  // squash by 0.5 along y, rotate 40 degrees about (1,1,0), translate
  Eigen::Matrix3f r = Eigen::AngleAxisf(0.7f, Eigen::Vector3f(1, 1, 0).normalized()).toRotationMatrix();
  Eigen::Matrix3f m = r * Eigen::Vector3f(1.2f, 0.5f, 1.0f).asDiagonal();
  for (size_t p = 0; p < s.size(); ++p) {
    Eigen::Vector3f q = m * Eigen::Vector3f(s.x0[p], s.y0[p], s.z0[p]) + Eigen::Vector3f(0.3f, -0.2f, 0.1f);
    s.x[p] = q.x(), s.y[p] = q.y(), s.z[p] = q.z();
  }
  const double before = rigidResidual(s);
  ASSERT_GT(before, 0.005);

  ff::Controller c;
  shapeMatchAlone(c, s, 400);
  const double after = rigidResidual(c.set());
  EXPECT_LT(after, 0.01 * before) << "before " << before << " after " << after;
  // The centre of mass is not moved by shape matching.
  double cx0 = 0, cx1 = 0;
  for (size_t p = 0; p < s.size(); ++p) cx0 += s.x[p], cx1 += c.set().x[p];
  EXPECT_NEAR(cx0 / s.size(), cx1 / s.size(), 1e-4);
}

// Coarse clusters (params.shape_matching.coarse_clusters): a long thin bar
// of control particles, 40 x 2 x 2 voxels, bent into a parabola that sags 3
// cm in its middle, with no fluid around. Its small clusters (5 voxels wide)
// are each nearly rigid, so the bend is a slow mode of their chain; clusters
// 3 times as wide match the bar with its ends and straighten it. After 1 s
// (200 steps) one level leaves more than half the bend; with the coarse
// level, less than 0.3 times what one level leaves.
TEST(ShapeMatching, CoarseClustersStraightenABentBar) {
  auto bentBarResidual = [](int coarse, double* before) {
    std::vector<int> vi, vj, vk;
    ff::ControlSet s = blockSet(40, 2, 2, 0.01f, vi, vj, vk);
    ff::CoarseLevel level;
    level.factor = coarse;
    ff::buildClusters(s, vi, vj, vk, 2, 2, false, level);
    const float len = 0.4f;
    for (size_t p = 0; p < s.size(); ++p) {
      const float u = 2.0f * s.x0[p] / len - 1.0f;
      s.y[p] = s.y0[p] - 0.03f * (1.0f - u * u);
    }
    *before = rigidResidual(s);
    ff::Controller c;
    shapeMatchAlone(c, s, 200);
    return rigidResidual(c.set());
  };
  double before1 = 0.0, before3 = 0.0;
  const double one = bentBarResidual(0, &before1), coarse = bentBarResidual(3, &before3);
  ASSERT_GT(before1, 0.005);
  EXPECT_EQ(before1, before3);
  EXPECT_GT(one, 0.5 * before1);
  EXPECT_LT(coarse, 0.3 * one) << "bend left: one level " << one << " m, with coarse clusters " << coarse
                               << " m, of " << before1 << " m";
}

// Two lumps joined by a bar, with a limb on one of them (voxel boxes, `m`
// voxels per unit): cubes of 8 m at x [2, 10) m and [34, 42) m, a bar 2 m
// thick from one to the other (24 m long), a limb 2 m thick standing 12 m
// up from the first cube, free at its top.
struct LumpsBarLimb {
  ff::VoxelGrid g;
  explicit LumpsBarLimb(int m) {
    g.voxel = 0.01f / float(m), g.nx = 44 * m, g.ny = 24 * m, g.nz = 12 * m;
    g.inside.assign(size_t(g.nx) * size_t(g.ny) * size_t(g.nz), 0);
    auto box = [&](int x0, int x1, int y0, int y1, int z0, int z1) {
      for (int k = z0 * m; k < z1 * m; ++k)
        for (int j = y0 * m; j < y1 * m; ++j)
          for (int i = x0 * m; i < x1 * m; ++i) g.inside[g.index(i, j, k)] = 1;
    };
    box(2, 10, 2, 10, 2, 10), box(34, 42, 2, 10, 2, 10);  // the lumps
    box(10, 34, 5, 7, 5, 7);                              // the bar
    box(5, 7, 10, 22, 5, 7);                              // the limb
  }
  // The part of the voxel at (x, y, z) units.
  uint8_t partAt(const std::vector<uint8_t>& parts, float x, float y, float z, int m) const {
    return parts[g.index(int(x * float(m)), int(y * float(m)), int(z * float(m)))];
  }
};

// shapeParts finds the two cubes as lumps, the bar between them as a bar and
// the limb as a limb, by construction; the same at twice the resolution (it
// reads depths relative to the shape's own).
TEST(ShapeParts, TwoLumpsABarAndALimb) {
  for (int m : {1, 2}) {
    const LumpsBarLimb s(m);
    const std::vector<uint8_t> parts = ff::shapeParts(s.g, 5.0f * float(m));
    EXPECT_EQ(s.partAt(parts, 6, 6, 6, m), ff::kPartLump) << m;
    EXPECT_EQ(s.partAt(parts, 38, 6, 6, m), ff::kPartLump) << m;
    for (float x : {14.0f, 22.0f, 30.0f})
      EXPECT_EQ(s.partAt(parts, x, 6, 6, m), ff::kPartBar) << m << " " << x;
    for (float y : {14.0f, 21.0f}) EXPECT_EQ(s.partAt(parts, 6, y, 6, m), ff::kPartLimb) << m << " " << y;
    EXPECT_EQ(s.partAt(parts, 0.5f, 0.5f, 0.5f, m), ff::kPartOutside);
  }
  // One cube with the limb and a stub of the bar: no second lump, no bar.
  LumpsBarLimb one(1);
  for (size_t q = 0; q < one.g.inside.size(); ++q)
    if (int(q % size_t(one.g.nx)) >= 20) one.g.inside[q] = 0;
  const std::vector<uint8_t> parts = ff::shapeParts(one.g, 5.0f);
  EXPECT_EQ(std::count(parts.begin(), parts.end(), ff::kPartBar), 0);
  EXPECT_EQ(one.partAt(parts, 14, 6, 6, 1), ff::kPartLimb);
}

// Coarse clusters on bars (shape_matching.coarse_bars): the shape above, its
// bar bent into a parabola sagging 3 cm and its limb swung 30 degrees about
// its root, with no fluid. With the coarse level over the whole shape the
// limb is held in clusters with the body, and the body swings it back; on
// bars alone the limb keeps only the fine clusters and moves as with one
// level, while the bar straightens as with the whole-shape coarse level.
TEST(ShapeMatching, CoarseClustersOnBarsStraightenTheBarAndLeaveTheLimb) {
  const LumpsBarLimb shape(1);
  const ff::VoxelGrid& g = shape.g;
  const std::vector<uint8_t> vparts = ff::shapeParts(g, 5.0f);
  std::vector<int> vi, vj, vk;
  std::vector<uint8_t> parts;
  ff::ControlSet s0;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        if (g.inside[g.index(i, j, k)]) {
          const ff::Vec3 c = g.center(i, j, k);
          s0.x0.push_back(c.x()), s0.y0.push_back(c.y()), s0.z0.push_back(c.z());
          vi.push_back(i), vj.push_back(j), vk.push_back(k), parts.push_back(vparts[g.index(i, j, k)]);
        }
  const size_t n = s0.x0.size();
  s0.vx.assign(n, 0), s0.vy.assign(n, 0), s0.vz.assign(n, 0);
  double c[3];
  ff::centreOfMass(s0.x0, s0.y0, s0.z0, c);
  s0.rest_cx = float(c[0]), s0.rest_cy = float(c[1]), s0.rest_cz = float(c[2]);
  // The pose: the bar sags, the limb swings 30 degrees about (0.06, 0.10).
  s0.x = s0.x0, s0.y = s0.y0, s0.z = s0.z0;
  const float a = 0.5236f;
  std::vector<size_t> bar, limb;
  for (size_t p = 0; p < n; ++p) {
    if (parts[p] == ff::kPartBar) {
      bar.push_back(p);
      const float u = (s0.x0[p] - 0.22f) / 0.12f;
      s0.y[p] = s0.y0[p] - 0.03f * (1.0f - u * u);
    } else if (parts[p] == ff::kPartLimb && s0.y0[p] > 0.10f) {
      limb.push_back(p);
      const float dx = s0.x0[p] - 0.06f, dy = s0.y0[p] - 0.10f;
      s0.x[p] = 0.06f + std::cos(a) * dx + std::sin(a) * dy,
      s0.y[p] = 0.10f - std::sin(a) * dx + std::cos(a) * dy;
    }
  }
  ASSERT_GT(bar.size(), 50u);
  ASSERT_GT(limb.size(), 30u);
  // After 0.25 s: the bar's bend (its RMS distance from the line between its
  // ends' rest offsets, taken as the residual of its own best rigid fit) and
  // the limb tip's distance from where the rigid shape puts it.
  struct Result {
    double bend, limb;
    size_t limb_clusters;
  };
  auto run = [&](int coarse, bool on_bars) {
    ff::ControlSet s = s0;
    using Scope = ff::CoarseLevel::Scope;
    ff::buildClusters(s, vi, vj, vk, 2, 2, false,
                      ff::CoarseLevel{coarse, on_bars ? Scope::Bars : Scope::WholeShape, parts});
    Result r{0.0, 0.0, 0};
    for (size_t p : limb) r.limb_clusters += s.clusters.of_start[p + 1] - s.clusters.of_start[p];
    ff::Controller ctl;
    shapeMatchAlone(ctl, s, 50);
    ff::ControlSet b, l;
    auto subset = [&](const std::vector<size_t>& idx, ff::ControlSet& out) {
      for (size_t p : idx) {
        out.x0.push_back(s.x0[p]), out.y0.push_back(s.y0[p]), out.z0.push_back(s.z0[p]);
        out.x.push_back(ctl.set().x[p]), out.y.push_back(ctl.set().y[p]), out.z.push_back(ctl.set().z[p]);
      }
    };
    subset(bar, b);
    r.bend = rigidResidual(b);
    // The limb: with the lumps, how far it is from the whole's rigid fit.
    std::vector<size_t> body_limb;
    for (size_t p = 0; p < n; ++p)
      if (parts[p] != ff::kPartBar) body_limb.push_back(p);
    subset(body_limb, l);
    r.limb = rigidResidual(l);
    return r;
  };
  const Result one = run(0, false), whole = run(3, false), bars = run(3, true);
  // The bar: the coarse level straightens it, on bars as over the whole.
  EXPECT_LT(bars.bend, 0.5 * one.bend) << "one level " << one.bend << ", on bars " << bars.bend;
  // The limb: on bars it is in no coarse cluster (as many clusters as with one
  // level) and comes back as with one level; over the whole shape the body's
  // clusters swing it back faster.
  EXPECT_EQ(bars.limb_clusters, one.limb_clusters);
  EXPECT_GT(whole.limb_clusters, one.limb_clusters);
  EXPECT_LT(whole.limb, 0.9 * one.limb) << "whole " << whole.limb << ", one level " << one.limb;
  EXPECT_NEAR(bars.limb, one.limb, 0.1 * one.limb) << "on bars " << bars.limb << ", one level " << one.limb;
}

TEST(ShapeMatching, BestFitFrameRecoversARigidMotion) {
  std::vector<int> vi, vj, vk;
  ff::ControlSet s = blockSet(5, 4, 3, 0.02f, vi, vj, vk);
  Eigen::Matrix3f r = Eigen::AngleAxisf(1.1f, Eigen::Vector3f(0.2f, 1, 0.4f).normalized()).toRotationMatrix();
  Eigen::Vector3f t(0.5f, 0.1f, -0.3f);
  for (size_t p = 0; p < s.size(); ++p) {
    Eigen::Vector3f q = r * Eigen::Vector3f(s.x0[p], s.y0[p], s.z0[p]) + t;
    s.x[p] = q.x(), s.y[p] = q.y(), s.z[p] = q.z();
  }
  ff_quat q = FF_Q(0, 0, 0, 1);
  float c[3];
  ff::bestFitFrame(s, q, c, 200);
  ff_mat3 got = ff_quat_to_mat3(q);
  EXPECT_NEAR(got.c0.x, r(0, 0), 1e-4f);
  EXPECT_NEAR(got.c1.y, r(1, 1), 1e-4f);
  EXPECT_NEAR(got.c2.x, r(0, 2), 1e-4f);
  Eigen::Vector3f expect_c = r * Eigen::Vector3f(s.rest_cx, s.rest_cy, s.rest_cz) + t;
  EXPECT_NEAR(c[0], expect_c.x(), 1e-5f);
  EXPECT_NEAR(c[2], expect_c.z(), 1e-5f);
}

}  // namespace

// The Euler characteristic of voxel solids, from topology: a box 1, a box
// pierced by one square hole (a ring) 0, by two holes -1, a box with a sealed
// cavity 2, two separate boxes 2.
TEST(ShapeParts, EulerCharacteristicCountsLoopsAndCavities) {
  auto grid = [](const std::vector<std::array<int, 6>>& on, const std::vector<std::array<int, 6>>& off) {
    ff::VoxelGrid g;
    g.voxel = 0.01f, g.nx = 20, g.ny = 12, g.nz = 10;
    g.inside.assign(size_t(g.nx) * size_t(g.ny) * size_t(g.nz), 0);
    for (int value : {1, 0})
      for (const auto& b : value ? on : off)
        for (int k = b[4]; k < b[5]; ++k)
          for (int j = b[2]; j < b[3]; ++j)
            for (int i = b[0]; i < b[1]; ++i) g.inside[g.index(i, j, k)] = uint8_t(value);
    return g;
  };
  const std::array<int, 6> box{1, 19, 1, 11, 1, 9};
  EXPECT_EQ(ff::eulerCharacteristic(grid({box}, {})), 1);
  EXPECT_EQ(ff::eulerCharacteristic(grid({box}, {{4, 8, 4, 8, 0, 10}})), 0);
  EXPECT_EQ(ff::eulerCharacteristic(grid({box}, {{4, 8, 4, 8, 0, 10}, {12, 16, 4, 8, 0, 10}})), -1);
  EXPECT_EQ(ff::eulerCharacteristic(grid({box}, {{4, 8, 4, 8, 3, 6}})), 2);
  EXPECT_EQ(ff::eulerCharacteristic(grid({{1, 8, 1, 11, 1, 9}, {10, 19, 1, 11, 1, 9}}, {})), 2);
}

// Coarse clusters on loops (docs/CONTROL_UNITS.md): a ring has no bar
// between two lumps, yet with shape_matching.coarse_bars 1 it gets the
// coarse level over the whole shape, the same clusters as coarse_bars 0;
// a ball (no loop, no bar) keeps one level.
TEST(ShapeMatching, CoarseClustersCoverAShapeWithALoop) {
  auto clusters = [](ff::TargetKind kind, int coarse, int bars) {
    ff::TargetSpec spec;
    spec.kind = kind;
    const ff::TargetShape t = ff::buildTarget(spec, 0.002, 0.004f);
    ff::ShapeMatchParams sm;
    sm.coarse_clusters = coarse, sm.coarse_bars = bars;
    const ff::ControlSet s = ff::placeControlParticles(t, t.boundsMin(), t.boundsMax(), sm,
                                                       ff::Vec3(-1, -1, -1), ff::Vec3(1, 1, 1));
    return std::make_pair(s.clusters.start, s.clusters.members);
  };
  const auto ring_one = clusters(ff::TargetKind::Torus, 0, 1),
             ring_bars = clusters(ff::TargetKind::Torus, 3, 1),
             ring_whole = clusters(ff::TargetKind::Torus, 3, 0);
  EXPECT_EQ(ring_bars, ring_whole);
  EXPECT_GT(ring_bars.first.size(), ring_one.first.size());
  EXPECT_EQ(clusters(ff::TargetKind::Sphere, 3, 1), clusters(ff::TargetKind::Sphere, 0, 1));
}

namespace {

// An extruded block letter as voxels: strokes (x0, y0, x1, y1) in voxels of
// the (x, y) plane drawn with a round pen of radius `pen`, `depth` voxels
// deep, every length times `scale`, with two outside voxels around it.
struct Stroke {
  float x0, y0, x1, y1;
};
ff::VoxelGrid letterGrid(const std::vector<Stroke>& strokes, float pen, int depth, int scale) {
  float lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
  for (const Stroke& s : strokes)
    for (int d = 0; d < 2; ++d) {
      const float a = d ? s.y0 : s.x0, b = d ? s.y1 : s.x1;
      lo[d] = std::min({lo[d], a - pen, b - pen}), hi[d] = std::max({hi[d], a + pen, b + pen});
    }
  ff::VoxelGrid g;
  g.voxel = 0.01f / float(scale);
  g.nx = int(std::ceil((hi[0] - lo[0]) * float(scale))) + 4;
  g.ny = int(std::ceil((hi[1] - lo[1]) * float(scale))) + 4;
  g.nz = depth * scale + 4;
  g.inside.assign(size_t(g.nx) * size_t(g.ny) * size_t(g.nz), 0);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      // The voxel centre in the strokes' unscaled coordinates.
      const float px = lo[0] + (float(i - 2) + 0.5f) / float(scale),
                  py = lo[1] + (float(j - 2) + 0.5f) / float(scale);
      bool in = false;
      for (const Stroke& s : strokes) {
        const float ax = s.x1 - s.x0, ay = s.y1 - s.y0, len2 = ax * ax + ay * ay;
        const float t = std::clamp(((px - s.x0) * ax + (py - s.y0) * ay) / len2, 0.0f, 1.0f);
        const float dx = px - (s.x0 + t * ax), dy = py - (s.y0 + t * ay);
        in = in || dx * dx + dy * dy <= pen * pen;
      }
      for (int k = 2; in && k < g.nz - 2; ++k) g.inside[g.index(i, j, k)] = 1;
    }
  return g;
}

// How many strokes leave the point of the letter where most meet, from its
// strokes alone: at each stroke's ends and at each crossing of two strokes,
// a stroke that ends there adds one branch and a stroke that passes through
// it two.
int branchesFromStrokes(const std::vector<Stroke>& strokes) {
  std::vector<std::array<float, 2>> points;
  for (size_t a = 0; a < strokes.size(); ++a) {
    const Stroke& s = strokes[a];
    points.push_back({s.x0, s.y0}), points.push_back({s.x1, s.y1});
    points.push_back({0.5f * (s.x0 + s.x1), 0.5f * (s.y0 + s.y1)});  // a point along it
    for (size_t b = a + 1; b < strokes.size(); ++b) {
      const Stroke& u = strokes[b];
      const float rx = s.x1 - s.x0, ry = s.y1 - s.y0, qx = u.x1 - u.x0, qy = u.y1 - u.y0;
      const float den = rx * qy - ry * qx;
      if (std::fabs(den) < 1e-6f) continue;
      const float t = ((u.x0 - s.x0) * qy - (u.y0 - s.y0) * qx) / den;
      const float v = ((u.x0 - s.x0) * ry - (u.y0 - s.y0) * rx) / den;
      if (t >= 0.0f && t <= 1.0f && v >= 0.0f && v <= 1.0f) points.push_back({s.x0 + t * rx, s.y0 + t * ry});
    }
  }
  int most = 0;
  for (const auto& p : points) {
    int n = 0;
    for (const Stroke& s : strokes) {
      const float ax = s.x1 - s.x0, ay = s.y1 - s.y0, len2 = ax * ax + ay * ay;
      const float t = ((p[0] - s.x0) * ax + (p[1] - s.y0) * ay) / len2;
      const float dx = p[0] - (s.x0 + t * ax), dy = p[1] - (s.y0 + t * ay);
      if (t < -1e-4f || t > 1.0f + 1e-4f || dx * dx + dy * dy > 1e-4f) continue;
      n += (t < 1e-4f || t > 1.0f - 1e-4f) ? 1 : 2;
    }
    most = std::max(most, n);
  }
  return most;
}

ff::TargetShape targetOf(const ff::VoxelGrid& g) {
  ff::TargetShape t;
  t.grid = g;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        if (g.inside[g.index(i, j, k)]) t.reference.push_back(g.center(i, j, k));
  t.shape_volume = t.voxel_volume();
  return t;
}

const std::vector<Stroke> kLetterX = {{0, 0, 24, 30}, {0, 30, 24, 0}};
const std::vector<Stroke> kLetterY = {{0, 30, 12, 15}, {24, 30, 12, 15}, {12, 15, 12, 0}};
const std::vector<Stroke> kLetterT = {{0, 30, 24, 30}, {12, 30, 12, 0}};
const std::vector<Stroke> kLetterL = {{0, 0, 0, 30}, {0, 0, 20, 0}};
const std::vector<Stroke> kLetterI = {{0, 0, 0, 30}};

}  // namespace

// The branches that meet at one point (docs/CONTROL_UNITS.md, "Coarse
// clusters on crossings"), against the strokes each letter is drawn with:
// X 4, Y and T 3, L (a corner) and I 2; the same at twice the resolution. A
// thin plate (a ring around any centre) has 1, a ball smaller than the shell
// 0, a plate with a hole (a loop, no junction) 1 or 2.
TEST(ShapeParts, BranchesCountTheStrokesThatMeet) {
  ASSERT_EQ(branchesFromStrokes(kLetterX), 4);
  ASSERT_EQ(branchesFromStrokes(kLetterY), 3);
  ASSERT_EQ(branchesFromStrokes(kLetterT), 3);
  ASSERT_EQ(branchesFromStrokes(kLetterL), 2);
  ASSERT_EQ(branchesFromStrokes(kLetterI), 2);
  for (int scale : {1, 2})
    for (const auto* letter : {&kLetterX, &kLetterY, &kLetterT, &kLetterL, &kLetterI})
      EXPECT_EQ(ff::mostBranches(letterGrid(*letter, 3.0f, 7, scale)), branchesFromStrokes(*letter))
          << "scale " << scale << ", strokes " << letter->size();
  auto solid = [](int n, const std::function<bool(float, float, float)>& in) {
    ff::VoxelGrid g;
    g.voxel = 0.01f, g.nx = g.ny = g.nz = n + 4;
    g.inside.assign(size_t(g.nx) * size_t(g.ny) * size_t(g.nz), 0);
    for (int k = 2; k < n + 2; ++k)
      for (int j = 2; j < n + 2; ++j)
        for (int i = 2; i < n + 2; ++i) {
          const float c = 0.5f * float(n);  // the centre, in voxels from the solid's corner
          g.inside[g.index(i, j, k)] =
              in(float(i - 2) + 0.5f - c, float(j - 2) + 0.5f - c, float(k - 2) + 0.5f - c);
        }
    return g;
  };
  EXPECT_EQ(ff::mostBranches(
                solid(30, [](float x, float y,
                             float z) { return std::fabs(y) < 1.5f && x * x + z * z < 15.0f * 15.0f; })),
            1);
  EXPECT_EQ(
      ff::mostBranches(solid(20, [](float x, float y, float z) { return x * x + y * y + z * z < 100.0f; })),
      0);
}

// Coarse clusters on crossings: an X with no limbs (shorter than 38 voxels)
// and no loop gets the coarse level over the whole shape with coarse_bars 1,
// the clusters of coarse_bars 0 and more than one level's; an L (its two
// strokes meet at a corner, no junction) keeps one level. Without the rule
// the X keeps one level and the test fails.
TEST(ShapeMatching, CoarseClustersCoverAShapeWhoseStrokesCross) {
  auto clusters = [](const std::vector<Stroke>& letter, int coarse, int bars) {
    const ff::TargetShape t = targetOf(letterGrid(letter, 3.0f, 7, 1));
    ff::ShapeMatchParams sm;
    sm.coarse_clusters = coarse, sm.coarse_bars = bars;
    const ff::ControlSet s = ff::placeControlParticles(t, t.boundsMin(), t.boundsMax(), sm,
                                                       ff::Vec3(-1, -1, -1), ff::Vec3(1, 1, 1));
    return std::make_pair(s.clusters.start, s.clusters.members);
  };
  const auto x_one = clusters(kLetterX, 0, 1), x_rule = clusters(kLetterX, 3, 1),
             x_whole = clusters(kLetterX, 3, 0);
  EXPECT_EQ(x_rule, x_whole);
  EXPECT_GT(x_rule.first.size(), x_one.first.size());
  EXPECT_EQ(clusters(kLetterL, 3, 1), clusters(kLetterL, 0, 1));
  EXPECT_NE(clusters(kLetterL, 3, 0),
            clusters(kLetterL, 0, 1));  // the L does have coarse clusters to leave out
}
