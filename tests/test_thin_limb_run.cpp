// test_thin_limb_run.cpp - thin features as a run (docs/CONTROL_UNITS.md,
// "The velocity force and thin figures"): a figure with a torso and two thin
// arms spread sideways at its shoulders, 3/4 of its height up, forms from a
// block of fluid on the floor, on the water preset. Whether a voxel of the
// target holds fluid is judged as docs/METRICS.md defines `filled`, written
// out here independently: the SPH density (poly6, brute force over every
// fluid particle) at the voxel's centre, placed by the control particles'
// best rigid fit, is at least half the rest density. The torso's voxels are
// the reference: a formed part fills them all. The arms must fill as the
// torso does with the water preset's velocity force (eq. 6 at `velocity_rate`
// 1.45), and measurably less at the rate it halved (2.9), where eq. 6 ties
// the fluid to the control particles it reached first and little of it
// flows through the filled torso out into the arms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "control/shape_matching.h"
#include "core/params.h"
#include "cpu/backend_cpu.h"
#include "ff_rotation.h"
#include "sim/simulation.h"
#include "temp_dir.h"
#include "test_scenes.h"

namespace {

using Cell = std::tuple<int, int, int>;

// The closed surface of a union of unit cubes as OBJ text: every face between
// a cube of the set and one outside it, wound outwards.
std::string blocksObj(const std::set<Cell>& cells) {
  std::map<Cell, int> index;
  std::ostringstream verts, faces;
  auto vert = [&](int x, int y, int z) {
    const Cell v{x, y, z};
    auto it = index.find(v);
    if (it != index.end()) return it->second;
    const int id = int(index.size()) + 1;
    index[v] = id;
    verts << "v " << x << ' ' << y << ' ' << z << '\n';
    return id;
  };
  for (const Cell& c : cells)
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        int n[3] = {std::get<0>(c), std::get<1>(c), std::get<2>(c)};
        n[axis] += side ? 1 : -1;
        if (cells.count(Cell{n[0], n[1], n[2]})) continue;
        const int u = (axis + 1) % 3, w = (axis + 2) % 3;
        int id[4];
        const int du[4] = {0, 1, 1, 0}, dw[4] = {0, 0, 1, 1};
        for (int q = 0; q < 4; ++q) {
          int p[3] = {std::get<0>(c), std::get<1>(c), std::get<2>(c)};
          p[axis] += side, p[u] += du[q], p[w] += dw[q];
          id[q] = vert(p[0], p[1], p[2]);
        }
        if (!side) std::swap(id[1], id[3]);
        faces << "f " << id[0] << ' ' << id[1] << ' ' << id[2] << "\nf " << id[0] << ' ' << id[2] << ' '
              << id[3] << '\n';
      }
  return verts.str() + faces.str();
}

// In cells: a torso 4 x 12 x 4 standing on y = 0, arms 2 x 2 across reaching
// 7 cells out of each side at y 10..12 (the target is scaled to the fluid's
// volume of 3584 fluid particles: a cell is 1.5 cm, an arm 3 cm, about 3
// control voxels and the control radius, thick).
constexpr int kTorsoHalf = 2, kArm = 7, kH = 12, kAY = 10;
std::set<Cell> figureCells() {
  std::set<Cell> cells;
  for (int i = -kTorsoHalf; i < kTorsoHalf; ++i)
    for (int j = 0; j < kH; ++j)
      for (int k = -2; k < 2; ++k) cells.insert({i, j, k});
  for (int i = kTorsoHalf; i < kTorsoHalf + kArm; ++i)
    for (int j = kAY; j < kAY + 2; ++j)
      for (int k = -1; k < 1; ++k) cells.insert({i, j, k}), cells.insert({-i - 1, j, k});
  return cells;
}

struct LimbFill {
  double arms = 0.0, torso = 0.0, iou = 0.0, stray = 0.0;
  long arm_voxels = 0;
};

// SPH density (poly6, support h) of the fluid at p, by brute force.
double densityAt(const ff::FluidState& s, const float p[3], double mass, double h) {
  const double coef = 315.0 / (64.0 * M_PI * std::pow(h, 9.0)), h2 = h * h;
  double rho = 0.0;
  for (size_t e = 0; e < s.size(); ++e) {
    const double dx = s.x[e] - p[0], dy = s.y[e] - p[1], dz = s.z[e] - p[2];
    const double r2 = dx * dx + dy * dy + dz * dz;
    if (r2 < h2) rho += mass * coef * std::pow(h2 - r2, 3.0);
  }
  return rho;
}

