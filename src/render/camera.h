// camera.h - the orbit camera of the viewer and the offscreen renderer:
// orbit around a target point, pan, zoom; view/projection matrices and
// picking rays through a pixel.
#pragma once
#include <Eigen/Core>

#include "core/vec3.h"

namespace ff::render {

using Mat4 = Eigen::Matrix4f;  // column-major, OpenGL conventions

struct OrbitCamera {
  Vec3 target{0.15f, 0.1f, 0.15f};  // point orbited around
  float yaw = 0.6f;                 // radians around +y, 0 = looking along -z
  float pitch = 0.45f;              // radians above the horizon
  float distance = 0.6f;            // metres from target
  float fov_y_deg = 40.0f;
  float z_near = 0.005f, z_far = 20.0f;

  Vec3 eye() const;
  Mat4 view() const;
  Mat4 projection(float aspect) const;

  void orbit(float dyaw, float dpitch);  // pitch clamped to (-89, 89) degrees
  void pan(float dx, float dy);          // in units of `distance` (screen fractions)
  void zoom(float factor);               // distance *= factor, clamped

  // Ray through pixel (px, py) of a w x h viewport whose origin is top-left.
  void ray(float px, float py, int w, int h, Vec3& origin, Vec3& dir) const;

  // A camera that shows the whole axis-aligned box from the default angle.
  static OrbitCamera framing(const Vec3& box_min, const Vec3& box_max);
};

}  // namespace ff::render
