// test_scenes.h - the scenes the tests build, written once: a box container
// with one block of fluid at the rest spacing, and targets by kind; the same
// as JSON text for the tests of the program's commands.
#pragma once
#include <string>

#include "control/control_set.h"
#include "core/vec3.h"
#include "scene/scene.h"
#include "target/target_shape.h"

namespace fftest {

// A box container from the origin to `box_max` holding one block of
// nx x ny x nz particles at the rest spacing, its corner at `origin`; no target.
inline ff::SceneDesc blockScene(const ff::Vec3& box_max, const ff::Vec3& origin, int nx, int ny, int nz,
                                const std::string& source = "test") {
  ff::SceneDesc s;
  s.source = source;
  s.container.min = ff::Vec3(0.0f, 0.0f, 0.0f);
  s.container.max = box_max;
  ff::FluidBlockDesc b;
  b.origin = origin;
  b.dims[0] = nx, b.dims[1] = ny, b.dims[2] = nz;
  s.fluid.push_back(b);
  return s;
}

// A built-in target shape; control_count 0 leaves the count to the fluid.
inline ff::TargetSpec target(ff::TargetKind kind, int control_count = 0) {
  ff::TargetSpec t;
  t.kind = kind;
  t.control_count = control_count;
  return t;
}

// A torus (control_count 700) of a quarter of the fluid's volume, formed over
// a block 30 x 16 x 30 particles wide: its control particles all lie in the
// fluid (each reads filled), the block's corners out of their reach.
inline ff::SceneDesc immersedTorusScene() {
  ff::SceneDesc s = blockScene(ff::Vec3(0.36f, 0.25f, 0.36f), ff::Vec3(0.085f, 0.0f, 0.085f), 30, 16, 30);
  ff::TargetSpec torus = target(ff::TargetKind::Torus, 700);
  torus.torus_major = 1.0f, torus.torus_minor = 0.3f;
  torus.volume = 0.25f * float(30 * 16 * 30) * s.params.fluid.restVolume();
  s.schedule.push_back({0.0, torus});
  return s;
}

// Scene JSON: a cube container of side `box` holding an n^3 block at `origin`
// (x, 0, z), with `extra` (e.g. "\"target\": \"sphere\"") added to the top level.
inline std::string blockSceneJson(const std::string& name, double box, double x, double z, int n,
                                  const std::string& extra) {
  const std::string b = std::to_string(box), d = std::to_string(n);
  return "{\"name\": \"" + name + "\", \"container\": {\"min\": [0, 0, 0], \"max\": [" + b + ", " + b + ", " +
         b + "]}, \"fluid\": [{\"origin\": [" + std::to_string(x) + ", 0.0, " + std::to_string(z) +
         "], \"dims\": [" + d + ", " + d + ", " + d + "]}]" + (extra.empty() ? "" : ", " + extra) + "}";
}

// Makes s's particles one cluster about its rest centre (rest_cx, rest_cy, rest_cz).
inline void setOneCluster(ff::ControlSet& s) {
  const uint32_t n = uint32_t(s.size());
  ff::Clusters& cl = s.clusters;
  cl = ff::Clusters();
  cl.start = {0, n};
  for (uint32_t p = 0; p < n; ++p) cl.members.push_back(p), cl.of.push_back(0), cl.of_start.push_back(p);
  cl.of_start.push_back(n);
  cl.rest_cx = {s.rest_cx}, cl.rest_cy = {s.rest_cy}, cl.rest_cz = {s.rest_cz};
}

}  // namespace fftest
