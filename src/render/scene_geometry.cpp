// scene_geometry.cpp - container, floor, region and instance geometry.
#include "render/scene_geometry.h"

#include <algorithm>
#include <cmath>

namespace ff::render {

namespace {

void pushVec(std::vector<float>& out, const Vec3& v) {
  out.insert(out.end(), {v.x(), v.y(), v.z()});
}

// Two triangles of the quad a b c d (in order around it) with normal n.
void pushQuad(std::vector<float>& out, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
              const Vec3& n) {
  for (const Vec3* p : {&a, &b, &c, &a, &c, &d}) {
    pushVec(out, *p);
    pushVec(out, n);
  }
}

}  // namespace

std::vector<float> boxEdges(const Vec3& lo, const Vec3& hi) {
  std::vector<float> out;
  auto corner = [&](int i) {
    return Vec3((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
  };
  // Corners i and j are joined by an edge when their indices differ in one bit.
  for (int i = 0; i < 8; ++i)
    for (int bit = 1; bit < 8; bit <<= 1)
      if (!(i & bit)) {
        pushVec(out, corner(i));
        pushVec(out, corner(i | bit));
      }
  return out;
}

std::vector<float> sphereWireframe(const Vec3& centre, float radius, int segments) {
  std::vector<float> out;
  const float kTwoPi = 6.28318530718f;
  for (int plane = 0; plane < 3; ++plane) {
    const int a = plane, b = (plane + 1) % 3;
    for (int s = 0; s < segments; ++s) {
      for (int e = 0; e < 2; ++e) {
        const float t = kTwoPi * float(s + e) / float(segments);
        Vec3 p = centre;
        p[a] += radius * std::cos(t);
        p[b] += radius * std::sin(t);
        pushVec(out, p);
      }
    }
  }
  return out;
}

std::vector<float> regionWireframe(const RegionDesc& region) {
  switch (region.kind) {
    case RegionDesc::Kind::Box:
      return boxEdges(region.min, region.max);
    case RegionDesc::Kind::Sphere:
      return sphereWireframe(region.center, region.radius, 64);
    case RegionDesc::Kind::All:
      break;
  }
  return {};
}

std::vector<float> floorQuad(const ContainerDesc& c, float half_extent) {
  const Vec3 m = 0.5f * (c.min + c.max);
  const float y = c.min.y(), e = half_extent;
  std::vector<float> out;
  pushQuad(out, Vec3(m.x() - e, y, m.z() - e), Vec3(m.x() - e, y, m.z() + e), Vec3(m.x() + e, y, m.z() + e),
           Vec3(m.x() + e, y, m.z() - e), Vec3(0.0f, 1.0f, 0.0f));
  return out;
}

std::vector<float> containerWalls(const ContainerDesc& c) {
  const Vec3 lo = c.min, hi = c.max;
  std::vector<float> out;
  pushQuad(out, Vec3(lo.x(), lo.y(), lo.z()), Vec3(lo.x(), hi.y(), lo.z()), Vec3(lo.x(), hi.y(), hi.z()),
           Vec3(lo.x(), lo.y(), hi.z()), Vec3(-1.0f, 0.0f, 0.0f));
  pushQuad(out, Vec3(hi.x(), lo.y(), lo.z()), Vec3(hi.x(), lo.y(), hi.z()), Vec3(hi.x(), hi.y(), hi.z()),
           Vec3(hi.x(), hi.y(), lo.z()), Vec3(1.0f, 0.0f, 0.0f));
  pushQuad(out, Vec3(lo.x(), lo.y(), lo.z()), Vec3(hi.x(), lo.y(), lo.z()), Vec3(hi.x(), hi.y(), lo.z()),
           Vec3(lo.x(), hi.y(), lo.z()), Vec3(0.0f, 0.0f, -1.0f));
  pushQuad(out, Vec3(lo.x(), lo.y(), hi.z()), Vec3(lo.x(), hi.y(), hi.z()), Vec3(hi.x(), hi.y(), hi.z()),
           Vec3(hi.x(), lo.y(), hi.z()), Vec3(0.0f, 0.0f, 1.0f));
  return out;
}

PixelRect projectedBounds(const std::vector<float>& instances, const Eigen::Matrix4f& view_proj, float radius,
                          int width, int height, int margin) {
  const float proj_11 = view_proj.row(1).head<3>().norm();  // the projection's y scale (view is a rotation)
  float lo_x = 1e30f, lo_y = 1e30f, hi_x = -1e30f, hi_y = -1e30f, nearest = 1e30f;
  for (size_t i = 0; i + 3 < instances.size(); i += 4) {
    const Eigen::Vector4f c =
        view_proj * Eigen::Vector4f(instances[i], instances[i + 1], instances[i + 2], 1.0f);
    if (c.w() <= radius) return {0, 0, width, height, 0.0f};
    const float sx = (0.5f * c.x() / c.w() + 0.5f) * float(width);
    const float sy = (0.5f * c.y() / c.w() + 0.5f) * float(height);
    // Twice the projected radius: room for the impostors' 1/cos stretch.
    const float r = 2.0f * radius * proj_11 * 0.5f * float(height) / c.w();
    lo_x = std::min(lo_x, sx - r), hi_x = std::max(hi_x, sx + r);
    lo_y = std::min(lo_y, sy - r), hi_y = std::max(hi_y, sy + r);
    nearest = std::min(nearest, c.w());
  }
  if (hi_x < lo_x) return {0, 0, 0, 0, 0.0f};
  const int x0 = std::clamp(int(std::floor(lo_x)) - margin, 0, width);
  const int y0 = std::clamp(int(std::floor(lo_y)) - margin, 0, height);
  const int x1 = std::clamp(int(std::ceil(hi_x)) + margin, 0, width);
  const int y1 = std::clamp(int(std::ceil(hi_y)) + margin, 0, height);
  return {x0, y0, x1 - x0, y1 - y0, nearest};
}

float floorTile(const ContainerDesc& c) {
  const float extent = (c.max - c.min).maxCoeff();
  const float want = extent > 0.0f ? extent / 8.0f : 0.05f;
  const float decade = std::pow(10.0f, std::floor(std::log10(want)));
  float best = decade;
  for (float m : {1.0f, 2.0f, 5.0f, 10.0f})
    if (std::abs(std::log(m * decade / want)) < std::abs(std::log(best / want))) best = m * decade;
  return best;
}

std::vector<float> fluidInstances(const FrameData& f) {
  const size_t n = std::min({f.x.size(), f.y.size(), f.z.size()});
  std::vector<float> out(4 * n);
  for (size_t i = 0; i < n; ++i) {
    out[4 * i] = f.x[i], out[4 * i + 1] = f.y[i], out[4 * i + 2] = f.z[i], out[4 * i + 3] = 0.0f;
  }
  return out;
}

std::vector<float> controlInstances(const FrameData& f) {
  const size_t n = std::min({f.cx.size(), f.cy.size(), f.cz.size()});
  std::vector<float> out(4 * n);
  for (size_t i = 0; i < n; ++i) {
    out[4 * i] = f.cx[i], out[4 * i + 1] = f.cy[i], out[4 * i + 2] = f.cz[i];
    out[4 * i + 3] = i < f.cs.size() ? f.cs[i] : 1.0f;
  }
  return out;
}

std::vector<float> ghostFaceInstances(const FrameData& f) {
  std::vector<float> out;
  const bool all = f.ghost_faces.size() != f.ghost.size();
  for (size_t i = 0; i < f.ghost.size(); ++i) {
    const unsigned mask = all ? 0x3fu : f.ghost_faces[i];
    for (int face = 0; face < 6; ++face)
      if (mask & (1u << face))
        out.insert(out.end(), {f.ghost[i].x(), f.ghost[i].y(), f.ghost[i].z(), float(face)});
  }
  return out;
}

}  // namespace ff::render
