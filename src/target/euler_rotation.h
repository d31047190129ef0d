// euler_rotation.h - the rotation a TargetSpec asks for: rotation_deg applied
// about x first, then y, then z (degrees), i.e. R = Rz * Ry * Rx.
#pragma once
#include <Eigen/Geometry>

#include "core/vec3.h"

namespace ff {

inline Eigen::Matrix3d eulerRotationXYZ(const Vec3& degrees) {
  const double k = 3.14159265358979323846 / 180.0;
  const Eigen::Matrix3d rx = Eigen::AngleAxisd(k * degrees.x(), Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Matrix3d ry = Eigen::AngleAxisd(k * degrees.y(), Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3d rz = Eigen::AngleAxisd(k * degrees.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return rz * ry * rx;
}

}  // namespace ff
