// test_target_voxelize.cpp - voxelisation of analytic shapes and meshes, the
// control-count search, robustness to holes and duplicated faces, and the
// target cache.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "core/error.h"
#include "target/analytic_shapes.h"
#include "target/mesh_io.h"
#include "target/target_shape.h"
#include "target/voxelize.h"
#include "temp_dir.h"
#include "test_meshes.h"

namespace fs = std::filesystem;
using ff::TargetKind;
using ff::TargetShape;
using ff::TargetSpec;

namespace {

constexpr double kPi = 3.14159265358979323846;
// The paper's Table 1 fluid: 12000 particles of 0.0002 kg at 800 kg/m^3.
constexpr double kFluidVolume = 12000 * 0.0002 / 800.0;

double relativeError(double value, double reference) {
  return std::abs(value - reference) / reference;
}

TargetSpec analyticSpec(TargetKind kind) {
  TargetSpec spec;
  spec.kind = kind;
  return spec;
}

TargetSpec meshSpec(const std::string& file, const std::string& path) {
  TargetSpec spec;
  spec.kind = TargetKind::Mesh;
  spec.mesh = file;
  spec.resolved_path = path;
  return spec;
}

// The structural promises of a target, checked against the grid it carries.
void expectConsistent(const TargetShape& t) {
  const ff::VoxelGrid& g = t.grid;
  ASSERT_EQ(g.inside.size(), size_t(g.nx) * g.ny * g.nz);
  EXPECT_EQ(t.reference.size(), g.countInside());
  size_t n = 0;
  for (int k = 0; k < g.nz; ++k) {
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        if (!g.inside[g.index(i, j, k)]) continue;
        const bool border = i == 0 || j == 0 || k == 0 || i == g.nx - 1 || j == g.ny - 1 || k == g.nz - 1;
        EXPECT_FALSE(border) << "inside voxel on the grid border at " << i << " " << j << " " << k;
        ASSERT_LT(n, t.reference.size());
        EXPECT_EQ(t.reference[n], g.center(i, j, k)) << "reference " << n << " out of index order";
        ++n;
      }
    }
  }
  EXPECT_EQ(n, t.reference.size());
}

// Simple OBJ text I/O for the tests' own mesh surgery (independent of assimp).
struct ObjText {
  std::vector<std::array<double, 3>> v;
  std::vector<std::array<int, 3>> f;  // 0-based
};

ObjText readObj(const std::string& path) {
  ObjText obj;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "v") {
      std::array<double, 3> p{};
      words >> p[0] >> p[1] >> p[2];
      obj.v.push_back(p);
    } else if (tag == "f") {
      std::array<int, 3> t{};
      words >> t[0] >> t[1] >> t[2];
      obj.f.push_back({t[0] - 1, t[1] - 1, t[2] - 1});
    }
  }
  return obj;
}

void writeObj(const ObjText& obj, const std::string& path) {
  std::ofstream out(path);
  out.precision(9);
  for (const auto& p : obj.v) out << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
  for (const auto& t : obj.f) out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
}

// Indices of the faces of `obj`, largest first by their smallest projected
// area onto the x, y and z planes: rays along every axis cross the first ones.
std::vector<size_t> facesSeenByAllAxes(const ObjText& obj) {
  std::vector<double> key(obj.f.size());
  for (size_t i = 0; i < key.size(); ++i) {
    const auto& t = obj.f[i];
    const Eigen::Vector3d a(obj.v[t[0]].data()), b(obj.v[t[1]].data()), c(obj.v[t[2]].data());
    key[i] = 0.5 * (b - a).cross(c - a).cwiseAbs().minCoeff();
  }
  std::vector<size_t> order(obj.f.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return key[a] > key[b]; });
  return order;
}

}  // namespace

// ---- analytic shapes -------------------------------------------------------------

