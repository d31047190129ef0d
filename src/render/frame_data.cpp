// frame_data.cpp - copies what a frame shows out of a running Simulation.
#include "render/frame_data.h"

#include <cmath>

#include "control/shape_matching.h"
#include "sim/simulation.h"

namespace ff::render {

namespace {

// Iterations of the best-fit rotation extraction (the same number the
// simulation uses when it regenerates a target from the current shape).
constexpr int kBestFitIterations = 50;

// Which faces of each reference voxel border the outside of the shape.
std::vector<uint8_t> surfaceFaces(const TargetShape& t) {
  const VoxelGrid& g = t.grid;
  std::vector<uint8_t> faces(t.reference.size(), 0);
  if (g.voxel <= 0.0f) return std::vector<uint8_t>(t.reference.size(), 0x3f);
  auto inside = [&g](int i, int j, int k) {
    return i >= 0 && j >= 0 && k >= 0 && i < g.nx && j < g.ny && k < g.nz && g.inside[g.index(i, j, k)] != 0;
  };
  static const int kDir[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  for (size_t p = 0; p < t.reference.size(); ++p) {
    const Vec3 cell = (t.reference[p] - g.origin) / g.voxel;
    const int i = int(std::floor(cell.x())), j = int(std::floor(cell.y())), k = int(std::floor(cell.z()));
    uint8_t mask = 0;
    for (int f = 0; f < 6; ++f)
      if (!inside(i + kDir[f][0], j + kDir[f][1], k + kDir[f][2])) mask = uint8_t(mask | (1u << f));
    faces[p] = mask;
  }
  return faces;
}

}  // namespace

FrameData captureFrame(Simulation& sim) {
  FrameData f;
  FluidState fluid;
  sim.backend().readFluid(fluid);
  f.x = std::move(fluid.x);
  f.y = std::move(fluid.y);
  f.z = std::move(fluid.z);
  f.particle_radius = sim.scene().params.fluid.particle_radius;
  f.particle_volume = sim.scene().params.fluid.restVolume();
  f.container = sim.scene().container;
  f.region = sim.scene().region;
  f.time = sim.time();

  const TargetShape* target = sim.target();
  if (!target) return f;
  ControlSet set;
  ControlFields fields;
  sim.backend().readControl(set, fields);
  f.cx = set.x;
  f.cy = set.y;
  f.cz = set.z;
  f.cs = fields.s;
  f.cs.resize(set.size(), 1.0f);  // before the first step the controller has not computed s yet
  if (set.size() == 0) return f;

  // Ghost: the reference particles (the control particles' rest positions x0)
  // where the best rigid fit of the control particles puts them,
  // x = R (x0 - rest_c) + c, the frame shape matching pulls the fluid towards.
  ff_quat q = FF_Q(0.0f, 0.0f, 0.0f, 1.0f);
  float c[3] = {0.0f, 0.0f, 0.0f};
  bestFitFrame(set, q, c, kBestFitIterations);
  const ff_mat3 r = ff_quat_to_mat3(q);
  const ff_float3 rest_c = FF_F3(set.rest_cx, set.rest_cy, set.rest_cz);
  f.ghost.reserve(target->reference.size());
  for (const Vec3& ref : target->reference) {
    const ff_float3 w = ff_mat3_mul_vec(r, FF_F3(ref.x(), ref.y(), ref.z()) - rest_c);
    f.ghost.emplace_back(w.x + c[0], w.y + c[1], w.z + c[2]);
  }
  for (int col = 0; col < 3; ++col) {
    const ff_float3 axis =
        ff_mat3_mul_vec(r, FF_F3(col == 0 ? 1.0f : 0.0f, col == 1 ? 1.0f : 0.0f, col == 2 ? 1.0f : 0.0f));
    f.ghost_rotation.col(col) = Vec3(axis.x, axis.y, axis.z);
  }
  f.ghost_voxel = target->grid.voxel;
  f.ghost_faces = surfaceFaces(*target);
  return f;
}

}  // namespace ff::render
