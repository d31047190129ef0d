// A shape-matching cluster's sums in the lane order of
// kernels/common/ff_cluster_sums.h (member k adds to lane k mod 8, the lanes
// combine as ((l0 + l4) + (l2 + l6)) + ((l1 + l5) + (l3 + l7))): against an
// independent double-precision computation, within a bound on float rounding
// worked out below, and against the lane order written out here in plain
// float arithmetic, bit for bit. The OpenMP backend's clusterFrames and
// clusterVelocities must give the same centres and mean velocities.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "control/shape_matching.h"
#include "ff_cluster_sums.h"

namespace {

constexpr double kU = 1.0 / 16777216.0;  // 2^-24, a float's unit roundoff

// 100 control particles in a 5 cm ball around (0.3, 0.5, 0.2) m (coordinates
// far from 0, so the centre's rounding matters), rest positions about a
// rotated copy, random velocities; cluster 0 holds 37 of them (not a multiple
// of 8) in a shuffled order, cluster 1 the other 63.
struct Fixture {
  ff::ControlSet set;
  ff_float3 rc{};
};

Fixture makeFixture() {
  Fixture f;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-0.05f, 0.05f);
  const int n = 100;
  ff::ControlSet& s = f.set;
  for (int p = 0; p < n; ++p) {
    const float a = u(rng), b = u(rng), c = u(rng);
    s.x.push_back(0.3f + a), s.y.push_back(0.5f + b), s.z.push_back(0.2f + c);
    s.x0.push_back(0.1f + 0.8f * a - 0.6f * b + u(rng) * 0.1f), s.y0.push_back(0.1f + 0.6f * a + 0.8f * b),
        s.z0.push_back(0.1f + c);
    s.vx.push_back(4.0f * u(rng)), s.vy.push_back(4.0f * u(rng) - 0.3f), s.vz.push_back(4.0f * u(rng));
  }
  std::vector<uint32_t> order(n);
  for (int p = 0; p < n; ++p) order[size_t(p)] = uint32_t(p);
  std::shuffle(order.begin(), order.end(), rng);
  ff::Clusters& cl = s.clusters;
  cl.members = order;
  cl.start = {0, 37, uint32_t(n)};
  for (size_t c = 0; c < 2; ++c) {
    double m[3] = {0, 0, 0};
    for (uint32_t k = cl.start[c]; k < cl.start[c + 1]; ++k)
      m[0] += s.x0[order[k]], m[1] += s.y0[order[k]], m[2] += s.z0[order[k]];
    const double cnt = cl.start[c + 1] - cl.start[c];
    cl.rest_cx.push_back(float(m[0] / cnt)), cl.rest_cy.push_back(float(m[1] / cnt)),
        cl.rest_cz.push_back(float(m[2] / cnt));
  }
  f.rc = FF_F3(cl.rest_cx[0], cl.rest_cy[0], cl.rest_cz[0]);
  return f;
}