TEST(TargetAnalytic, VolumesFollowTheFormulas) {
  TargetSpec box = analyticSpec(TargetKind::Box);
  box.box_size = ff::Vec3(1.0f, 2.0f, 0.5f);
  EXPECT_NEAR(ff::makeAnalyticShape(box).volume(), 1.0, 1e-12);
  EXPECT_NEAR(ff::makeAnalyticShape(analyticSpec(TargetKind::Sphere)).volume(), 4.0 / 3.0 * kPi, 1e-12);
  TargetSpec torus = analyticSpec(TargetKind::Torus);
  torus.torus_major = 1.5f;
  torus.torus_minor = 0.5f;
  EXPECT_NEAR(ff::makeAnalyticShape(torus).volume(), 2.0 * kPi * kPi * 1.5 * 0.25, 1e-9);
  TargetSpec capsule = analyticSpec(TargetKind::Capsule);
  capsule.capsule_radius = 0.5f;
  capsule.capsule_length = 2.0f;
  EXPECT_NEAR(ff::makeAnalyticShape(capsule).volume(), kPi * 0.25 * 2.0 + 4.0 / 3.0 * kPi * 0.125, 1e-9);
  for (const TargetSpec& spec : {box, torus, capsule}) {
    EXPECT_NEAR(ff::scaledToVolume(ff::makeAnalyticShape(spec), 0.003).volume(), 0.003, 1e-12);
  }
}

TEST(TargetAnalytic, InsideTestsAgreeWithMonteCarloAndBoundsAreTight) {
  // Monte Carlo volume from inside() over the bounding box from halfExtent(),
  // for rotated shapes: checks the inside tests, the rotation and the bounds
  // (no sample may be inside outside the bounds; the bounds must be touched).
  std::mt19937 random(4242);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  TargetSpec specs[4] = {analyticSpec(TargetKind::Sphere), analyticSpec(TargetKind::Box),
                         analyticSpec(TargetKind::Torus), analyticSpec(TargetKind::Capsule)};
  specs[1].box_size = ff::Vec3(1.0f, 0.6f, 0.3f);
  for (TargetSpec& spec : specs) {
    spec.rotation_deg = ff::Vec3(30.0f, 50.0f, -20.0f);
    const ff::AnalyticShape shape = ff::makeAnalyticShape(spec);
    const Eigen::Vector3d half = shape.halfExtent();
    const int samples = 200000;
    int hits = 0;
    Eigen::Vector3d reach = Eigen::Vector3d::Zero();
    for (int s = 0; s < samples; ++s) {
      const Eigen::Vector3d p(unit(random) * half.x(), unit(random) * half.y(), unit(random) * half.z());
      if (shape.inside(p)) {
        ++hits;
        reach = reach.cwiseMax(p.cwiseAbs().cwiseQuotient(half));
      }
      Eigen::Vector3d beyond = p;  // a point just outside the bounds on one axis
      const int axis = s % 3;
      beyond[axis] = (p[axis] < 0 ? -1.0 : 1.0) * half[axis] * (1.0 + 1e-6 + 0.5 * std::abs(unit(random)));
      EXPECT_FALSE(shape.inside(beyond)) << spec.label() << ": inside beyond the bounds";
    }
    const double estimate = 8.0 * half.prod() * hits / samples;
    EXPECT_LT(relativeError(estimate, shape.volume()), 0.02) << spec.label();
    EXPECT_GT(reach.minCoeff(), 0.9) << spec.label() << ": bounds not tight";
  }
}

TEST(TargetAnalytic, StandingTorusBounds) {
  TargetSpec torus = analyticSpec(TargetKind::Torus);
  torus.torus_major = 1.0f;
  torus.torus_minor = 0.25f;
  torus.rotation_deg = ff::Vec3(90.0f, 0.0f, 0.0f);  // axis y -> z
  const Eigen::Vector3d half = ff::makeAnalyticShape(torus).halfExtent();
  EXPECT_NEAR(half.x(), 1.25, 1e-6);
  EXPECT_NEAR(half.y(), 1.25, 1e-6);
  EXPECT_NEAR(half.z(), 0.25, 1e-6);
}

TEST(TargetAnalytic, RotationIsXThenYThenZ) {
  // Box 1 x 2 x 3: Rx(90) gives extents (1, 3, 2), then Ry(90) gives (2, 3, 1).
  TargetSpec box = analyticSpec(TargetKind::Box);
  box.box_size = ff::Vec3(1.0f, 2.0f, 3.0f);
  box.rotation_deg = ff::Vec3(90.0f, 90.0f, 0.0f);
  const Eigen::Vector3d half = ff::makeAnalyticShape(box).halfExtent();
  EXPECT_NEAR(half.x(), 1.0, 1e-6);
  EXPECT_NEAR(half.y(), 1.5, 1e-6);
  EXPECT_NEAR(half.z(), 0.5, 1e-6);
}

