// analytic_shapes.h - sphere, box, torus and capsule targets: inside tests,
// exact volumes and bounds. All are centred at the origin; the proportions
// come from a TargetSpec and the size from scaledToVolume().
#pragma once
#include <Eigen/Core>

#include "target/target_shape.h"

namespace ff {

struct AnalyticShape {
  TargetKind kind = TargetKind::Sphere;
  double radius = 1.0;                 // Sphere; Capsule: radius of the caps and the cylinder
  Eigen::Vector3d half_size{1, 1, 1};  // Box: half edge lengths
  double major = 1.0, minor = 0.4;     // Torus around the y axis: R, r
  double length = 1.0;                 // Capsule along the y axis: length of the cylinder part
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // shape frame -> target frame

  bool inside(const Eigen::Vector3d& p) const;  // p in the target frame; the surface counts as inside
  double volume() const;                        // exact (rotation does not change it)
  Eigen::Vector3d halfExtent() const;           // half size of the tight axis-aligned bounding box
};

// The shape of spec.kind (not Mesh) with spec's proportions and rotation.
// Throws ff::Error for proportions that are not positive and finite, or a
// torus whose minor radius is not smaller than its major radius.
AnalyticShape makeAnalyticShape(const TargetSpec& spec);

// The same shape scaled uniformly so that volume() == volume.
AnalyticShape scaledToVolume(const AnalyticShape& shape, double volume);

// Sets grid.inside (resized to the grid) from shape.inside() at the voxel centres.
void voxelizeAnalytic(const AnalyticShape& shape, VoxelGrid& grid);

}  // namespace ff
