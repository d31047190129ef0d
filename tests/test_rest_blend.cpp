// The rest-shape blend of a target change (params.shape_matching.blend,
// docs/CONTROL_UNITS.md, "Rest-shape blend"): the shape-matching goals move
// continuously from where the control particles start into the new rest
// shape, against a closed form; with the blend off they jump at once.
//
// The control particles are a lattice held still (stiffness, damping and
// feedback 0: eq. 7 moves nothing), and the reference is the lattice
// stretched by s about its centre and moved away. Every cluster c then sees
// rest offsets (1 + w (s - 1)) (b_p - cb_c) at blend weight w (b: the lattice,
// cb_c: the cluster's centre), A_pq is symmetric, R = I, and the goal of
// particle p is
//   g_p(w) = b_p + w (s - 1) m_p,  m_p = mean over p's clusters of (b_p - cb_c),
// with w the smoothstep of t / T (kernels/common/ff_control.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "control/clusters.h"
#include "control/controller.h"
#include "control/placement.h"

namespace {

constexpr int kNx = 6, kNy = 4, kNz = 3;
constexpr float kSpacing = 0.01f, kStretch = 1.5f;
const float kGravity[3] = {0.0f, -9.81f, 0.0f};

// The lattice at b, the stretched reference, clusters of the paper's size.
ff::ControlSet stretchedLattice() {
  ff::ControlSet s;
  std::vector<int> vi, vj, vk;
  const double cx = 0.5 * (kNx - 1) * kSpacing, cy = 0.5 * (kNy - 1) * kSpacing,
               cz = 0.5 * (kNz - 1) * kSpacing;
  for (int k = 0; k < kNz; ++k)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i) {
        const float b[3] = {0.1f + i * kSpacing, 0.05f + j * kSpacing, 0.2f + k * kSpacing};
        s.x.push_back(b[0]), s.y.push_back(b[1]), s.z.push_back(b[2]);
        s.x0.push_back(float(1.0 + kStretch * (i * kSpacing - cx)));
        s.y0.push_back(float(2.0 + kStretch * (j * kSpacing - cy)));
        s.z0.push_back(float(3.0 + kStretch * (k * kSpacing - cz)));
        vi.push_back(i), vj.push_back(j), vk.push_back(k);
      }
  const size_t n = s.x.size();
  s.vx.assign(n, 0.0f), s.vy.assign(n, 0.0f), s.vz.assign(n, 0.0f);
  s.rest_cx = 1.0f, s.rest_cy = 2.0f, s.rest_cz = 3.0f;
  s.particle_volume = kSpacing * kSpacing * kSpacing;
  ff::buildClusters(s, vi, vj, vk, 2, 2);
  return s;
}

// m_p of the closed form, from the lattice and the clusters' members.
std::vector<double> meanOffsets(const ff::ControlSet& s, int axis) {
  const std::vector<float>& b = axis == 0 ? s.x : axis == 1 ? s.y : s.z;
  const ff::Clusters& cl = s.clusters;
  std::vector<double> centre(cl.count());
  for (size_t c = 0; c < cl.count(); ++c) {
    double sum = 0;
    for (uint32_t k = cl.start[c]; k < cl.start[c + 1]; ++k) sum += b[cl.members[k]];
    centre[c] = sum / double(cl.start[c + 1] - cl.start[c]);
  }
  std::vector<double> m(s.size(), 0.0);
  for (size_t p = 0; p < s.size(); ++p) {
    for (uint32_t k = cl.of_start[p]; k < cl.of_start[p + 1]; ++k) m[p] += b[p] - centre[cl.of[k]];
    m[p] /= double(cl.of_start[p + 1] - cl.of_start[p]);
  }
  return m;
}

ff::Controller stillController(const ff::ControlSet& set) {
  ff::ControlParams cp;
  cp.feedback = 0.0f;
  ff::ShapeMatchParams sm;
  sm.stiffness = 0.0f, sm.damping = 0.0f;
  ff::Controller c;
  c.setParams(cp, sm);
  c.reset(set);
  return c;
}

}  // namespace