TEST(TargetAnalytic, BadProportionsAreErrors) {
  TargetSpec torus = analyticSpec(TargetKind::Torus);
  torus.torus_major = 0.3f;
  torus.torus_minor = 0.4f;
  EXPECT_THROW(ff::makeAnalyticShape(torus), ff::Error);
  TargetSpec box = analyticSpec(TargetKind::Box);
  box.box_size = ff::Vec3(1.0f, 0.0f, 1.0f);
  EXPECT_THROW(ff::makeAnalyticShape(box), ff::Error);
  TargetSpec capsule = analyticSpec(TargetKind::Capsule);
  capsule.capsule_radius = -1.0f;
  EXPECT_THROW(ff::makeAnalyticShape(capsule), ff::Error);
}

TEST(TargetVoxelize, SphereAndBoxVolumesWithin2Percent) {
  TargetSpec box = analyticSpec(TargetKind::Box);
  box.box_size = ff::Vec3(1.0f, 1.7f, 0.6f);
  box.rotation_deg = ff::Vec3(0.0f, 25.0f, 0.0f);
  for (TargetSpec spec : {analyticSpec(TargetKind::Sphere), box}) {
    spec.control_count = 4000;
    const TargetShape t = ff::buildTarget(spec, kFluidVolume, 0.0f);
    EXPECT_NEAR(t.shape_volume, kFluidVolume, 1e-9);
    EXPECT_LT(relativeError(t.voxel_volume(), kFluidVolume), 0.02)
        << spec.label() << " " << t.reference.size();
    expectConsistent(t);
  }
}

TEST(TargetVoxelize, TorusAndCapsuleVolumesWithin3Percent) {
  TargetSpec torus = analyticSpec(TargetKind::Torus);
  torus.rotation_deg = ff::Vec3(90.0f, 0.0f, 0.0f);
  TargetSpec capsule = analyticSpec(TargetKind::Capsule);
  for (TargetSpec spec : {torus, capsule}) {
    spec.control_count = 3000;
    spec.volume = 0.002f;
    const TargetShape t = ff::buildTarget(spec, kFluidVolume, 0.0f);
    EXPECT_NEAR(t.shape_volume, 0.002, 1e-9);
    EXPECT_LT(relativeError(t.voxel_volume(), 0.002), 0.03) << spec.label() << " " << t.reference.size();
    expectConsistent(t);
  }
}

TEST(TargetVoxelize, GivenVoxelSizeIsUsedAndSphereBoundsMatchItsRadius) {
  TargetSpec sphere = analyticSpec(TargetKind::Sphere);
  sphere.voxel_size = 0.01f;
  const TargetShape t = ff::buildTarget(sphere, kFluidVolume, 0.0f);
  EXPECT_EQ(t.grid.voxel, 0.01f);
  EXPECT_EQ(t.label, "sphere");
  const double radius = std::cbrt(kFluidVolume * 3.0 / (4.0 * kPi));
  for (int a = 0; a < 3; ++a) {  // centred at the origin, reaching the radius to within a voxel
    EXPECT_NEAR(t.boundsMax()[a], radius, 0.01);
    EXPECT_NEAR(t.boundsMin()[a], -radius, 0.01);
  }
  EXPECT_LT(relativeError(t.voxel_volume(), kFluidVolume), 0.02);
  // The default voxel size applies when neither count nor size is given.
  sphere.voxel_size = 0.0f;
  EXPECT_EQ(ff::buildTarget(sphere, kFluidVolume, 0.012f).grid.voxel, 0.012f);
}