// The figure formed over `seconds` with eq. 6's rate `velocity_rate` (0: the
// water preset's).
LimbFill runFigure(const std::string& mesh, float velocity_rate, double seconds) {
  ff::SceneDesc scene = fftest::blockScene(ff::Vec3(0.5f, 0.4f, 0.3f), ff::Vec3(0.2f, 0.0f, 0.1f), 16, 14, 16,
                                           "thin limb test");
  scene.params = ff::presetParams("water");
  // The velocity force alone: the recapture at the speed sqrt(g r) with which
  // the rate was measured (docs/CONTROL_UNITS.md). The water preset's faster
  // recapture (2 sqrt(g r) since 2026-12-01) also lifts fluid into the arms,
  // and hides the rate's effect (arms 0.889 at twice the rate).
  scene.params.control.recapture = 1.0f;
  if (velocity_rate > 0.0f) scene.params.control.velocity_rate = velocity_rate;
  ff::TargetSpec t = fftest::target(ff::TargetKind::Mesh);
  t.mesh = t.resolved_path = mesh;
  scene.schedule.push_back({0.0, t});
  ff::Simulation sim(scene, std::make_unique<ff::CpuBackend>(2));
  const int steps = int(seconds / double(sim.scene().params.fluid.time_step) + 0.5);
  for (int i = 0; i < steps; ++i) sim.step();
  auto& cpu = static_cast<ff::CpuBackend&>(sim.backend());
  const ff::ControlSet& set = cpu.controller().set();
  ff_quat q;
  float c[3];
  ff::bestFitFrame(set, q, c, 50);
  const ff_mat3 R = ff_quat_to_mat3(q);
  const float rest_c[3] = {set.rest_cx, set.rest_cy, set.rest_cz};
  const ff::VoxelGrid& g = sim.target()->grid;
  // The figure's extent along x in voxels: the arms are the voxels beyond
  // the torso's half-width (kTorsoHalf of kTorsoHalf + kArm cells) plus one
  // voxel (the shoulder), the torso those within its half-width less one.
  int lo = g.nx, hi = -1;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        if (g.inside[g.index(i, j, k)]) lo = std::min(lo, i), hi = std::max(hi, i);
  const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo + 1);
  const double torso_half = half * kTorsoHalf / double(kTorsoHalf + kArm);
  const ff::Params& p = sim.scene().params;
  const double mass = p.fluid.particle_mass, h = p.fluid.smoothing_radius, rho0 = p.fluid.rest_density;
  long arm = 0, arm_filled = 0, torso = 0, torso_filled = 0;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        if (!g.inside[g.index(i, j, k)]) continue;
        const double off = std::fabs(i - mid);
        const bool is_arm = off > torso_half + 1.0, is_torso = off < torso_half - 1.0;
        if (!is_arm && !is_torso) continue;
        const ff::Vec3 v = g.center(i, j, k);
        const ff_float3 w =
            ff_mat3_mul_vec(R, FF_F3(v.x() - rest_c[0], v.y() - rest_c[1], v.z() - rest_c[2]));
        const float pw[3] = {w.x + c[0], w.y + c[1], w.z + c[2]};
        const bool full = densityAt(cpu.fluid().s, pw, mass, h) >= 0.5 * rho0;
        (is_arm ? arm : torso) += 1;
        (is_arm ? arm_filled : torso_filled) += full ? 1 : 0;
      }
  LimbFill f;
  f.arm_voxels = arm;
  f.arms = double(arm_filled) / double(arm);
  f.torso = double(torso_filled) / double(torso);
  f.iou = sim.metrics().iou;
  f.stray = sim.metrics().stray;
  return f;
}

