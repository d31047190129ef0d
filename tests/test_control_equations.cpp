// The control equations of Yoshino & Tsuruno (eq. 4-9) and the fluid feedback,
// one step each, through the controller's public phases, against hand
// calculations. Every expected number is worked out here in double precision
// from the paper's formulas (/work/shared/seed, docs/DESIGN.md): the poly6
// kernel is written out again below, not taken from kernels/common, so a wrong
// formula in the shared headers (which both backends include) fails here.
//
// The parameters are the `paper` preset's, with one change per test where the
// test isolates a term (e.g. gravity compensation off, which the paper has not).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "control/controller.h"
#include "core/params.h"

namespace {

// Müller et al. 2003: W_poly6(d) = 315 / (64 pi r^9) (r^2 - d^2)^3 for d < r.
double poly6(double d, double r) {
  if (d >= r) return 0.0;
  const double q = r * r - d * d;
  return 315.0 / (64.0 * M_PI * std::pow(r, 9)) * q * q * q;
}

using V3 = std::array<double, 3>;

double dist(const V3& a, const V3& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

// A few fluid particles as a FluidView over vectors it owns.
struct Fluid {
  std::vector<float> x, y, z, vx, vy, vz;
  void add(const V3& p, const V3& v = {0, 0, 0}) {
    x.push_back(float(p[0])), y.push_back(float(p[1])), z.push_back(float(p[2]));
    vx.push_back(float(v[0])), vy.push_back(float(v[1])), vz.push_back(float(v[2]));
  }
  V3 pos(size_t e) const { return {x[e], y[e], z[e]}; }
  V3 vel(size_t e) const { return {vx[e], vy[e], vz[e]}; }
  ff::FluidView view(float volume) const {
    ff::FluidView f;
    f.n = x.size();
    f.x = x.data(), f.y = y.data(), f.z = z.data(), f.vx = vx.data(), f.vy = vy.data(), f.vz = vz.data();
    f.volume = volume;
    return f;
  }
};

// Control particles at `pos` with velocities `vel`, all in one cluster whose
// rest shape is `rest` (or the positions themselves).
ff::ControlSet controlSet(const std::vector<V3>& pos, const std::vector<V3>& vel, std::vector<V3> rest = {}) {
  if (rest.empty()) rest = pos;
  ff::ControlSet s;
  const size_t n = pos.size();
  V3 rc = {0, 0, 0};
  for (size_t i = 0; i < n; ++i) {
    s.x.push_back(float(pos[i][0])), s.y.push_back(float(pos[i][1])), s.z.push_back(float(pos[i][2]));
    s.vx.push_back(float(vel[i][0])), s.vy.push_back(float(vel[i][1])), s.vz.push_back(float(vel[i][2]));
    s.x0.push_back(float(rest[i][0])), s.y0.push_back(float(rest[i][1])), s.z0.push_back(float(rest[i][2]));
    for (int d = 0; d < 3; ++d) rc[d] += rest[i][d] / double(n);
  }
  ff::Clusters& c = s.clusters;
  c.start = {0, uint32_t(n)};
  for (size_t i = 0; i < n; ++i) c.members.push_back(uint32_t(i)), c.of.push_back(0);
  for (size_t i = 0; i <= n; ++i) c.of_start.push_back(uint32_t(i));
  c.rest_cx = {float(rc[0])}, c.rest_cy = {float(rc[1])}, c.rest_cz = {float(rc[2])};
  s.rest_cx = float(rc[0]), s.rest_cy = float(rc[1]), s.rest_cz = float(rc[2]);
  s.particle_volume = 1e-6f;
  return s;
}

// The paper's constants, without the recapture (an addition that the paper's
// equations do not have; tests/test_recapture.cpp covers it).
ff::Params paper() {
  ff::Params p = ff::presetParams("paper");
  p.control.recapture = 0.0f;
  return p;
}

// Runs computeScale and addForces; returns the accelerations of the fluid.
std::vector<V3> controlAccelerations(ff::Controller& c, const Fluid& fl, float volume, float dt) {
  const ff::FluidView f = fl.view(volume);
  const size_t n = fl.x.size();
  std::vector<float> ax(n, 0.0f), ay(n, 0.0f), az(n, 0.0f);
  EXPECT_TRUE(c.computeScale(f));
  EXPECT_TRUE(c.addForces(f, dt, ax.data(), ay.data(), az.data()));
  std::vector<V3> a(n);
  for (size_t e = 0; e < n; ++e) a[e] = {ax[e], ay[e], az[e]};
  return a;
}

// Relative agreement of float results with double hand calculations: a few
// float roundings of sums of ~10 terms, nothing more.
constexpr double kRel = 2e-5;

void expectVecNear(const V3& got, const V3& want, double scale, const char* what) {
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(got[d], want[d], kRel * scale) << what << " component " << d;
}

double norm(const V3& v) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

// Eq. 5: s_i = 1 - min(1, sum_e V_e W(|p_i - x_e|)). Three control particles:
// one deep in the fluid (the sum passes 1: s = 0), one at its edge (0 < s < 1),
// one out of reach of every fluid particle (s = 1).
TEST(ControlEquations, ControlScaleEq5) {
  const ff::Params p = paper();
  const double r = p.control.radius;  // 0.03 m
  Fluid fl;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j)
      for (int k = -2; k <= 2; ++k) fl.add({0.1 + 0.01 * i, 0.1 + 0.01 * j, 0.1 + 0.01 * k});
  const std::vector<V3> cps = {{0.1, 0.1, 0.1}, {0.1, 0.1, 0.135}, {0.2, 0.2, 0.2}};
  const float volume = 1.0e-6f;  // the fluid's rest spacing is 0.01 m
  ff::Controller c;
  c.setParams(p.control, p.shape);
  c.reset(controlSet(cps, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}));
  ASSERT_TRUE(c.computeScale(fl.view(volume)));
  std::vector<double> want;
  for (const V3& cp : cps) {
    double rho_hat = 0;
    for (size_t e = 0; e < fl.x.size(); ++e) rho_hat += volume * poly6(dist(cp, fl.pos(e)), r);
    want.push_back(1.0 - std::min(1.0, rho_hat));
  }
  // The hand values are what this test claims they are.
  ASSERT_EQ(want[0], 0.0);
  ASSERT_GT(want[1], 0.05);
  ASSERT_LT(want[1], 0.95);
  ASSERT_EQ(want[2], 1.0);
  for (size_t i = 0; i < cps.size(); ++i)
    EXPECT_NEAR(c.fields().s[i], want[i], 1e-5) << "control particle " << i;
}