TEST(TargetVoxelize, BadRequestsAreErrors) {
  TargetSpec sphere = analyticSpec(TargetKind::Sphere);
  sphere.voxel_size = 0.2f;  // the whole 0.003 m^3 sphere is smaller than a voxel or two
  try {
    ff::buildTarget(sphere, kFluidVolume, 0.0f);
    ADD_FAILURE() << "no error";
  } catch (const ff::Error& e) {
    EXPECT_NE(std::string(e.what()).find("too small"), std::string::npos) << e.what();
  }
  sphere.control_count = 100;  // both count and size
  EXPECT_THROW(ff::buildTarget(sphere, kFluidVolume, 0.0f), ff::Error);
  sphere.voxel_size = 0.0f;
  EXPECT_THROW(ff::buildTarget(sphere, 0.0, 0.0f), ff::Error);  // no volume
  sphere.control_count = 0;
  EXPECT_THROW(ff::buildTarget(sphere, kFluidVolume, 0.0f), ff::Error);  // no voxel size at all
  sphere.voxel_size = 1e-6f;                                             // absurdly fine grid
  EXPECT_THROW(ff::buildTarget(sphere, kFluidVolume, 0.0f), ff::Error);
}

// ---- meshes ----------------------------------------------------------------------

TEST(TargetVoxelize, RotatedCubeMeshMatchesAnExactInsideTest) {
  // A unit cube, rotated so that its edges cross the columns at all sorts of
  // angles; every voxel centre must be classified like |R^T p|_inf <= 1/2.
  ff::TriangleMesh cube;
  for (int k = 0; k < 8; ++k)
    cube.vertices.emplace_back(float(k & 1) - 0.5f, float((k >> 1) & 1) - 0.5f, float((k >> 2) & 1) - 0.5f);
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    cube.triangles.push_back({q[0], q[1], q[2]});
    cube.triangles.push_back({q[0], q[2], q[3]});
  }
  const Eigen::Matrix3f rotation =
      (Eigen::AngleAxisf(0.4f, Eigen::Vector3f::UnitX()) * Eigen::AngleAxisf(0.7f, Eigen::Vector3f::UnitY()) *
       Eigen::AngleAxisf(-0.3f, Eigen::Vector3f::UnitZ()))
          .toRotationMatrix();
  for (auto& p : cube.vertices) p = rotation * p;
  ff::Vec3 lo, hi;
  ff::meshBounds(cube, lo, hi);
  ff::VoxelGrid grid = ff::makeVoxelGrid(lo, hi, 0.05f, ff::Vec3(0.2f, -0.1f, 0.3f));
  ff::voxelizeMesh(cube, grid);
  size_t inside = 0, mismatches = 0;
  for (int k = 0; k < grid.nz; ++k) {
    for (int j = 0; j < grid.ny; ++j) {
      for (int i = 0; i < grid.nx; ++i) {
        const float d = (rotation.transpose() * grid.center(i, j, k)).cwiseAbs().maxCoeff();
        if (std::abs(d - 0.5f) < 1e-5f) continue;  // too close to call
        inside += d < 0.5f;
        mismatches += (d < 0.5f) != (grid.inside[grid.index(i, j, k)] != 0);
      }
    }
  }
  EXPECT_GT(inside, 6000u);  // (1 / 0.05)^3 = 8000
  EXPECT_EQ(mismatches, 0u);
}

TEST(TargetVoxelize, RaysThroughVerticesAndEdgesCountOnce) {
  // An axis-aligned box [2h, 8h]^3 (grid frame) whose faces are tessellated
  // with vertices at every half voxel: rays pass (almost) exactly through
  // vertices and diagonals. The exact answer is 6 x 6 x 6 voxels.
  const float h = 0.1f;
  ff::VoxelGrid grid = ff::makeVoxelGrid(ff::Vec3::Zero(), ff::Vec3::Constant(0.8f), h);
  const ff::Vec3 o =
      grid.origin + ff::Vec3::Constant(h);  // box corner on voxel boundaries, away from the border
  ff::TriangleMesh box;
  const int m = 12;  // 6 voxels, vertices every h/2
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const int base = int(box.vertices.size());
      for (int b = 0; b <= m; ++b) {
        for (int a = 0; a <= m; ++a) {
          ff::Vec3 p;
          p[axis] = o[axis] + 6.0f * h * side;
          p[u] = o[u] + 0.5f * h * a;
          p[v] = o[v] + 0.5f * h * b;
          box.vertices.push_back(p);
        }
      }
      for (int b = 0; b < m; ++b) {
        for (int a = 0; a < m; ++a) {
          const int i00 = base + a + (m + 1) * b, i10 = i00 + 1, i01 = i00 + m + 1, i11 = i01 + 1;
          if (side == 1) {
            box.triangles.push_back({i00, i10, i11});
            box.triangles.push_back({i00, i11, i01});
          } else {
            box.triangles.push_back({i00, i11, i10});
            box.triangles.push_back({i00, i01, i11});
          }
        }
      }
    }
  }
  ASSERT_NEAR(std::abs(ff::meshVolume(box)), std::pow(0.6, 3), 1e-5);
  for (int axis = 0; axis < 3; ++axis) {  // every single axis must already be exact
    std::vector<uint8_t> parity;
    ff::rayParity(box, grid, axis, parity);
    size_t count = 0;
    for (uint8_t p : parity) count += p;
    EXPECT_EQ(count, 216u) << "axis " << axis;
  }
  ff::voxelizeMesh(box, grid);
  EXPECT_EQ(grid.countInside(), 216u);
}

