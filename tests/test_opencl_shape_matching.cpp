// Shape matching on the OpenMP backend and on both OpenCL kernel variants
// (scalar: 8 work-items per cluster, sm_cluster_frames_by_lane; lanes: one
// per cluster), on clusters made here so that neither the cluster count (45)
// nor the member counts (14 .. 42) are multiples of 8 or of a work-group
// size: the last work-group holds a partial set of clusters and most clusters
// leave some of their 8 lanes with one member fewer. Every new device buffer
// starts as NaN (FLOWFORM_CL_POISON=1). On PoCL the three must agree bit for
// bit (the summation order is kernels/common/ff_cluster_sums.h on all of
// them); on other devices within the GPU tolerance of tests/gpu_tolerance.h.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "control/placement.h"
#include "cpu/backend_cpu.h"
#include "gpu_tolerance.h"
#include "host/backend_opencl.h"
#include "host/cl_program.h"
#include "sim/simulation.h"
#include "test_scenes.h"

namespace {

// Sets FLOWFORM_CL_POISON=1 for its lifetime, then restores what was there.
class PoisonScope {
 public:
  PoisonScope() {
    const char* v = std::getenv("FLOWFORM_CL_POISON");
    had_ = v != nullptr;
    if (had_) old_ = v;
    setenv("FLOWFORM_CL_POISON", "1", 1);
  }
  ~PoisonScope() {
    if (had_)
      setenv("FLOWFORM_CL_POISON", old_.c_str(), 1);
    else
      unsetenv("FLOWFORM_CL_POISON");
  }

