// test_recapture.cpp - recapture (docs/CONTROL_UNITS.md): controlled fluid out
// of the control's reach is brought back into the target from anywhere in the
// container. A small blob of fluid lies on the floor 0.2 m from the block the
// target forms over: with recapture it ends inside the target, without it it
// stays where it is. And fluid in a torus's hole goes into the ring: the
// recapture aims at the nearest unfilled control particle, never at a point
// outside the shape.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "control/shape_matching.h"
#include "cpu/backend_cpu.h"
#include "metrics/fluid_shares.h"
#include "sim/simulation.h"
#include "test_scenes.h"

namespace {

constexpr long kBlock = 12 * 12 * 12, kBlob = 2 * 2 * 4;

ff::SceneDesc blobScene(float recapture) {
  ff::SceneDesc s;
  s.source = "test";
  s.container.min = ff::Vec3(0, 0, 0);
  s.container.max = ff::Vec3(0.36f, 0.2f, 0.2f);
  ff::FluidBlockDesc block;  // 0.07 m cube at x = 0.03 .. 0.10
  block.origin = ff::Vec3(0.03f, 0.0f, 0.065f);
  block.dims[0] = 12, block.dims[1] = 12, block.dims[2] = 12;
  ff::FluidBlockDesc blob;  // 16 particles (under 1%: they do not stretch the placement) at x = 0.30
  blob.origin = ff::Vec3(0.30f, 0.0f, 0.09f);
  blob.dims[0] = 2, blob.dims[1] = 2, blob.dims[2] = 4;
  s.fluid = {block, blob};
  s.params.control.recapture = recapture;
  ff::TargetSpec sphere;
  sphere.kind = ff::TargetKind::Sphere;
  sphere.control_count = 600;
  s.schedule.push_back({0.0, sphere});
  return s;
}

// The blob's share inside the target (at the control particles' best fit) and
// its share out of every control particle's reach, after `seconds`.
struct BlobEnd {
  double inside = 0.0, stray = 0.0;
};

BlobEnd runBlob(float recapture, double seconds) {
  ff::Simulation sim(blobScene(recapture), std::make_unique<ff::CpuBackend>(2));
  const int steps = int(seconds / double(sim.scene().params.fluid.time_step) + 0.5);
  for (int i = 0; i < steps; ++i) sim.step();
  auto& cpu = static_cast<ff::CpuBackend&>(sim.backend());
  const ff::ControlSet& set = cpu.controller().set();
  ff::RigidFrame frame;
  frame.rest_c[0] = set.rest_cx, frame.rest_c[1] = set.rest_cy, frame.rest_c[2] = set.rest_cz;
  ff::bestFitFrame(set, frame.q, frame.c, 50);
  const ff::FluidState& s = cpu.fluid().s;
  std::vector<uint8_t> blob(s.size(), 0);
  for (long i = kBlock; i < kBlock + kBlob; ++i) blob[size_t(i)] = 1;  // ids follow the blocks' order
  const std::vector<uint8_t>& reached = cpu.controller().reached();
  const ff::FluidShares sh = ff::fluidShares(*sim.target(), frame, 2, s.x.data(), s.y.data(), s.z.data(),
                                             s.id.data(), s.size(), blob.data(), reached.data());
  EXPECT_EQ(sh.controlled, kBlob);
  BlobEnd e;
  e.inside = double(sh.captured) / double(kBlob);
  e.stray = double(sh.stray) / double(kBlob);
  return e;
}

TEST(Recapture, ABlobOnTheFloorFarFromTheTargetEndsInsideIt) {
  const BlobEnd off = runBlob(0.0f, 2.5);
  std::printf("  without recapture: blob inside %.3f, out of reach %.3f\n", off.inside, off.stray);
  EXPECT_EQ(off.inside, 0.0);  // the control alone never reaches 0.2 m
  EXPECT_EQ(off.stray, 1.0);
  const BlobEnd on = runBlob(1.0f, 2.5);
  std::printf("  with recapture:    blob inside %.3f, out of reach %.3f\n", on.inside, on.stray);
  EXPECT_GE(on.inside, 0.75);
  EXPECT_EQ(on.stray, 0.0);
}

// A torus target formed over a block of fluid: the block's middle lies in the
// torus's hole, farther than the control radius from every control particle
// (checked below). The recapture must bring that fluid into the ring; aimed at
// the centre of the unfilled control particles (the recapture before it aimed
// per particle) it floated, weightless, in the hole.
struct TorusEnd {
  double inside = 0.0, stray = 0.0, in_hole = 0.0, hole_at_start = 0.0;
};

// The share of the fluid (x, y, z) in the torus's hole: nearer its axis than
// the innermost control particle less the control radius, within the control
// particles' height, judged from the control particles themselves (the ring's
// axis is vertical: the torus is not rotated).
double holeShare(const ff::ControlSet& c, const ff::FluidState& s, float r) {
  double cx = 0.0, cz = 0.0, ylo = 1e9, yhi = -1e9;
  for (size_t i = 0; i < c.size(); ++i) cx += c.x[i], cz += c.z[i];
  cx /= double(c.size()), cz /= double(c.size());
  double inner = 1e9;
  for (size_t i = 0; i < c.size(); ++i) {
    inner = std::min(inner, std::hypot(c.x[i] - cx, c.z[i] - cz));
    ylo = std::min(ylo, double(c.y[i])), yhi = std::max(yhi, double(c.y[i]));
  }
  EXPECT_GT(inner, 1.5 * r) << "the torus's hole is too small for the test";
  long n = 0;
  for (size_t i = 0; i < s.size(); ++i)
    n += std::hypot(s.x[i] - cx, s.z[i] - cz) < inner - r && s.y[i] > ylo - r && s.y[i] < yhi + r;
  return double(n) / double(s.size());
}

TorusEnd runTorus(double seconds) {
  ff::SceneDesc scene =
      fftest::blockScene(ff::Vec3(0.36f, 0.25f, 0.36f), ff::Vec3(0.085f, 0.0f, 0.085f), 30, 7, 30);
  ff::TargetSpec torus = fftest::target(ff::TargetKind::Torus, 700);
  torus.torus_major = 1.0f, torus.torus_minor = 0.3f;
  scene.schedule.push_back({0.0, torus});
  ff::Simulation sim(scene, std::make_unique<ff::CpuBackend>(2));
  auto& cpu = static_cast<ff::CpuBackend&>(sim.backend());
  const float r = sim.scene().params.control.radius;
  TorusEnd e;
  const int steps = int(seconds / double(sim.scene().params.fluid.time_step) + 0.5);
  for (int i = 0; i < steps; ++i) {
    sim.step();
    if (i == 0) e.hole_at_start = holeShare(cpu.controller().set(), cpu.fluid().s, r);
  }
  const ff::ControlSet& set = cpu.controller().set();
  ff::RigidFrame frame;
  frame.rest_c[0] = set.rest_cx, frame.rest_c[1] = set.rest_cy, frame.rest_c[2] = set.rest_cz;
  ff::bestFitFrame(set, frame.q, frame.c, 50);
  const ff::FluidState& s = cpu.fluid().s;
  const ff::FluidShares sh =
      ff::fluidShares(*sim.target(), frame, 2, s.x.data(), s.y.data(), s.z.data(), s.id.data(), s.size(),
                      nullptr, cpu.controller().reached().data());
  e.inside = double(sh.captured) / double(s.size());
  e.stray = double(sh.stray) / double(s.size());
  e.in_hole = holeShare(set, s, r);
  return e;
}

TEST(Recapture, FluidInATorusHoleGoesIntoTheRing) {
  const TorusEnd e = runTorus(2.5);
  std::printf(
      "  in the hole at the start %.3f; after 2.5 s: in the hole %.3f, inside the torus %.3f, "
      "out of reach %.3f\n",
      e.hole_at_start, e.in_hole, e.inside, e.stray);
  EXPECT_GE(e.hole_at_start, 0.02);  // the hole starts with fluid in it
  EXPECT_LE(e.in_hole, 0.01);
  EXPECT_LE(e.stray, 0.05);
  EXPECT_GE(e.inside, 0.8);
}

}  // namespace