TEST(ThinLimbRun, TheArmsOfAFigureFillWithTheWaterPresetsVelocityForce) {
  fftest::TempDir dir("thin_limb_run");
  const std::string mesh = dir.write("figure.obj", blocksObj(figureCells())).string();
  const float water_rate = ff::presetParams("water").control.velocity_rate;
  ASSERT_FLOAT_EQ(water_rate, 1.45f);  // the mechanism under test
  const LimbFill on = runFigure(mesh, 0.0f, 2.0);
  const LimbFill off = runFigure(mesh, 2.0f * water_rate, 2.0);
  for (const auto& [name, f] : {std::pair<const char*, const LimbFill&>{"velocity_rate 1.45", on},
                                std::pair<const char*, const LimbFill&>{"velocity_rate 2.9 ", off}})
    std::printf("  %s: arms filled %.3f (%ld voxels), torso %.3f, iou %.3f, stray %.3f\n", name, f.arms,
                f.arm_voxels, f.torso, f.iou, f.stray);
  ASSERT_GE(on.arm_voxels, 100);  // the arms are resolved
  // The figure formed: its torso is filled and nothing is stray, either way.
  EXPECT_GE(on.torso, 0.95);
  EXPECT_GE(off.torso, 0.95);
  EXPECT_LE(on.stray, 0.01);
  // With the mechanism the arms fill as the torso does (within 0.1); without
  // it they lack at least a fifth of their voxels more than the torso does.
  EXPECT_GE(on.arms, on.torso - 0.1);
  EXPECT_LE(off.arms, off.torso - 0.2);
  EXPECT_GE(on.arms - off.arms, 0.15);
}

// With adaptive control each control particle's own radius acts in eq. 5
// only: eq. 4 and 6, and so the carried gravity and the recapture, reach
// every fluid particle within the control radius of a control particle,
// however small its own radius. On a thin plate (a box 1 x 0.12 x 1, most
// radii below the control radius) the fluid the control reaches after one
// step is exactly the fluid within the control radius of some control
// particle, by brute force, and some of it lies beyond every control
// particle's own radius (it fell out of reach when eq. 4 and 6 used them:
// the thin disc's 9 % stray, docs/RESULTS.md).
TEST(ThinLimbRun, OwnRadiiLeaveNoFluidOutOfTheControlsReach) {
  ff::SceneDesc scene = fftest::blockScene(ff::Vec3(0.3f, 0.2f, 0.3f), ff::Vec3(0.08f, 0.0f, 0.08f), 20, 8,
                                           20, "own radii test");
  ff::TargetSpec plate = fftest::target(ff::TargetKind::Box, 700);
  plate.box_size = ff::Vec3(1.0f, 0.12f, 1.0f);
  scene.schedule.push_back({0.0, plate});
  scene.params.control.adaptive = 1;
  ff::Simulation sim(scene, std::make_unique<ff::CpuBackend>(2));
  auto& cpu = static_cast<ff::CpuBackend&>(sim.backend());
  const float dt = sim.scene().params.fluid.time_step;
  cpu.buildGrid(), cpu.computeDensity(), cpu.computeForces(0.0f);
  cpu.computeControlScale(), cpu.applyControlForces(dt);
  const ff::ControlSet& c = cpu.controller().set();
  const ff::FluidState& s = cpu.fluid().s;
  const std::vector<uint8_t>& reached = cpu.controller().reached();
  const double r = sim.scene().params.control.radius;
  long smaller = 0, within = 0, beyond_own = 0, wrong = 0;
  for (float k : c.radius_scale) smaller += k < 0.99f ? 1 : 0;
  for (size_t e = 0; e < s.size(); ++e) {
    bool in_reach = false, in_own = false;
    for (size_t i = 0; i < c.size(); ++i) {
      const double dx = double(c.x[i]) - s.x[e], dy = double(c.y[i]) - s.y[e], dz = double(c.z[i]) - s.z[e];
      const double d2 = dx * dx + dy * dy + dz * dz, ri = r * c.radius_scale[i];
      in_reach = in_reach || d2 < r * r;
      in_own = in_own || d2 < ri * ri;
    }
    within += in_reach ? 1 : 0;
    beyond_own += in_reach && !in_own ? 1 : 0;
    wrong += (reached[e] != 0) != in_reach ? 1 : 0;
  }
  std::printf(
      "  %ld of %zu radii below the control radius; fluid within the control radius %ld of %zu, "
      "%ld of it beyond every own radius; reached wrongly %ld\n",
      smaller, c.size(), within, s.size(), beyond_own, wrong);
  ASSERT_GT(smaller, long(c.size()) / 2);  // the plate has its own, smaller radii
  EXPECT_GT(beyond_own, 100);              // ... which alone would leave this fluid out of reach
  // Particles within a rounding of the radius may go either way.
  EXPECT_LE(wrong, 2);
  EXPECT_GT(within, 0);
}

}  // namespace
