// Rotation extraction (Mueller et al. 2016) against the SVD polar
// decomposition, and its guarantee of a proper rotation for any input.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "ff_rotation.h"

namespace {

ff_mat3 toFF(const Eigen::Matrix3f& m) {
  ff_mat3 r;
  r.c0 = FF_F3(m(0, 0), m(1, 0), m(2, 0));
  r.c1 = FF_F3(m(0, 1), m(1, 1), m(2, 1));
  r.c2 = FF_F3(m(0, 2), m(1, 2), m(2, 2));
  return r;
}
Eigen::Matrix3f toEigen(const ff_mat3& m) {
  Eigen::Matrix3f r;
  r << m.c0.x, m.c1.x, m.c2.x, m.c0.y, m.c1.y, m.c2.y, m.c0.z, m.c1.z, m.c2.z;
  return r;
}

Eigen::Matrix3f randomRotation(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  Eigen::Quaternionf q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q.toRotationMatrix();
}

TEST(RotationExtraction, RecoversRandomRotationsOfStretchedMatrices) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> s(0.5f, 2.0f);
  for (int t = 0; t < 200; ++t) {
    Eigen::Matrix3f r = randomRotation(rng);
    Eigen::Matrix3f q = randomRotation(rng);
    // symmetric positive definite stretch
    Eigen::Matrix3f stretch = q * Eigen::Vector3f(s(rng), s(rng), s(rng)).asDiagonal() * q.transpose();
    Eigen::Matrix3f a = r * stretch;
    // independent reference: polar factor U V^T from the SVD
    Eigen::JacobiSVD<Eigen::Matrix3f> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3f ref = svd.matrixU() * svd.matrixV().transpose();
    ff_quat out = ff_extract_rotation(toFF(a), FF_Q(0, 0, 0, 1), 200);
    Eigen::Matrix3f got = toEigen(ff_quat_to_mat3(out));
    EXPECT_LT((got - ref).norm(), 1e-4f) << "trial " << t;
    EXPECT_LT((got - r).norm(), 1e-4f) << "trial " << t;
  }
}

TEST(RotationExtraction, WarmStartConvergesInFewIterations) {
  std::mt19937 rng(3);
  Eigen::Matrix3f r = randomRotation(rng);
  Eigen::AngleAxisf small(0.05f, Eigen::Vector3f(1, 2, 3).normalized());
  Eigen::Quaternionf warm(r);
  Eigen::Matrix3f a = (small.toRotationMatrix() * r) * 1.3f;
  // The engine's default: 8 iterations per shape-matching step.
  ff_quat out = ff_extract_rotation(toFF(a), FF_Q(warm.x(), warm.y(), warm.z(), warm.w()), 8);
  EXPECT_LT((toEigen(ff_quat_to_mat3(out)) - small.toRotationMatrix() * r).norm(), 1e-4f);
}

void expectProperRotation(const Eigen::Matrix3f& a, const char* what) {
  std::mt19937 rng(11);
  for (int t = 0; t < 20; ++t) {
    Eigen::Quaternionf w(randomRotation(rng));
    ff_quat out = ff_extract_rotation(toFF(a), FF_Q(w.x(), w.y(), w.z(), w.w()), 50);
    Eigen::Matrix3f got = toEigen(ff_quat_to_mat3(out));
    EXPECT_TRUE(got.allFinite()) << what;
    EXPECT_NEAR(got.determinant(), 1.0f, 1e-4f) << what;
    EXPECT_LT((got.transpose() * got - Eigen::Matrix3f::Identity()).norm(), 1e-4f) << what;
  }
}

TEST(RotationExtraction, NeverReturnsAReflection) {
  std::mt19937 rng(5);
  Eigen::Matrix3f r = randomRotation(rng);
  Eigen::Matrix3f flat = r * Eigen::Vector3f(1.0f, 0.7f, 0.0f).asDiagonal();       // planar cluster
  Eigen::Matrix3f line = r * Eigen::Vector3f(1.0f, 0.0f, 0.0f).asDiagonal();       // collinear
  Eigen::Matrix3f inverted = r * Eigen::Vector3f(1.0f, 1.0f, -1.0f).asDiagonal();  // det < 0
  Eigen::Matrix3f mirror = -Eigen::Matrix3f::Identity();                           // point reflection
  expectProperRotation(flat, "flat");
  expectProperRotation(line, "collinear");
  expectProperRotation(inverted, "inverted");
  expectProperRotation(mirror, "mirror");
  expectProperRotation(Eigen::Matrix3f::Zero(), "zero");
  ASSERT_LT(inverted.determinant(), 0.0f);
}

TEST(RotationExtraction, FlatMatrixKeepsItsInPlaneRotation) {
  // A planar cluster rotated by r: the two in-plane axes must be recovered.
  std::mt19937 rng(9);
  Eigen::Matrix3f r = randomRotation(rng);
  Eigen::Matrix3f flat = r * Eigen::Vector3f(2.0f, 1.0f, 0.0f).asDiagonal();
  ff_quat out = ff_extract_rotation(toFF(flat), FF_Q(0, 0, 0, 1), 200);
  Eigen::Matrix3f got = toEigen(ff_quat_to_mat3(out));
  EXPECT_LT((got.col(0) - r.col(0)).norm(), 1e-3f);
  EXPECT_LT((got.col(1) - r.col(1)).norm(), 1e-3f);
}

}  // namespace