// Three control particles within reach of the fluid particles at (0.1, 0.1, 0.1)
// and (0.112, 0.095, 0.104) of the next two tests.
const std::vector<V3> kThreeControlParticles = {
    {0.110, 0.100, 0.100}, {0.100, 0.085, 0.120}, {0.090, 0.112, 0.093}};

// Eq. 4 alone (w_v = 0, no gravity compensation): f_a(e) = w_a sum_i s_i
// (p_i - x_e) / |p_i - x_e| W(|p_i - x_e|), with s_i of eq. 5.
TEST(ControlEquations, AttractionEq4) {
  ff::Params p = paper();
  p.control.velocity = 0.0f;
  p.control.gravity_compensation = 0.0f;
  Fluid fl;
  fl.add({0.100, 0.100, 0.100}, {0.3, -0.2, 0.1});  // its velocity must not matter
  fl.add({0.112, 0.095, 0.104});
  const double r = p.control.radius, wa = p.control.attraction;
  fl.add({0.300, 0.300, 0.300});  // out of every control particle's reach
  const std::vector<V3>& cps = kThreeControlParticles;
  // Large enough that the fluid around the first control particle matters in
  // eq. 5 (0 < s < 1), not so large that it clamps.
  const float volume = 2.0e-6f;
  ff::Controller c;
  c.setParams(p.control, p.shape);
  c.reset(controlSet(cps, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}));
  const std::vector<V3> a = controlAccelerations(c, fl, volume, 0.004f);

  std::vector<double> s;
  for (const V3& cp : cps) {
    double rho_hat = 0;
    for (size_t e = 0; e < fl.x.size(); ++e) rho_hat += volume * poly6(dist(cp, fl.pos(e)), r);
    s.push_back(1.0 - std::min(1.0, rho_hat));
  }
  ASSERT_LT(*std::min_element(s.begin(), s.end()), 0.95);  // s matters
  for (size_t e = 0; e < fl.x.size(); ++e) {
    V3 fa = {0, 0, 0};
    for (size_t i = 0; i < cps.size(); ++i) {
      const double d = dist(cps[i], fl.pos(e));
      for (int k = 0; k < 3; ++k) fa[k] += wa * s[i] * (cps[i][k] - fl.pos(e)[k]) / d * poly6(d, r);
    }
    if (e < 2) {
      ASSERT_GT(norm(fa), 0.1);  // ~0.5-3 m/s^2 with the paper's w_a: not a trivial zero
    }
    expectVecNear(a[e], fa, std::max(norm(fa), 1e-3), "f_a");
  }
  EXPECT_EQ(norm(a[2]), 0.0);
}

