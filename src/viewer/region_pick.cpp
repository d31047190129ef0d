// region_pick.cpp - screen-rectangle and ray picking of fluid particles.
#include "viewer/region_pick.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ff::viewer {

bool projectToPixel(const render::OrbitCamera& camera, int width, int height, const Vec3& p, float& px,
                    float& py) {
  if (width <= 0 || height <= 0) return false;
  const render::Mat4 vp = camera.projection(float(width) / float(height)) * camera.view();
  const Eigen::Vector4f c = vp * Eigen::Vector4f(p.x(), p.y(), p.z(), 1.0f);
  if (!(c.w() > camera.z_near * 0.5f)) return false;
  const float ndc_x = c.x() / c.w(), ndc_y = c.y() / c.w();
  px = (ndc_x * 0.5f + 0.5f) * float(width);
  py = (1.0f - (ndc_y * 0.5f + 0.5f)) * float(height);
  return std::isfinite(px) && std::isfinite(py);
}

std::vector<int> particlesInRect(const render::OrbitCamera& camera, int width, int height,
                                 const std::vector<float>& x, const std::vector<float>& y,
                                 const std::vector<float>& z, const ScreenRect& rect) {
  std::vector<int> out;
  if (width <= 0 || height <= 0) return out;
  const float lo_x = std::min(rect.x0, rect.x1), hi_x = std::max(rect.x0, rect.x1);
  const float lo_y = std::min(rect.y0, rect.y1), hi_y = std::max(rect.y0, rect.y1);
  const render::Mat4 vp = camera.projection(float(width) / float(height)) * camera.view();
  const size_t n = std::min({x.size(), y.size(), z.size()});
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector4f c = vp * Eigen::Vector4f(x[i], y[i], z[i], 1.0f);
    if (!(c.w() > camera.z_near * 0.5f)) continue;
    const float px = (c.x() / c.w() * 0.5f + 0.5f) * float(width);
    const float py = (0.5f - c.y() / c.w() * 0.5f) * float(height);
    if (px >= lo_x && px <= hi_x && py >= lo_y && py <= hi_y) out.push_back(int(i));
  }
  return out;
}

RegionDesc boxAroundParticles(const std::vector<float>& x, const std::vector<float>& y,
                              const std::vector<float>& z, const std::vector<int>& chosen, float pad) {
  RegionDesc region;
  if (chosen.empty()) return region;
  const size_t n = chosen.size(), k = n >= 200 ? n / 100 : 0;
  std::vector<float> v(n);
  auto range = [&](const std::vector<float>& src, float& lo, float& hi) {
    for (size_t i = 0; i < n; ++i) v[i] = src[size_t(chosen[i])];
    std::nth_element(v.begin(), v.begin() + long(k), v.end());
    lo = v[k];
    std::nth_element(v.begin(), v.begin() + long(n - 1 - k), v.end());
    hi = v[n - 1 - k];
  };
  region.kind = RegionDesc::Kind::Box;
  range(x, region.min.x(), region.max.x());
  range(y, region.min.y(), region.max.y());
  range(z, region.min.z(), region.max.z());
  const float grow = std::max(pad, 0.0f);
  for (int a = 0; a < 3; ++a) {
    region.min[a] -= grow;
    region.max[a] += grow;
    // A region box needs min < max on every axis (one particle, a flat sheet).
    if (!(region.min[a] < region.max[a])) {
      const float mid = 0.5f * (region.min[a] + region.max[a]);
      const float half = std::max(1e-4f, std::abs(mid) * 1e-5f);
      region.min[a] = mid - half;
      region.max[a] = mid + half;
    }
  }
  return region;
}

int pickParticleOnRay(const Vec3& origin, const Vec3& dir, const std::vector<float>& x,
                      const std::vector<float>& y, const std::vector<float>& z, float hit_radius) {
  const float len = dir.norm();
  if (!(len > 0.0f) || !(hit_radius > 0.0f)) return -1;
  const Vec3 d = dir / len;
  const float r2 = hit_radius * hit_radius;
  const size_t n = std::min({x.size(), y.size(), z.size()});
  int best = -1;
  float best_t = std::numeric_limits<float>::infinity();
  for (size_t i = 0; i < n; ++i) {
    const Vec3 rel = Vec3(x[i], y[i], z[i]) - origin;
    const float t = rel.dot(d);
    if (!(t > 0.0f) || t >= best_t) continue;
    if ((rel - t * d).squaredNorm() <= r2) {
      best_t = t;
      best = int(i);
    }
  }
  return best;
}

RegionDesc sphereRegion(const Vec3& center, float radius) {
  RegionDesc region;
  region.kind = RegionDesc::Kind::Sphere;
  region.center = center;
  region.radius = radius;
  return region;
}

}  // namespace ff::viewer