TEST(TargetVoxelize, BunnyVoxelVolumeWithin2PercentOfMeshVolume) {
  FF_MESH_OR_SKIP(bunny_path, "bunny.obj");
  TargetSpec bunny = meshSpec("bunny.obj", bunny_path);
  bunny.control_count = 3197;
  bunny.volume = 0.003f;
  const TargetShape t = ff::buildTarget(bunny, 1.0, 0.0f);
  // The continuous volume, recomputed from the file by the divergence theorem
  // and scaled like buildTarget must have scaled it.
  EXPECT_LT(relativeError(t.shape_volume, 0.003), 1e-5);
  EXPECT_LT(relativeError(t.voxel_volume(), 0.003), 0.02) << t.reference.size();
  EXPECT_EQ(t.label, "bunny.obj");
  expectConsistent(t);
  // The bounding box is centred at the origin (to within a voxel).
  EXPECT_LT((t.boundsMin() + t.boundsMax()).cwiseAbs().maxCoeff(), 2.0f * t.grid.voxel);
}

TEST(TargetVoxelize, MeshRotationTurnsTheShape) {
  // The teapot is 6.4 x 3.1 x 4 (x, y, z); rotated 90 degrees about z its
  // long side runs along y.
  FF_MESH_OR_SKIP(teapot_path, "teapot.obj");
  TargetSpec teapot = meshSpec("teapot.obj", teapot_path);
  teapot.voxel_size = 0.008f;
  const TargetShape plain = ff::buildTarget(teapot, kFluidVolume, 0.0f);
  teapot.rotation_deg = ff::Vec3(0.0f, 0.0f, 90.0f);
  const TargetShape turned = ff::buildTarget(teapot, kFluidVolume, 0.0f);
  const ff::Vec3 a = plain.boundsMax() - plain.boundsMin(), b = turned.boundsMax() - turned.boundsMin();
  EXPECT_NEAR(b.y(), a.x(), 2.0f * 0.008f);
  EXPECT_NEAR(b.x(), a.y(), 2.0f * 0.008f);
  EXPECT_NEAR(b.z(), a.z(), 2.0f * 0.008f);
  EXPECT_GT(a.x(), 1.8f * a.y());
  EXPECT_NEAR(double(turned.reference.size()), double(plain.reference.size()), 0.03 * plain.reference.size());
  // x first, then y: (x, y, z) extents -> (x, z, y) -> (y, z, x).
  teapot.rotation_deg = ff::Vec3(90.0f, 90.0f, 0.0f);
  const TargetShape both = ff::buildTarget(teapot, kFluidVolume, 0.0f);
  const ff::Vec3 c = both.boundsMax() - both.boundsMin();
  EXPECT_NEAR(c.x(), a.y(), 2.0f * 0.008f);
  EXPECT_NEAR(c.y(), a.z(), 2.0f * 0.008f);
  EXPECT_NEAR(c.z(), a.x(), 2.0f * 0.008f);
}

struct Table1Case {
  const char* file;
  int count;
};

std::ostream& operator<<(std::ostream& out, const Table1Case& c) {
  return out << c.file << " at " << c.count;
}

class TargetTable1 : public ::testing::TestWithParam<Table1Case> {};