// Eq. 6 alone (w_a = 0), as integrated over the step: f_v = V - K v_e with
// V = w_v sum_i W_i v_i and K = w_v sum_i W_i (eq. 6 rearranged), taken
// implicitly: a = (V - K v_e) / (1 + dt K). It must also match the explicit
// eq. 6 to first order in dt K.
TEST(ControlEquations, VelocityForceEq6Implicit) {
  ff::Params p = paper();
  p.control.attraction = 0.0f;
  p.control.gravity_compensation = 0.0f;
  const double r = p.control.radius, wv = p.control.velocity;
  Fluid fl;
  fl.add({0.100, 0.100, 0.100}, {0.3, -0.2, 0.1});
  fl.add({0.112, 0.095, 0.104}, {0.0, 0.0, -0.5});
  const std::vector<V3>& cps = kThreeControlParticles;
  const std::vector<V3> cvs = {{1.0, 0.0, 0.0}, {0.0, 0.8, 0.0}, {-0.2, 0.1, 0.6}};
  const float volume = 2.0e-6f, dt = 0.004f;
  ff::Controller c;
  c.setParams(p.control, p.shape);
  c.reset(controlSet(cps, cvs));
  const std::vector<V3> a = controlAccelerations(c, fl, volume, dt);
  for (size_t e = 0; e < fl.x.size(); ++e) {
    double k = 0;
    V3 vsum = {0, 0, 0}, explicit_fv = {0, 0, 0}, want;
    for (size_t i = 0; i < cps.size(); ++i) {
      const double w = poly6(dist(cps[i], fl.pos(e)), r);
      k += wv * w;
      for (int d = 0; d < 3; ++d) {
        vsum[d] += wv * w * cvs[i][d];
        explicit_fv[d] += wv * (cvs[i][d] - fl.vel(e)[d]) * w;  // eq. 6 as printed
      }
    }
    for (int d = 0; d < 3; ++d) want[d] = (vsum[d] - k * fl.vel(e)[d]) / (1.0 + dt * k);
    ASSERT_GT(norm(want), 0.1);
    ASSERT_GT(dt * k, 1e-3);  // the implicit factor is visible at this tolerance
    expectVecNear(a[e], want, norm(want), "f_v");
    // Same direction and, to O(dt K), the same size as eq. 6 taken explicitly.
    for (int d = 0; d < 3; ++d)
      EXPECT_NEAR(a[e][d], explicit_fv[d], 1.01 * dt * k * norm(explicit_fv)) << "explicit eq. 6, " << d;
  }
}

// Fluid feedback: in a shape-matching step, each control particle's velocity
// relaxes towards u_i, the kernel-weighted fluid velocity around it
// (sum_e V_e W v_e / max(1, rho_hat)): v_i += c_fb (u_i - v_i). The control
// particles sit at their rest shape and at rest, so eq. 7 and the damping add
// nothing and the feedback is all that moves them.
TEST(ControlEquations, FluidFeedback) {
  const ff::Params p = paper();
  const double r = p.control.radius, fb = p.control.feedback, h = p.shape.time_step;
  ASSERT_GT(fb, 0.0);
  Fluid fl;
  const V3 u = {0.4, -0.3, 0.2};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) fl.add({0.10 + 0.01 * i, 0.10 + 0.01 * j, 0.10}, u);
  const std::vector<V3> cps = {{0.11, 0.11, 0.105}, {0.13, 0.10, 0.10}, {0.10, 0.12, 0.108}, {0.3, 0.3, 0.3}};
  const float volume = 1.0e-6f;
  ff::Controller c;
  c.setParams(p.control, p.shape);
  c.reset(controlSet(cps, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}}));
  ASSERT_TRUE(c.computeScale(fl.view(volume)));
  ASSERT_TRUE(c.shapeMatchStep());
  for (size_t i = 0; i < cps.size(); ++i) {
    double rho_hat = 0;
    V3 sum = {0, 0, 0};
    for (size_t e = 0; e < fl.x.size(); ++e) {
      const double w = poly6(dist(cps[i], fl.pos(e)), r);
      rho_hat += volume * w;
      for (int d = 0; d < 3; ++d) sum[d] += volume * w * fl.vel(e)[d];
    }
    V3 want_v, want_x;
    for (int d = 0; d < 3; ++d) {
      want_v[d] = fb * sum[d] / std::max(1.0, rho_hat);
      want_x[d] = cps[i][d] + h * want_v[d];
    }
    if (i < 3) {
      ASSERT_GT(norm(want_v), 5e-4) << i;
    }
    const V3 got_v = {c.set().vx[i], c.set().vy[i], c.set().vz[i]};
    const V3 got_x = {c.set().x[i], c.set().y[i], c.set().z[i]};
    // Float sums of ~10 terms; the goal (the rest shape itself) is exact to
    // a few float ulps of the positions, which eq. 7 divides by h.
    for (int d = 0; d < 3; ++d) {
      EXPECT_NEAR(got_v[d], want_v[d], 1e-4 * norm(want_v) + 1e-5) << "v of control particle " << i;
      EXPECT_NEAR(got_x[d], want_x[d], 1e-7) << "x of control particle " << i;
    }
  }
}