 private:
  bool had_ = false;
  std::string old_;
};

constexpr size_t kClusters = 45;

// Overlapping windows of the control particles (wrapping at the end), cluster
// c from c * stride with stride + 1 + (11 c mod 29) members, so every
// particle is in one at least; rest centres and particle -> cluster lists.
ff::Clusters windowClusters(const ff::ControlSet& s) {
  const size_t n = s.size(), stride = (n + kClusters - 1) / kClusters;
  ff::Clusters cl;
  cl.start.push_back(0);
  std::vector<std::vector<uint32_t>> of(n);
  for (size_t c = 0; c < kClusters; ++c) {
    const size_t size = stride + 1 + (11 * c) % 29;
    double m[3] = {0, 0, 0};
    for (size_t k = 0; k < size; ++k) {
      const uint32_t p = uint32_t((c * stride + k) % n);
      cl.members.push_back(p);
      of[p].push_back(uint32_t(c));
      m[0] += s.x0[p], m[1] += s.y0[p], m[2] += s.z0[p];
    }
    cl.start.push_back(uint32_t(cl.members.size()));
    cl.rest_cx.push_back(float(m[0] / double(size))), cl.rest_cy.push_back(float(m[1] / double(size))),
        cl.rest_cz.push_back(float(m[2] / double(size)));
  }
  cl.of_start.push_back(0);
  for (const auto& list : of) {
    cl.of.insert(cl.of.end(), list.begin(), list.end());
    cl.of_start.push_back(uint32_t(cl.of.size()));
  }
  return cl;
}

// The control particles of a sphere target, turned 0.4 rad about (1, 2, 3)
// about their centre, jittered by up to 2 mm and given random velocities:
// every cluster has a real rotation to find.
void deform(ff::ControlSet& s) {
  std::mt19937 rng(45);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  double c[3] = {0, 0, 0};
  for (size_t p = 0; p < s.size(); ++p) c[0] += s.x[p], c[1] += s.y[p], c[2] += s.z[p];
  for (double& v : c) v /= double(s.size());
  const double ax[3] = {1 / std::sqrt(14.0), 2 / std::sqrt(14.0), 3 / std::sqrt(14.0)}, th = 0.4;
  const double ct = std::cos(th), st = std::sin(th);
  for (size_t p = 0; p < s.size(); ++p) {
    const double r[3] = {s.x0[p] - s.rest_cx, s.y0[p] - s.rest_cy, s.z0[p] - s.rest_cz};
    const double d = ax[0] * r[0] + ax[1] * r[1] + ax[2] * r[2];
    const double x[3] = {ax[1] * r[2] - ax[2] * r[1], ax[2] * r[0] - ax[0] * r[2],
                         ax[0] * r[1] - ax[1] * r[0]};
    double out[3];
    for (int k = 0; k < 3; ++k) out[k] = c[k] + r[k] * ct + x[k] * st + ax[k] * d * (1 - ct) + 0.002 * u(rng);
    s.x[p] = float(out[0]), s.y[p] = float(out[1]), s.z[p] = float(out[2]);
    s.vx[p] = 0.2f * u(rng), s.vy[p] = 0.2f * u(rng), s.vz[p] = 0.2f * u(rng);
  }
}

struct Result {
  std::vector<ff_quat> q;
  std::vector<float> v[9];  // goals x y z, positions x y z, velocities x y z
};

// One shape-matching step after the control scale (for u_bar) on `b`.
template <class B>
void step(B& b, const ff::Params& params, const ff::SceneDesc& scene, const ff::FluidState& fluid,
          const ff::ControlSet& control) {
  b.init(params, scene.container, fluid);
  b.setControl(control);
  b.buildGrid();
  b.computeControlScale();
  EXPECT_EQ(b.shapeMatching(params.shape.time_step), 1);
  ASSERT_EQ(b.firstNonFinite(), ff::Phase::Count);
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

TEST(OpenClShapeMatching, ClusterSumsAgreeOnBothVariantsAndTheCpuBackend) {
  const PoisonScope poison;
  ASSERT_TRUE(ff::clPoisonEnabled());
  // 990 fluid particles (not a multiple of 8) under a sphere target.
  ff::SceneDesc scene =
      fftest::blockScene(ff::Vec3(0.2f, 0.2f, 0.2f), ff::Vec3(0.06f, 0.0f, 0.06f), 9, 11, 10);
  scene.schedule.push_back({0.0, fftest::target(ff::TargetKind::Sphere, 600)});
  ff::Simulation sim(scene, std::make_unique<ff::CpuBackend>(2));
  sim.step();
  ff::FluidState fluid;
  ff::ControlSet control;
  ff::ControlFields fields;
  sim.backend().readFluid(fluid);
  sim.backend().readControl(control, fields);
  ASSERT_GT(control.size(), 200u);
  control.clusters = windowClusters(control);
  deform(control);
  // Both with the anchor (ff_anchor.h: its sums over the whole set and its
  // correction) and without it; and in the middle of a rest-shape blend
  // (ControlSet::bx0, ff_blend_rest) from the reference jittered by up to
  // 5 mm (so that the clusters still turn), at blend weight 7 / 27 (a third of
  // the blend time).
  // And with the standing anchor (FF_ANCHOR_STAND), 1 cm above its anchor so
  // that its height is relaxed as well as its tilt.
  for (int mode : {0, 1, 2, 3}) {
    const int anchor = mode == 1 ? 1 : mode == 3 ? 2 : 0;
    const bool blend = mode == 2;
    SCOPED_TRACE(blend ? "blending" : anchor == 2 ? "standing" : anchor ? "anchored" : "not anchored");
    ff::Params params = sim.scene().params;
    params.shape.anchor = anchor;
    ASSERT_NE(params.fluid.gravity[1], 0.0f);
    ff::ControlSet ctl = control;
    if (anchor == 2) {
      double c[3];
      ff::centreOfMass(ctl.x, ctl.y, ctl.z, c);
      ctl.anchor_y = float(c[1] - 0.01);
    }
    if (blend) {
      std::mt19937 rng(7);
      std::uniform_real_distribution<float> u(-0.005f, 0.005f);
      for (size_t p = 0; p < ctl.size(); ++p)
        ctl.x[p] = ctl.x0[p] + u(rng), ctl.y[p] = ctl.y0[p] + u(rng), ctl.z[p] = ctl.z0[p] + u(rng);
      ff::startBlend(ctl, 1.0f, params.fluid.gravity);
      ctl.x = control.x, ctl.y = control.y, ctl.z = control.z;
      ASSERT_GT(ctl.blend_time, 0.0f);
      ASSERT_EQ(ctl.clusters.from_cx.size(), kClusters);
      ctl.blend_elapsed = ctl.blend_time / 3.0;
      ASSERT_GT(ctl.blendWeight(), 0.25f);
      ASSERT_LT(ctl.blendWeight(), 0.27f);
    }

    ff::CpuBackend cpu(2);
    step(cpu, params, scene, fluid, ctl);
    Result ref;
    ref.q = cpu.controller().clusterRotations();
    const ff::ControlSet& cs = cpu.controller().set();
    ref.v[0] = cpu.controller().goalX(), ref.v[1] = cpu.controller().goalY(),
    ref.v[2] = cpu.controller().goalZ();
    ref.v[3] = cs.x, ref.v[4] = cs.y, ref.v[5] = cs.z, ref.v[6] = cs.vx, ref.v[7] = cs.vy, ref.v[8] = cs.vz;
    const double elapsed = cs.blend_elapsed;
    EXPECT_EQ(elapsed, ctl.blend_elapsed + (blend ? double(params.shape.time_step) : 0.0));
    ASSERT_EQ(ref.q.size(), kClusters);
    // Every cluster turned (by about 0.4 rad, |w| = cos(0.2) = 0.980; a flat
    // cluster's warm-started iterations get part of the way): more than 0.09 rad.
    for (const ff_quat& q : ref.q) EXPECT_LT(std::fabs(q.w), 0.999f);

    for (auto variant : {ff::OpenClBackend::KernelVariant::Scalar, ff::OpenClBackend::KernelVariant::Lanes}) {
      std::unique_ptr<ff::OpenClBackend> ocl;
      ASSERT_NO_THROW(ocl = std::make_unique<ff::OpenClBackend>(-1)) << "the OpenCL backend did not start";
      ocl->setKernelVariant(variant);
      const bool lanes = variant == ff::OpenClBackend::KernelVariant::Lanes;
      ASSERT_EQ(ocl->usesLanes(), lanes);
      const bool pocl = ff::roundsAsTheCpuBackend(ocl->deviceInfo());
      step(*ocl, params, scene, fluid, ctl);
      Result got;
      ocl->readClusterRotations(got.q);
      ocl->readGoals(got.v[0], got.v[1], got.v[2]);
      ff::ControlSet oc;
      ff::ControlFields of;
      ocl->readControl(oc, of);
      got.v[3] = oc.x, got.v[4] = oc.y, got.v[5] = oc.z, got.v[6] = oc.vx, got.v[7] = oc.vy, got.v[8] = oc.vz;
      EXPECT_EQ(oc.blend_elapsed, elapsed);
      const char* names[9] = {"goal x", "goal y", "goal z", "x", "y", "z", "vx", "vy", "vz"};
      const char* which = lanes ? "lanes kernels" : "scalar kernels";
      ASSERT_EQ(got.q.size(), ref.q.size()) << which;
      if (pocl) {
        EXPECT_EQ(std::memcmp(got.q.data(), ref.q.data(), ref.q.size() * sizeof(ff_quat)), 0)
            << which << ": cluster rotations differ";
        for (int k = 0; k < 9; ++k) EXPECT_TRUE(sameBits(got.v[k], ref.v[k])) << which << ": " << names[k];
      } else {  // another device's rounding: the per-phase GPU tolerance of each value's scale
        for (size_t c = 0; c < ref.q.size(); ++c) {
          const ff_quat a = ref.q[c], b = got.q[c];
          const double d =
              std::fabs(a.x - b.x) + std::fabs(a.y - b.y) + std::fabs(a.z - b.z) + std::fabs(a.w - b.w);
          EXPECT_LE(d, ff::test::kGpuPhaseTol) << which << ", cluster " << c;
        }
        // positions: scale 0.2 m (the container); velocities: alpha / dt of it (eq. 7)
        const double v_scale = params.shape.stiffness / params.shape.time_step * 0.2;
        for (int k = 0; k < 9; ++k)
          for (size_t i = 0; i < ref.v[k].size(); ++i)
            EXPECT_NEAR(got.v[k][i], ref.v[k][i], ff::test::kGpuPhaseTol * (k < 6 ? 0.2 : v_scale))
                << which << ": " << names[k] << "[" << i << "]";
      }
    }
  }
}
