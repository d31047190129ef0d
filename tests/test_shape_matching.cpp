// Cluster shape matching pulls a rotated, translated and squashed point set
// back to its rigid shape.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "control/clusters.h"
#include "control/controller.h"
#include "control/shape_matching.h"

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
    ff::buildClusters(s, vi, vj, vk, 2, 2, false, coarse);
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
