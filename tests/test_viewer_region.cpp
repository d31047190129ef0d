// Region selection without a window: the particles a screen rectangle covers
// (checked against a projection computed independently from the camera's
// basis), the percentile box around them, and the sphere brush's ray pick.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "viewer/region_pick.h"

namespace {

using ff::Vec3;
using ff::render::OrbitCamera;
using ff::viewer::ScreenRect;

constexpr float kPi = 3.14159265358979f;

// Pinhole projection from the eye, the viewing direction and the up vector:
// no matrices, so an error in the view or projection matrix shows.
bool independentPixel(const OrbitCamera& cam, int w, int h, const Vec3& p, double& px, double& py) {
  const Vec3 eye = cam.eye();
  const Vec3 f = (cam.target - eye).normalized();
  const Vec3 s = f.cross(Vec3(0, 1, 0)).normalized();
  const Vec3 u = s.cross(f);
  const Vec3 d = p - eye;
  const double depth = d.dot(f);
  if (depth <= cam.z_near) return false;
  const double t = std::tan(0.5 * cam.fov_y_deg * kPi / 180.0);
  const double aspect = double(w) / double(h);
  const double nx = d.dot(s) / depth / (t * aspect), ny = d.dot(u) / depth / t;
  px = (nx + 1.0) * 0.5 * w;
  py = (1.0 - ny) * 0.5 * h;
  return true;
}

struct Cloud {
  std::vector<float> x, y, z;
};

Cloud randomCloud(int n, unsigned seed, const Vec3& lo, const Vec3& hi) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> ux(lo.x(), hi.x()), uy(lo.y(), hi.y()), uz(lo.z(), hi.z());
  Cloud c;
  for (int i = 0; i < n; ++i) {
    c.x.push_back(ux(rng));
    c.y.push_back(uy(rng));
    c.z.push_back(uz(rng));
  }
  return c;
}

TEST(ViewerRegion, RectangleSelectsExactlyTheParticlesProjectingIntoIt) {
  const Cloud c = randomCloud(4000, 7, Vec3(0, 0, 0), Vec3(0.36f, 0.3f, 0.36f));
  OrbitCamera cam = OrbitCamera::framing(Vec3(0, 0, 0), Vec3(0.36f, 0.3f, 0.36f));
  cam.yaw = 0.9f;
  cam.pitch = 0.35f;
  const int w = 800, h = 500;
  const ScreenRect rects[] = {{300, 120, 520, 380}, {610, 410, 150, 90}, {0, 0, 800, 500}, {10, 10, 40, 30}};
  size_t total_selected = 0;
  for (const ScreenRect& r : rects) {
    const std::vector<int> got = ff::viewer::particlesInRect(cam, w, h, c.x, c.y, c.z, r);
    EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
    total_selected += got.size();
    const double x0 = std::min(r.x0, r.x1), x1 = std::max(r.x0, r.x1);
    const double y0 = std::min(r.y0, r.y1), y1 = std::max(r.y0, r.y1);
    for (size_t i = 0; i < c.x.size(); ++i) {
      double px = 0.0, py = 0.0;
      const bool front = independentPixel(cam, w, h, Vec3(c.x[i], c.y[i], c.z[i]), px, py);
      // Skip the particles within 1e-3 px of an edge: float rounding may put them either side.
      const double margin =
          std::min({std::abs(px - x0), std::abs(px - x1), std::abs(py - y0), std::abs(py - y1)});
      if (front && margin < 1e-3) continue;
      const bool expected = front && px >= x0 && px <= x1 && py >= y0 && py <= y1;
      const bool selected = std::binary_search(got.begin(), got.end(), int(i));
      EXPECT_EQ(selected, expected) << "particle " << i << " at pixel " << px << ", " << py;
    }
  }
  EXPECT_GT(total_selected, 100u);  // the rectangles are not all empty
}

TEST(ViewerRegion, ProjectionAgreesWithThePickingRay) {
  OrbitCamera cam;
  cam.yaw = -0.4f;
  cam.pitch = 0.7f;
  const int w = 640, h = 480;
  for (float px : {5.5f, 320.5f, 600.5f})
    for (float py : {3.5f, 240.5f, 470.5f}) {
      Vec3 o, d;
      cam.ray(px - 0.5f, py - 0.5f, w, h, o, d);  // ray() takes pixel indices (centre at +0.5)
      float qx, qy;
      ASSERT_TRUE(ff::viewer::projectToPixel(cam, w, h, o + 0.3f * d, qx, qy));
      EXPECT_NEAR(qx, px, 1e-2);
      EXPECT_NEAR(qy, py, 1e-2);
    }
  float qx, qy;
  EXPECT_FALSE(
      ff::viewer::projectToPixel(cam, w, h, cam.eye() + (cam.eye() - cam.target), qx, qy));  // behind
}