TEST_P(TargetTable1, ControlCountWithin3Percent) {
  FF_MESH_OR_SKIP(path, GetParam().file);
  TargetSpec spec = meshSpec(GetParam().file, path);
  spec.control_count = GetParam().count;
  const TargetShape t = ff::buildTarget(spec, kFluidVolume, 0.0f);
  EXPECT_LE(std::abs(double(t.reference.size()) - GetParam().count), 0.03 * GetParam().count)
      << t.reference.size() << " at voxel size " << t.grid.voxel;
  EXPECT_EQ(t.reference.size(), t.grid.countInside());
  EXPECT_LT(relativeError(t.shape_volume, kFluidVolume), 1e-5);
  // The voxel volume follows the continuous volume (coarser for the runner's thin limbs).
  EXPECT_LT(relativeError(t.voxel_volume(), kFluidVolume), 0.06);
  expectConsistent(t);
}

INSTANTIATE_TEST_SUITE_P(Meshes, TargetTable1,
                         ::testing::Values(Table1Case{"bunny.obj", 3197}, Table1Case{"teapot.obj", 2154},
                                           Table1Case{"runner.obj", 549}, Table1Case{"dragon.obj", 2714}),
                         [](const ::testing::TestParamInfo<Table1Case>& info) {
                           std::string name = info.param.file;
                           return name.substr(0, name.find('.'));
                         });

// ---- holes and non-manifold faces ---------------------------------------------------

namespace {

// Voxelises the closed bunny_lowres and a copy damaged at the faces
// `damaged_faces` (indices into the closed mesh) on the same grid (about 60000
// voxels, so that rays along every axis cross the damaged faces). A single
// axis's parity flips whole columns through the damage, far from it; the
// majority vote may only differ right next to the damage (voxels two of whose
// rays cross it), and the volume stays right.
void expectDamageTolerated(const std::string& closed_path, const ObjText& original, const ObjText& damaged,
                           const std::vector<size_t>& damaged_faces, const std::string& name) {
  const fftest::TempDir dir("voxelize");
  const std::string damaged_path = (dir / name).string();
  writeObj(damaged, damaged_path);
  const ff::TriangleMesh closed = ff::loadMesh(closed_path);
  const ff::TriangleMesh broken = ff::loadMesh(damaged_path);

  const double volume = ff::meshVolume(closed);
  ff::Vec3 lo, hi;
  ff::meshBounds(closed, lo, hi);
  const float h = float(std::cbrt(volume / 60000.0));
  ff::VoxelGrid a = ff::makeVoxelGrid(lo, hi, h), b = a;
  ff::voxelizeMesh(closed, a);
  ff::voxelizeMesh(broken, b);

  // The damaged region, widened by two voxels.
  Eigen::AlignedBox3f near_damage;
  for (size_t f : damaged_faces) {
    for (int k : original.f[f]) near_damage.extend(Eigen::Vector3d(original.v[k].data()).cast<float>());
  }
  near_damage.min().array() -= 2.0f * h;
  near_damage.max().array() += 2.0f * h;
  auto differences = [&](const std::vector<uint8_t>& x, const std::vector<uint8_t>& y, size_t* far) {
    size_t all = 0;
    *far = 0;
    for (int k = 0; k < a.nz; ++k) {
      for (int j = 0; j < a.ny; ++j) {
        for (int i = 0; i < a.nx; ++i) {
          const size_t n = a.index(i, j, k);
          if ((x[n] != 0) == (y[n] != 0)) continue;
          ++all;
          *far += !near_damage.contains(a.center(i, j, k));
        }
      }
    }
    return all;
  };
  size_t far = 0;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<uint8_t> pa, pb;
    ff::rayParity(closed, a, axis, pa);
    ff::rayParity(broken, a, axis, pb);
    differences(pa, pb, &far);
    EXPECT_GT(far, 3u) << "no ray along axis " << axis << " crosses the damage: the test proves nothing";
  }
  EXPECT_LE(differences(a.inside, b.inside, &far), 30u);
  EXPECT_EQ(far, 0u);
  const double voxel_volume = double(b.countInside()) * h * h * h;
  EXPECT_LT(relativeError(voxel_volume, volume), 0.02);
}

}  // namespace

TEST(TargetVoxelize, SmallHoleIsTolerated) {
  FF_MESH_OR_SKIP(path, "bunny_lowres.obj");
  const ObjText closed = readObj(path);
  ASSERT_GT(closed.f.size(), 2u) << path;
  const std::vector<size_t> order = facesSeenByAllAxes(closed);
  const std::vector<size_t> removed = {std::max(order[0], order[1]), std::min(order[0], order[1])};
  ObjText holed = closed;
  for (size_t f : removed) holed.f.erase(holed.f.begin() + long(f));  // two faces, the later one first
  expectDamageTolerated(path, closed, holed, removed, "holed_bunny.obj");
}