// The lane order written out: lane l sums the members k = l mod 8 in ascending k.
float laneOrderSum(const std::vector<float>& terms) {
  float lane[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  for (size_t k = 0; k < terms.size(); ++k) lane[k % 8] += terms[k];
  return ((lane[0] + lane[4]) + (lane[2] + lane[6])) + ((lane[1] + lane[5]) + (lane[3] + lane[7]));
}

bool sameBits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace

// Float rounding of a mean of 37 values in the lane order: a lane of 5
// members rounds 4 additions (0 + t is exact), the combine 3 more, the
// reciprocal 1/37 and the product one each: at most 9 roundings, each 2^-24
// of at most sum |x|, so |mean - exact| <= 9 u mean |x| (+ u^2 terms; 10 u
// allowed).
TEST(ClusterSums, MeansAreTheDoubleMeansWithinFloatRounding) {
  const Fixture f = makeFixture();
  const ff::ControlSet& s = f.set;
  const ff::Clusters& cl = s.clusters;
  const uint32_t b = cl.start[0], e = cl.start[1];
  ASSERT_EQ(e - b, 37u);
  const ff_float3 com = ff_cluster_mean3_of(s.x.data(), s.y.data(), s.z.data(), cl.members.data(), b, e);
  const ff_float3 vel = ff_cluster_mean3_of(s.vx.data(), s.vy.data(), s.vz.data(), cl.members.data(), b, e);
  const std::vector<float>* pos[3] = {&s.x, &s.y, &s.z};
  const std::vector<float>* v[3] = {&s.vx, &s.vy, &s.vz};
  const float got_pos[3] = {com.x, com.y, com.z}, got_v[3] = {vel.x, vel.y, vel.z};
  for (int d = 0; d < 3; ++d) {
    double sp = 0, sv = 0, ap = 0, av = 0;
    for (uint32_t k = b; k < e; ++k) {
      const uint32_t p = cl.members[k];
      sp += (*pos[d])[p], ap += std::fabs((*pos[d])[p]);
      sv += (*v[d])[p], av += std::fabs((*v[d])[p]);
    }
    EXPECT_NEAR(got_pos[d], sp / 37.0, 10 * kU * ap / 37.0) << "centre of mass, axis " << d;
    EXPECT_NEAR(got_v[d], sv / 37.0, 10 * kU * av / 37.0) << "mean velocity, axis " << d;
    EXPECT_NE(got_pos[d], 0.0f);
  }
}

// A_pq = sum_p (x_p - c)(x0_p - rc)^T, with c the float centre (error delta
// <= 10 u mean |x|, above). Per term: x_p - c carries delta plus one
// rounding, x0_p - rc one rounding, the product one; the sum 7 (as above). So
// |A_ij - exact_ij| <= sum_p (delta |qq_pj| + 10 u |pp_pi| |qq_pj|), with the
// exact A_ij taken about the exact (double) centre.
TEST(ClusterSums, ApqIsTheDoubleApqWithinFloatRounding) {
  const Fixture f = makeFixture();
  const ff::ControlSet& s = f.set;
  const ff::Clusters& cl = s.clusters;
  const uint32_t b = cl.start[0], e = cl.start[1];
  const ff_float3 com = ff_cluster_mean3_of(s.x.data(), s.y.data(), s.z.data(), cl.members.data(), b, e);
  const ff_mat3 a = ff_cluster_apq_of(s.x.data(), s.y.data(), s.z.data(), s.x0.data(), s.y0.data(),
                                      s.z0.data(), cl.members.data(), b, e, com, f.rc);
  double c[3] = {0, 0, 0}, mean_abs[3] = {0, 0, 0};
  for (uint32_t k = b; k < e; ++k) {
    const uint32_t p = cl.members[k];
    c[0] += s.x[p], c[1] += s.y[p], c[2] += s.z[p];
    mean_abs[0] += std::fabs(s.x[p]), mean_abs[1] += std::fabs(s.y[p]), mean_abs[2] += std::fabs(s.z[p]);
  }
  for (int d = 0; d < 3; ++d) c[d] /= 37.0, mean_abs[d] /= 37.0;
  const double rc[3] = {f.rc.x, f.rc.y, f.rc.z};
  const ff_float3 cols[3] = {a.c0, a.c1, a.c2};
  double largest = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double exact = 0.0, bound = 0.0;
      for (uint32_t k = b; k < e; ++k) {
        const uint32_t p = cl.members[k];
        const double pp[3] = {s.x[p] - c[0], s.y[p] - c[1], s.z[p] - c[2]};
        const double qq[3] = {s.x0[p] - rc[0], s.y0[p] - rc[1], s.z0[p] - rc[2]};
        exact += pp[i] * qq[j];
        bound += 10 * kU * mean_abs[i] * std::fabs(qq[j]) + 10 * kU * std::fabs(pp[i] * qq[j]);
      }
      const float col[3] = {cols[j].x, cols[j].y, cols[j].z};  // column j holds A_ij
      EXPECT_NEAR(col[i], exact, bound) << "A_pq(" << i << ", " << j << ")";
      largest = std::max(largest, std::fabs(exact));
    }
  EXPECT_GT(largest, 1e-3);  // a real deformation, not a matrix of zeros
}

// The same sums in the lane order written out in plain float arithmetic, bit
// for bit; and the OpenMP backend's clusterFrames / clusterVelocities give
// these centres and mean velocities, for both clusters (37 and 63 members).
TEST(ClusterSums, FollowTheLaneOrderBitForBit) {
  const Fixture f = makeFixture();
  const ff::ControlSet& s = f.set;
  const ff::Clusters& cl = s.clusters;
  std::vector<ff_quat> q;
  std::vector<float> cx, cy, cz, vx, vy, vz;
  ff::clusterFrames(s, q, cx, cy, cz, 0);
  ff::clusterVelocities(s, vx, vy, vz);
  const std::vector<float>* in[6] = {&s.x, &s.y, &s.z, &s.vx, &s.vy, &s.vz};
  const std::vector<float>* out[6] = {&cx, &cy, &cz, &vx, &vy, &vz};
  for (size_t c = 0; c < 2; ++c) {
    const uint32_t b = cl.start[c], e = cl.start[c + 1];
    for (int d = 0; d < 6; ++d) {
      std::vector<float> terms;
      for (uint32_t k = b; k < e; ++k) terms.push_back((*in[d])[cl.members[k]]);
      const float mean = laneOrderSum(terms) * (1.0f / float(e - b));
      EXPECT_TRUE(sameBits((*out[d])[c], mean)) << "cluster " << c << ", quantity " << d;
    }
    // A_pq, entry by entry.
    const ff_float3 com = FF_F3(cx[c], cy[c], cz[c]);
    const ff_float3 rc = FF_F3(cl.rest_cx[c], cl.rest_cy[c], cl.rest_cz[c]);
    const ff_mat3 a = ff_cluster_apq_of(s.x.data(), s.y.data(), s.z.data(), s.x0.data(), s.y0.data(),
                                        s.z0.data(), cl.members.data(), b, e, com, rc);
    const ff_float3 cols[3] = {a.c0, a.c1, a.c2};
    const float cm[3] = {com.x, com.y, com.z}, r[3] = {rc.x, rc.y, rc.z};
    const std::vector<float>* x[3] = {&s.x, &s.y, &s.z};
    const std::vector<float>* x0[3] = {&s.x0, &s.y0, &s.z0};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        std::vector<float> terms;
        for (uint32_t k = b; k < e; ++k) {
          const uint32_t p = cl.members[k];
          terms.push_back(((*x[i])[p] - cm[i]) * ((*x0[j])[p] - r[j]));
        }
        const float col[3] = {cols[j].x, cols[j].y, cols[j].z};
        EXPECT_TRUE(sameBits(col[i], laneOrderSum(terms)))
            << "cluster " << c << ", A_pq(" << i << ", " << j << ")";
      }
  }
}