TEST(RestBlend, GoalsMoveContinuouslyAlongTheClosedForm) {
  ff::ControlSet set = stretchedLattice();
  ff::startBlend(set, 1.0f, kGravity);
  // One fall time over the largest move of a rest position: (s - 1) times the
  // lattice's half diagonal, (2.5, 1.5, 1) spacings.
  const double d = (kStretch - 1.0) * kSpacing * std::sqrt(2.5 * 2.5 + 1.5 * 1.5 + 1.0);
  const double T = std::sqrt(2.0 * d / 9.81);
  ASSERT_NEAR(set.blend_time, T, 1e-4 * T);  // the reference in float, 3 m from the origin
  ff::Controller c = stillController(set);
  const double h = double(ff::ShapeMatchParams().time_step);
  const std::vector<double> m[3] = {meanOffsets(set, 0), meanOffsets(set, 1), meanOffsets(set, 2)};
  const std::vector<float>* b[3] = {&set.x, &set.y, &set.z};
  double largest_m = 0.0;
  for (size_t p = 0; p < set.size(); ++p)
    largest_m = std::max(largest_m, std::sqrt(m[0][p] * m[0][p] + m[1][p] * m[1][p] + m[2][p] * m[2][p]));
  ASSERT_GT(largest_m, 0.5 * kSpacing);  // the corners' clusters lie to one side of them

  const int steps = int(std::ceil(T / h)) + 4;
  std::vector<float> prev[3] = {set.x, set.y, set.z};  // the goals before the change: where the particles are
  double largest_jump = 0.0, w_end = 0.0;
  for (int k = 0; k < steps; ++k) {
    ASSERT_TRUE(c.shapeMatchStep());
    const double s = std::min(1.0, double(k) * h / T), w = s * s * (3.0 - 2.0 * s);
    const std::vector<float>* g[3] = {&c.goalX(), &c.goalY(), &c.goalZ()};
    for (size_t p = 0; p < set.size(); ++p) {
      double jump2 = 0.0;
      for (int a = 0; a < 3; ++a) {
        const double want = double((*b[a])[p]) + w * (kStretch - 1.0) * m[a][p];
        EXPECT_NEAR((*g[a])[p], want, 2e-6) << "step " << k << ", particle " << p << ", axis " << a;
        const double dj = double((*g[a])[p]) - double(prev[a][p]);
        jump2 += dj * dj;
      }
      largest_jump = std::max(largest_jump, std::sqrt(jump2));
    }
    for (int a = 0; a < 3; ++a) prev[a] = *g[a];
    w_end = w;
  }
  EXPECT_EQ(w_end, 1.0);
  EXPECT_GE(c.set().blend_elapsed, T);
  EXPECT_FALSE(c.set().blending());
  // The smoothstep's steepest slope is 1.5 / T: no step moves a goal further
  // than 1.5 h / T of the whole way, (s - 1) |m_p| (plus float rounding).
  const double bound = 1.5 * h / T * (kStretch - 1.0) * largest_m;
  EXPECT_LE(largest_jump, bound + 1e-6);
  EXPECT_GT(largest_jump, 0.8 * bound);  // and it does move at about that rate
}

TEST(RestBlend, OffMeansTheNewRestShapeAtOnce) {
  ff::ControlSet set = stretchedLattice();
  ff::startBlend(set, 0.0f, kGravity);
  EXPECT_TRUE(set.bx0.empty());
  EXPECT_TRUE(set.clusters.from_cx.empty());
  EXPECT_EQ(set.blend_time, 0.0f);
  EXPECT_EQ(set.blendWeight(), 1.0f);
  ff::Controller c = stillController(set);
  ASSERT_TRUE(c.shapeMatchStep());
  // The first step's goals are the new rest shape's (w = 1): the whole jump at once.
  const std::vector<double> m[3] = {meanOffsets(set, 0), meanOffsets(set, 1), meanOffsets(set, 2)};
  const std::vector<float>* b[3] = {&set.x, &set.y, &set.z};
  const std::vector<float>* g[3] = {&c.goalX(), &c.goalY(), &c.goalZ()};
  for (size_t p = 0; p < set.size(); ++p)
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR((*g[a])[p], double((*b[a])[p]) + (kStretch - 1.0) * m[a][p], 2e-6);
  EXPECT_EQ(c.set().blend_elapsed, 0.0);
}