// A shape that reads full still draws in the fluid wholly out of its reach.
// SPH density fills a control particle's kernel at half the rest density, so
// every control particle reads filled (the recapture's fade is 0) while part
// of the fluid still lies out of reach (7% of Fig. 12's box on the water
// preset, on the floor). Here a torus of a quarter of the fluid's volume lies
// in a block of fluid: all its control particles read filled, the block's
// corners are out of reach. After one step of the control, each fluid
// particle out of reach has lost its weight and is drawn at half strength
// towards a control particle near the nearest one: its acceleration
// (without gravity) is 0.5 v / (1 / rate + dt) (speed v = recapture sqrt(g r),
// rate sqrt(g / r), docs/CONTROL_UNITS.md, "Recapture"), computed here from
// the parameters, pointing at a control particle no more than a field cell's
// diagonal (the field's own accuracy) farther than the nearest, by brute
// force. Before the fix the fade's 0 switched the recapture off: no
// acceleration at all.
TEST(Recapture, FluidOutOfReachIsDrawnInWhileTheShapeReadsFull) {
  ff::Simulation sim(fftest::immersedTorusScene(), std::make_unique<ff::CpuBackend>(2));
  auto& cpu = static_cast<ff::CpuBackend&>(sim.backend());
  const ff::Params& p = sim.scene().params;
  const float dt = p.fluid.time_step;
  cpu.buildGrid(), cpu.computeDensity(), cpu.computeForces(0.0f);
  const ff::FluidState& s = cpu.fluid().s;
  const std::vector<float> ax0 = cpu.fluid().ax, ay0 = cpu.fluid().ay, az0 = cpu.fluid().az;
  cpu.computeControlScale(), cpu.applyControlForces(dt);
  const ff::ControlSet& c = cpu.controller().set();
  const std::vector<float>& cs = cpu.controller().fields().s;
  const long unfilled = std::count_if(cs.begin(), cs.end(), [](float v) { return v > 0.5f; });
  ASSERT_EQ(unfilled, 0) << "a control particle reads unfilled: the shape is not full";
  const std::vector<uint8_t>& reached = cpu.controller().reached();
  const float* g = p.fluid.gravity;
  const double gm = std::sqrt(double(g[0]) * g[0] + double(g[1]) * g[1] + double(g[2]) * g[2]);
  const double r = p.control.radius, speed = p.control.recapture * std::sqrt(gm * r),
               rate = std::sqrt(gm / r), expect = 0.5 * speed / (1.0 / rate + double(dt));
  const double diag = std::sqrt(3.0) * double(cpu.controller().recaptureField().geom().fcell);
  long out = 0, right = 0;
  double worst = 0.0;
  for (size_t i = 0; i < s.size(); ++i) {
    if (reached[i]) continue;
    ++out;
    // The recapture's part: the change of acceleration, its weight given back.
    const double a[3] = {double(cpu.fluid().ax[i]) - ax0[i] + g[0], double(cpu.fluid().ay[i]) - ay0[i] + g[1],
                         double(cpu.fluid().az[i]) - az0[i] + g[2]};
    const double am = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    worst = std::max(worst, std::fabs(am - expect) / expect);
    double nearest = 1e30;
    std::vector<double> dist(c.size());
    for (size_t k = 0; k < c.size(); ++k) {
      dist[k] = std::sqrt(std::pow(double(c.x[k]) - s.x[i], 2) + std::pow(double(c.y[k]) - s.y[i], 2) +
                          std::pow(double(c.z[k]) - s.z[i], 2));
      nearest = std::min(nearest, dist[k]);
    }
    bool aims = false;  // along the line to a control particle near the nearest
    for (size_t k = 0; k < c.size() && !aims && am > 0.0; ++k) {
      if (dist[k] > nearest + diag) continue;
      const double cosang = (a[0] * (double(c.x[k]) - s.x[i]) + a[1] * (double(c.y[k]) - s.y[i]) +
                             a[2] * (double(c.z[k]) - s.z[i])) /
                            (am * dist[k]);
      aims = cosang > 1.0 - 1e-5;
    }
    right += aims;
  }
  std::printf(
      "  %zu control particles, all filled; %ld of %zu fluid particles out of reach, %ld aimed "
      "at a control particle near the nearest; worst |a| error %.2g of %.3g m/s^2\n",
      c.size(), out, s.size(), right, worst, expect);
  ASSERT_GT(out, 100) << "no fluid out of reach";
  EXPECT_EQ(right, out);
  EXPECT_LE(worst, 1e-4);
}
