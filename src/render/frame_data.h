// frame_data.h - everything one rendered frame shows, copied out of a
// Simulation (or built by hand in tests), so that rendering never touches the
// backend.
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "scene/scene.h"

namespace ff {
class Simulation;
}

namespace ff::render {

struct FrameData {
  // Fluid particles (any order).
  std::vector<float> x, y, z;
  float particle_radius = 0.0059f;
  // Rest volume of one particle (mass / rest density), m^3. The thickness
  // pass sums the particles' sphere chords and scales them by this over the
  // sphere's volume, so absorption acts on metres of liquid. 0: no scaling.
  float particle_volume = 0.0f;
  // Control particles with their density scale s_i (eq. 5), 0..1.
  std::vector<float> cx, cy, cz, cs;
  // The target's reference particles placed at the control particles' best
  // rigid fit (world space), drawn as a ghost; empty when there is no target.
  std::vector<Vec3> ghost;
  float ghost_voxel = 0.0f;  // edge of one ghost voxel
  // The best fit's rotation (the ghost voxels' orientation in the world).
  Eigen::Matrix3f ghost_rotation = Eigen::Matrix3f::Identity();
  // Per ghost voxel, which of its faces lie on the shape's surface (bit 0..5:
  // -x, +x, -y, +y, -z, +z in the shape's frame), so that the ghost is drawn
  // as a translucent shell. Empty: every face is drawn.
  std::vector<uint8_t> ghost_faces;
  ContainerDesc container;
  // The controlled region (drawn as a wireframe when it is a box or sphere).
  RegionDesc region;
  double time = 0.0;
};

// Copies the current state of `sim` (fluid, control, ghost, container, region).
FrameData captureFrame(Simulation& sim);

}  // namespace ff::render
