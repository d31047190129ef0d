// camera.cpp - orbit camera matrices and picking rays.
#include "render/camera.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace ff::render {

namespace {
constexpr float kPi = 3.14159265358979f;
constexpr float kMaxPitch = 89.0f * kPi / 180.0f;
}  // namespace

Vec3 OrbitCamera::eye() const {
  const float cp = std::cos(pitch), sp = std::sin(pitch);
  // yaw = 0 looks along -z: the eye sits on +z of the target.
  const Vec3 offset(distance * cp * std::sin(yaw), distance * sp, distance * cp * std::cos(yaw));
  return target + offset;
}

Mat4 OrbitCamera::view() const {
  const Vec3 e = eye();
  const Vec3 f = (target - e).normalized();
  const Vec3 s = f.cross(Vec3(0.0f, 1.0f, 0.0f)).normalized();
  const Vec3 u = s.cross(f);
  Mat4 m = Mat4::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(e);
  m(1, 3) = -u.dot(e);
  m(2, 3) = f.dot(e);
  return m;
}

Mat4 OrbitCamera::projection(float aspect) const {
  const float t = 1.0f / std::tan(0.5f * fov_y_deg * kPi / 180.0f);
  Mat4 m = Mat4::Zero();
  m(0, 0) = t / aspect;
  m(1, 1) = t;
  m(2, 2) = (z_far + z_near) / (z_near - z_far);
  m(2, 3) = 2.0f * z_far * z_near / (z_near - z_far);
  m(3, 2) = -1.0f;
  return m;
}

void OrbitCamera::orbit(float dyaw, float dpitch) {
  yaw += dyaw;
  pitch = std::clamp(pitch + dpitch, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::pan(float dx, float dy) {
  const Vec3 e = eye();
  const Vec3 f = (target - e).normalized();
  const Vec3 s = f.cross(Vec3(0.0f, 1.0f, 0.0f)).normalized();
  const Vec3 u = s.cross(f);
  target += distance * (dx * s + dy * u);
}

void OrbitCamera::zoom(float factor) {
  if (!(factor > 0.0f) || !std::isfinite(factor)) return;
  distance = std::clamp(distance * factor, 4.0f * z_near, 0.5f * z_far);
}

void OrbitCamera::ray(float px, float py, int w, int h, Vec3& origin, Vec3& dir) const {
  const float aspect = float(std::max(w, 1)) / float(std::max(h, 1));
  const float t = std::tan(0.5f * fov_y_deg * kPi / 180.0f);
  const float ndc_x = 2.0f * (px + 0.5f) / float(std::max(w, 1)) - 1.0f;
  const float ndc_y = 1.0f - 2.0f * (py + 0.5f) / float(std::max(h, 1));
  const Vec3 e = eye();
  const Vec3 f = (target - e).normalized();
  const Vec3 s = f.cross(Vec3(0.0f, 1.0f, 0.0f)).normalized();
  const Vec3 u = s.cross(f);
  origin = e;
  dir = (f + ndc_x * t * aspect * s + ndc_y * t * u).normalized();
}

OrbitCamera OrbitCamera::framing(const Vec3& box_min, const Vec3& box_max) {
  OrbitCamera c;
  c.target = 0.5f * (box_min + box_max);
  c.target.y() = box_min.y() + 0.4f * (box_max.y() - box_min.y());
  const float radius = 0.5f * (box_max - box_min).norm();
  c.distance = radius / std::sin(0.5f * c.fov_y_deg * kPi / 180.0f) * 1.05f;
  return c;
}

}  // namespace ff::render