TEST(ViewerRegion, ParticlesBehindTheCameraAreNeverSelected) {
  OrbitCamera cam;
  const Vec3 behind = cam.eye() + 0.5f * (cam.eye() - cam.target);
  const std::vector<float> x = {behind.x(), cam.target.x()}, y = {behind.y(), cam.target.y()},
                           z = {behind.z(), cam.target.z()};
  const std::vector<int> got =
      ff::viewer::particlesInRect(cam, 400, 300, x, y, z, {-1e6f, -1e6f, 1e6f, 1e6f});
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0], 1);
}

TEST(ViewerRegion, BoxIsThePercentileRangeOfTheChosenParticles) {
  const Cloud c = randomCloud(1500, 11, Vec3(0, 0, 0), Vec3(1, 2, 3));
  std::vector<int> chosen;
  for (int i = 0; i < 1500; i += 2) chosen.push_back(i);  // 750 particles: k = 7
  const float pad = 0.01f;
  const ff::RegionDesc r = ff::viewer::boxAroundParticles(c.x, c.y, c.z, chosen, pad);
  ASSERT_EQ(r.kind, ff::RegionDesc::Kind::Box);
  const std::vector<float>* axes[3] = {&c.x, &c.y, &c.z};
  for (int a = 0; a < 3; ++a) {
    std::vector<float> v;
    for (int i : chosen) v.push_back((*axes[a])[size_t(i)]);
    std::sort(v.begin(), v.end());
    EXPECT_FLOAT_EQ(r.min[a], v[7] - pad) << a;
    EXPECT_FLOAT_EQ(r.max[a], v[v.size() - 8] + pad) << a;
  }

  // Fewer than 200 particles: all of them count.
  const std::vector<int> few = {3, 9, 27};
  const ff::RegionDesc s = ff::viewer::boxAroundParticles(c.x, c.y, c.z, few, 0.0f);
  EXPECT_FLOAT_EQ(s.min.x(), std::min({c.x[3], c.x[9], c.x[27]}));
  EXPECT_FLOAT_EQ(s.max.z(), std::max({c.z[3], c.z[9], c.z[27]}));

  // One particle still gives a valid box (min < max) around it; none gives "all".
  const ff::RegionDesc single = ff::viewer::boxAroundParticles(c.x, c.y, c.z, {5}, 0.0f);
  for (int a = 0; a < 3; ++a) {
    EXPECT_LT(single.min[a], single.max[a]);
    EXPECT_LE(single.min[a], (*axes[a])[5]);
    EXPECT_GE(single.max[a], (*axes[a])[5]);
  }
  EXPECT_EQ(ff::viewer::boxAroundParticles(c.x, c.y, c.z, {}, 0.0f).kind, ff::RegionDesc::Kind::All);
}

TEST(ViewerRegion, BrushPicksTheNearestParticleAlongTheRay) {
  // Particles on the x axis at 1, 2, 3; one off-axis at 0.5 (0.2 away); one behind the origin.
  const std::vector<float> x = {3.0f, 1.0f, 2.0f, 0.5f, -1.0f}, y = {0.0f, 0.01f, 0.0f, 0.2f, 0.0f},
                           z = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  const Vec3 o(0, 0, 0), dir(2, 0, 0);  // not normalised on purpose
  EXPECT_EQ(ff::viewer::pickParticleOnRay(o, dir, x, y, z, 0.05f), 1);
  EXPECT_EQ(ff::viewer::pickParticleOnRay(o, dir, x, y, z, 0.25f), 3);   // the off-axis one is nearer
  EXPECT_EQ(ff::viewer::pickParticleOnRay(o, dir, x, y, z, 0.005f), 2);  // 1 is 0.01 off the ray
  EXPECT_EQ(ff::viewer::pickParticleOnRay(o, Vec3(0, 0, 1), x, y, z, 0.05f), -1);
  EXPECT_EQ(ff::viewer::pickParticleOnRay(o, Vec3(-1, 0, 0), x, y, z, 0.05f), 4);

  const ff::RegionDesc s = ff::viewer::sphereRegion(Vec3(1, 2, 3), 0.25f);
  EXPECT_EQ(s.kind, ff::RegionDesc::Kind::Sphere);
  EXPECT_FLOAT_EQ(s.center.y(), 2.0f);
  EXPECT_FLOAT_EQ(s.radius, 0.25f);
}

}  // namespace
