// region_pick.h - the window-free geometry of region selection (the paper's
// Figs. 2 and 7): which fluid particles a screen rectangle covers, the box
// around them, and the particle under the mouse for the sphere brush.
#pragma once
#include <cstddef>
#include <vector>

#include "core/vec3.h"
#include "render/camera.h"
#include "scene/scene.h"

namespace ff::viewer {

// A rectangle in pixels of a width x height viewport, origin top-left; the two
// corners may be given in any order.
struct ScreenRect {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Projects p with the camera into pixel coordinates (origin top-left, pixel
// centres at +0.5). False when p is behind the camera's near plane.
bool projectToPixel(const render::OrbitCamera& camera, int width, int height, const Vec3& p, float& px,
                    float& py);

// Indices of the particles whose projection lies inside the rectangle (edges
// included) and in front of the camera, in increasing order.
std::vector<int> particlesInRect(const render::OrbitCamera& camera, int width, int height,
                                 const std::vector<float>& x, const std::vector<float>& y,
                                 const std::vector<float>& z, const ScreenRect& rect);

// The box around the chosen particles: per axis the 1st to 99th percentile
// (all of them for fewer than 200, as Simulation::setTarget does), grown by
// `pad` on every side. A region kind Box; kind All when `chosen` is empty.
RegionDesc boxAroundParticles(const std::vector<float>& x, const std::vector<float>& y,
                              const std::vector<float>& z, const std::vector<int>& chosen, float pad);

// The particle the sphere brush hits: among the particles within `hit_radius`
// of the ray (origin + t dir, t > 0, dir need not be unit), the one nearest
// to the origin along the ray. -1 when the ray misses them all.
int pickParticleOnRay(const Vec3& origin, const Vec3& dir, const std::vector<float>& x,
                      const std::vector<float>& y, const std::vector<float>& z, float hit_radius);

// A sphere region of the given centre and radius.
RegionDesc sphereRegion(const Vec3& center, float radius);

}  // namespace ff::viewer
