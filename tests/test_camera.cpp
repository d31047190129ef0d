// The orbit camera's matrices and picking rays, checked against geometry
// computed here independently: angles and distances of the eye, the
// frustum's edges, and projections of points along a picking ray.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>

#include "render/camera.h"

namespace {

using ff::Vec3;
using ff::render::Mat4;
using ff::render::OrbitCamera;

constexpr float kPi = 3.14159265358979f;

Eigen::Vector3f ndcOf(const Mat4& vp, const Vec3& p) {
  const Eigen::Vector4f c = vp * Eigen::Vector4f(p.x(), p.y(), p.z(), 1.0f);
  return c.head<3>() / c.w();
}

OrbitCamera sampleCamera(int i) {
  OrbitCamera c;
  c.target = Vec3(0.1f * float(i), -0.05f, 0.3f - 0.02f * float(i));
  c.yaw = -2.5f + 1.3f * float(i);
  c.pitch = -0.6f + 0.35f * float(i);
  c.distance = 0.3f + 0.4f * float(i);
  c.fov_y_deg = 30.0f + 10.0f * float(i % 3);
  return c;
}

TEST(Camera, EyeSitsAtTheOrbitAnglesAndDistance) {
  for (int i = 0; i < 5; ++i) {
    const OrbitCamera c = sampleCamera(i);
    const Vec3 d = c.eye() - c.target;
    EXPECT_NEAR(d.norm(), c.distance, 1e-5f);
    // Elevation above the horizontal plane is the pitch.
    EXPECT_NEAR(std::asin(d.y() / d.norm()), c.pitch, 1e-4f);
    // Azimuth: yaw 0 puts the eye on +z of the target (looking along -z),
    // growing yaw turns it towards +x.
    float az = std::atan2(d.x(), d.z()) - c.yaw;
    az = std::remainder(az, 2.0f * kPi);
    EXPECT_NEAR(az, 0.0f, 1e-4f);
  }
}

TEST(Camera, ViewIsARigidMotionFromTheEyeLookingAtTheTarget) {
  for (int i = 0; i < 5; ++i) {
    const OrbitCamera c = sampleCamera(i);
    const Mat4 v = c.view();
    const Eigen::Matrix3f r = v.block<3, 3>(0, 0);
    EXPECT_LT((r * r.transpose() - Eigen::Matrix3f::Identity()).norm(), 1e-5f);
    EXPECT_NEAR(r.determinant(), 1.0f, 1e-5f);
    EXPECT_NEAR(v(3, 3), 1.0f, 0.0f);
    const Eigen::Vector4f eye = v * Eigen::Vector4f(c.eye().x(), c.eye().y(), c.eye().z(), 1.0f);
    EXPECT_LT(eye.head<3>().norm(), 1e-5f);
    const Eigen::Vector4f tgt = v * Eigen::Vector4f(c.target.x(), c.target.y(), c.target.z(), 1.0f);
    EXPECT_NEAR(tgt.x(), 0.0f, 1e-5f);
    EXPECT_NEAR(tgt.y(), 0.0f, 1e-5f);
    EXPECT_NEAR(tgt.z(), -c.distance, 1e-5f);
    // No roll: world up stays in the eye's vertical plane and points up on screen.
    const Eigen::Vector3f up = r * Eigen::Vector3f(0.0f, 1.0f, 0.0f);
    EXPECT_NEAR(up.x(), 0.0f, 1e-5f);
    EXPECT_GT(up.y(), 0.0f);
  }
}

TEST(Camera, TargetProjectsToTheScreenCentreAndTheFrustumEdgesToTheBorder) {
  for (int i = 0; i < 5; ++i) {
    const OrbitCamera c = sampleCamera(i);
    const float aspect = 1.0f + 0.4f * float(i);
    const Mat4 vp = c.projection(aspect) * c.view();
    const Eigen::Vector3f centre = ndcOf(vp, c.target);
    EXPECT_NEAR(centre.x(), 0.0f, 1e-5f);
    EXPECT_NEAR(centre.y(), 0.0f, 1e-5f);
    // Independent frame: forward from the eye to the target, right =
    // forward x world-up, up = right x forward. A point seen fov/2 above the
    // forward direction lies on the top border; (fov/2 widened by the aspect)
    // to the right lies on the right border.
    const Vec3 e = c.eye(), f = (c.target - e).normalized();
    const Vec3 right = f.cross(Vec3::UnitY()).normalized(), up = right.cross(f);
    const float half = 0.5f * c.fov_y_deg * kPi / 180.0f;
    const float dist = 0.7f * c.distance;
    const Vec3 top = e + dist * (f + std::tan(half) * up);
    EXPECT_NEAR(ndcOf(vp, top).y(), 1.0f, 1e-4f);
    EXPECT_NEAR(ndcOf(vp, top).x(), 0.0f, 1e-4f);
    const Vec3 side = e + dist * (f + aspect * std::tan(half) * right);
    EXPECT_NEAR(ndcOf(vp, side).x(), 1.0f, 1e-4f);
    // Depth: the near and far planes map to -1 and +1.
    EXPECT_NEAR(ndcOf(vp, e + c.z_near * f).z(), -1.0f, 1e-3f);
    EXPECT_NEAR(ndcOf(vp, e + c.z_far * f).z(), 1.0f, 1e-3f);
  }
}

TEST(Camera, RayThroughAPixelProjectsBackToThatPixel) {
  const int w = 640, h = 360;
  for (int i = 0; i < 5; ++i) {
    const OrbitCamera c = sampleCamera(i);
    const Mat4 vp = c.projection(float(w) / float(h)) * c.view();
    for (const auto& px : {Eigen::Vector2f(0.0f, 0.0f), Eigen::Vector2f(319.0f, 179.0f),
                           Eigen::Vector2f(639.0f, 359.0f), Eigen::Vector2f(17.0f, 301.0f)}) {
      Vec3 o, d;
      c.ray(px.x(), px.y(), w, h, o, d);
      EXPECT_LT((o - c.eye()).norm(), 1e-5f);
      EXPECT_NEAR(d.norm(), 1.0f, 1e-5f);
      for (float t : {0.1f, 1.0f, 5.0f}) {
        const Eigen::Vector3f n = ndcOf(vp, o + t * d);
        // Pixel (px, py) has its centre at (px + 0.5, py + 0.5), y from the top.
        const float sx = (0.5f * n.x() + 0.5f) * float(w) - 0.5f;
        const float sy = (0.5f - 0.5f * n.y()) * float(h) - 0.5f;
        EXPECT_NEAR(sx, px.x(), 2e-3f) << "camera " << i << " t " << t;
        EXPECT_NEAR(sy, px.y(), 2e-3f) << "camera " << i << " t " << t;
      }
    }
  }
}

TEST(Camera, FramingShowsEveryCornerOfTheBox) {
  const Vec3 lo(-0.1f, 0.0f, 0.2f), hi(0.4f, 0.3f, 0.5f);
  const OrbitCamera c = OrbitCamera::framing(lo, hi);
  for (float aspect : {1.0f, 16.0f / 9.0f}) {
    const Mat4 vp = c.projection(aspect) * c.view();
    for (int k = 0; k < 8; ++k) {
      const Vec3 p((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z());
      const Eigen::Vector3f n = ndcOf(vp, p);
      EXPECT_LT(std::abs(n.x()), 1.0f) << "corner " << k;
      EXPECT_LT(std::abs(n.y()), 1.0f) << "corner " << k;
      EXPECT_GT(n.z(), -1.0f);
      EXPECT_LT(n.z(), 1.0f);
    }
  }
}

TEST(Camera, OrbitClampsPitchPanKeepsDistanceZoomScales) {
  OrbitCamera c;
  c.orbit(0.3f, 10.0f);
  EXPECT_LT(c.pitch, 89.5f * kPi / 180.0f);
  EXPECT_GT(c.pitch, 88.5f * kPi / 180.0f);
  c.orbit(0.0f, -20.0f);
  EXPECT_GT(c.pitch, -89.5f * kPi / 180.0f);
  EXPECT_LT(c.pitch, -88.5f * kPi / 180.0f);

  OrbitCamera p;
  const Vec3 before_eye = p.eye(), before_target = p.target;
  const Vec3 forward = (p.target - p.eye()).normalized();
  p.pan(0.2f, -0.1f);
  const Vec3 moved = p.target - before_target;
  EXPECT_NEAR(moved.norm(), p.distance * std::sqrt(0.2f * 0.2f + 0.1f * 0.1f), 1e-5f);
  EXPECT_NEAR(moved.dot(forward), 0.0f, 1e-6f);               // sideways, in the view plane
  EXPECT_LT(((p.eye() - before_eye) - moved).norm(), 1e-5f);  // the eye moves along
  // Panning right moves the old target to the left half of the screen.
  EXPECT_LT(ndcOf(p.projection(1.0f) * p.view(), before_target).x(), 0.0f);

  OrbitCamera z;
  const float d0 = z.distance;
  z.zoom(0.5f);
  EXPECT_NEAR(z.distance, 0.5f * d0, 1e-6f);
  z.zoom(-1.0f);  // ignored
  EXPECT_NEAR(z.distance, 0.5f * d0, 1e-6f);
  z.zoom(1e-6f);
  EXPECT_GE(z.distance, 4.0f * z.z_near);
}

}  // namespace