// Eq. 7-9, one shape-matching step on a displaced cluster. The rest shape is a
// cube's 8 corners q_i (sum q q^T = 8 a^2 I); the current shape is x_i = R S q_i + c
// with a rotation R and a symmetric stretch S. Then A_pq = sum p q^T = 8 a^2 R S,
// whose rotation (polar decomposition, eq. 9) is R, so the goals are
// g_i = R q_i + c (eq. 8), and after one step from rest
// v_i = alpha (g_i - x_i) / h (eq. 7) and x_i += h v_i.
TEST(ControlEquations, ShapeMatchingStepEq7To9) {
  ff::Params p = paper();
  // Eq. 9's R is the exact polar factor. The engine finds it by warm-started
  // iterations (8 a step, converging over the steps); from a cold start on a
  // 20 degree turn it needs more to reach it within these tolerances.
  p.shape.rotation_iterations = 100;
  const double alpha = p.shape.stiffness, h = p.shape.time_step;
  const double a = 0.01;
  const double ang = 0.35, ax[3] = {1 / std::sqrt(3.0), 1 / std::sqrt(3.0), -1 / std::sqrt(3.0)};
  // Rodrigues: R = cos I + sin [ax]x + (1 - cos) ax ax^T.
  double R[3][3];
  const double cs = std::cos(ang), sn = std::sin(ang);
  const double cross[3][3] = {{0, -ax[2], ax[1]}, {ax[2], 0, -ax[0]}, {-ax[1], ax[0], 0}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = (i == j ? cs : 0.0) + sn * cross[i][j] + (1 - cs) * ax[i] * ax[j];
  const double S[3][3] = {
      {1.25, 0.1, 0.0}, {0.1, 0.8, 0.05}, {0.0, 0.05, 1.1}};  // symmetric, positive definite
  const V3 centre = {0.15, 0.12, 0.1}, rest_centre = {0.05, 0.05, 0.05};
  std::vector<V3> rest, pos, goal;
  for (int k = 0; k < 8; ++k) {
    const V3 q = {(k & 1 ? a : -a), (k & 2 ? a : -a), (k & 4 ? a : -a)};
    V3 sq = {0, 0, 0}, x, g;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) sq[i] += S[i][j] * q[j];
    for (int i = 0; i < 3; ++i) {
      x[i] = centre[i], g[i] = centre[i];
      for (int j = 0; j < 3; ++j) x[i] += R[i][j] * sq[j], g[i] += R[i][j] * q[j];
    }
    rest.push_back({rest_centre[0] + q[0], rest_centre[1] + q[1], rest_centre[2] + q[2]});
    pos.push_back(x), goal.push_back(g);
  }
  ff::Controller c;
  c.setParams(p.control, p.shape);
  c.reset(controlSet(pos, std::vector<V3>(8, V3{0, 0, 0}), rest));
  ASSERT_TRUE(c.shapeMatchStep());  // no fluid: the feedback's u_i is 0, and v_i = 0

  // The rotation found is R.
  ASSERT_EQ(c.clusterRotations().size(), 1u);
  const ff_mat3 got = ff_quat_to_mat3(c.clusterRotations()[0]);
  const ff_float3 cols[3] = {got.c0, got.c1, got.c2};
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(cols[j].x, R[0][j], 1e-5) << "column " << j;
    EXPECT_NEAR(cols[j].y, R[1][j], 1e-5) << "column " << j;
    EXPECT_NEAR(cols[j].z, R[2][j], 1e-5) << "column " << j;
  }
  for (size_t i = 0; i < 8; ++i) {
    const V3 gg = {c.goalX()[i], c.goalY()[i], c.goalZ()[i]};
    const V3 v = {c.set().vx[i], c.set().vy[i], c.set().vz[i]};
    const V3 x = {c.set().x[i], c.set().y[i], c.set().z[i]};
    V3 dx;
    for (int d = 0; d < 3; ++d) dx[d] = goal[i][d] - pos[i][d];
    ASSERT_GT(norm(dx), 1e-3);  // displaced by millimetres
    for (int d = 0; d < 3; ++d) {
      EXPECT_NEAR(gg[d], goal[i][d], 2e-7) << "goal of " << i;
      EXPECT_NEAR(v[d], alpha * dx[d] / h, 1e-4 * alpha * norm(dx) / h) << "velocity of " << i;
      EXPECT_NEAR(x[d], pos[i][d] + alpha * dx[d], 2e-7) << "position of " << i;
    }
  }
}

}  // namespace