TEST(TargetVoxelize, DuplicatedFaceIsTolerated) {
  FF_MESH_OR_SKIP(path, "bunny_lowres.obj");
  const ObjText closed = readObj(path);
  ASSERT_GT(closed.f.size(), 2u) << path;
  const std::vector<size_t> order = facesSeenByAllAxes(closed);
  ObjText doubled = closed;
  doubled.f.push_back(closed.f[order[0]]);  // a third face on three edges: non-manifold
  doubled.f.push_back(closed.f[order[1]]);
  expectDamageTolerated(path, closed, doubled, {order[0], order[1]}, "duplicated_bunny.obj");
}

// ---- specs and the cache -------------------------------------------------------------

TEST(TargetSpecs, LabelsAndCacheKeys) {
  TargetSpec mesh = meshSpec("bunny.obj", "/meshes/bunny.obj");
  mesh.mesh = "meshes/bunny.obj";
  EXPECT_EQ(mesh.label(), "bunny.obj");
  EXPECT_EQ(analyticSpec(TargetKind::Torus).label(), "torus");
  const TargetSpec base = analyticSpec(TargetKind::Box);
  EXPECT_EQ(base.cacheKey(0.003f), base.cacheKey(0.003f));
  EXPECT_NE(base.cacheKey(0.003f), base.cacheKey(0.004f));
  std::vector<TargetSpec> variants(6, base);
  variants[0].box_size.x() = 2.0f;
  variants[1].rotation_deg.y() = 10.0f;
  variants[2].control_count = 100;
  variants[3].voxel_size = 0.01f;
  variants[4].kind = TargetKind::Sphere;
  variants[5] = mesh;
  for (const TargetSpec& v : variants) EXPECT_NE(v.cacheKey(0.003f), base.cacheKey(0.003f));
  TargetSpec other_mesh = mesh;
  other_mesh.resolved_path = "/meshes/teapot.obj";
  EXPECT_NE(other_mesh.cacheKey(0.003f), mesh.cacheKey(0.003f));
}

TEST(TargetCache, SameSpecGivesTheSameObject) {
  ff::TargetCache cache;
  TargetSpec sphere = analyticSpec(TargetKind::Sphere);
  sphere.control_count = 500;
  const TargetShape* first = &cache.get(sphere, kFluidVolume, 0.0f);
  const size_t first_count = first->reference.size();
  EXPECT_EQ(&cache.get(sphere, kFluidVolume, 0.0f), first);
  EXPECT_EQ(cache.size(), 1u);

  TargetSpec more = sphere;
  more.control_count = 900;
  const TargetShape* second = &cache.get(more, kFluidVolume, 0.0f);
  EXPECT_NE(second, first);
  EXPECT_GT(second->reference.size(), first_count);
  EXPECT_NE(&cache.get(sphere, 2.0 * kFluidVolume, 0.0f), first);  // another fluid volume
  EXPECT_EQ(cache.size(), 3u);

  // Many more entries later the first reference is still the same, intact object.
  for (int n = 0; n < 20; ++n) {
    TargetSpec box = analyticSpec(TargetKind::Box);
    box.voxel_size = 0.01f + 0.0005f * n;
    cache.get(box, kFluidVolume, 0.0f);
  }
  EXPECT_EQ(cache.size(), 23u);
  EXPECT_EQ(&cache.get(sphere, kFluidVolume, 0.0f), first);
  EXPECT_EQ(first->reference.size(), first_count);
}

TEST(TargetCache, DefaultVoxelSizeIsPartOfTheKey) {
  ff::TargetCache cache;
  const TargetSpec sphere = analyticSpec(TargetKind::Sphere);
  const TargetShape& a = cache.get(sphere, kFluidVolume, 0.01f);
  const TargetShape& b = cache.get(sphere, kFluidVolume, 0.012f);
  EXPECT_NE(&a, &b);
  EXPECT_EQ(a.grid.voxel, 0.01f);
  EXPECT_EQ(b.grid.voxel, 0.012f);
}
