// control_set.h - control particles (Thuerey et al. 2006) with their rest
// shape and shape-matching clusters, structure of arrays.
//
// Control particles keep a fixed order (the reference voxel order, which is
// already sorted by the rest shape's grid cell); neighbour queries go through
// an index grid rebuilt each step, so cluster membership never needs remapping.
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "ff_control.h"

namespace ff {

// Overlapping clusters in compressed-row form.
struct Clusters {
  std::vector<uint32_t> start;                   // cluster c holds members[start[c] .. start[c+1])
  std::vector<uint32_t> members;                 // control-particle indices
  std::vector<float> rest_cx, rest_cy, rest_cz;  // rest centre of mass of each cluster
  // Rest-shape blend: each cluster's centre of mass in the start
  // configuration (ControlSet::bx0); empty with no blend.
  std::vector<float> from_cx, from_cy, from_cz;
  // particle -> clusters, compressed-row: particle i is in of[of_start[i] .. of_start[i+1])
  std::vector<uint32_t> of_start;
  std::vector<uint32_t> of;
  size_t count() const { return start.empty() ? 0 : start.size() - 1; }
};

struct ControlSet {
  std::vector<float> x, y, z;     // current positions
  std::vector<float> vx, vy, vz;  // current velocities
  std::vector<float> x0, y0, z0;  // rest positions (reference particles, target frame)
  // Adaptive control: each particle's radius as a share (0, 1] of
  // params.control.radius (placement: the target's local thickness). Empty,
  // or of another size than x: 1 for every particle (the controller and the
  // OpenCL backend fill it so).
  std::vector<float> radius_scale;
  // Rest-shape blend at a target change (kernels/common/ff_control.h,
  // ff_blend_weight): the start configuration each rest position moves from
  // to (x0, y0, z0) over blend_time seconds of the shape-matching clock;
  // blend_elapsed of them have run. Empty (and blend_time 0): no blend.
  std::vector<float> bx0, by0, bz0;
  float blend_time = 0.0f;
  double blend_elapsed = 0.0;
  // The blend weight of the next shape-matching step (1: the reference alone).
  float blendWeight() const {
    return !x.empty() && bx0.size() == x.size() ? ff_blend_weight(float(blend_elapsed), blend_time) : 1.0f;
  }
  bool blending() const { return blendWeight() < 1.0f; }
  Clusters clusters;
  float rest_cx = 0, rest_cy = 0, rest_cz = 0;  // rest centre of mass of the whole shape
  float particle_volume = 0;                    // rest volume of one control particle (the voxel volume)
  // The anchor (shape_matching.anchor, kernels/common/ff_anchor.h): the centre
  // of mass the set is held at along "up", where the placement put the rest
  // shape (placeControlParticles). NaN: the set's centre of mass when the
  // controller takes it (anchorAtCentre).
  float anchor_x = std::numeric_limits<float>::quiet_NaN(), anchor_y = anchor_x, anchor_z = anchor_x;
  size_t size() const { return x.size(); }
};

// The centre of mass of the points (x, y, z)[p], summed in double (0 for none).
inline void centreOfMass(const std::vector<float>& x, const std::vector<float>& y,
                         const std::vector<float>& z, double c[3]) {
  c[0] = c[1] = c[2] = 0.0;
  for (size_t p = 0; p < x.size(); ++p) c[0] += x[p], c[1] += y[p], c[2] += z[p];
  for (int d = 0; d < 3 && !x.empty(); ++d) c[d] /= double(x.size());
}

// Sets an unset (non-finite) anchor to the set's centre of mass.
inline void anchorAtCentre(ControlSet& s) {
  if (std::isfinite(s.anchor_x) && std::isfinite(s.anchor_y) && std::isfinite(s.anchor_z)) return;
  double c[3];
  centreOfMass(s.x, s.y, s.z, c);
  s.anchor_x = float(c[0]), s.anchor_y = float(c[1]), s.anchor_z = float(c[2]);
}

// Per-step values the controller computes for each control particle.
struct ControlFields {
  std::vector<float> s;           // eq. 5 density scale
  std::vector<float> ux, uy, uz;  // kernel-weighted fluid velocity around the particle
};

}  // namespace ff
