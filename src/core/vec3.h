// vec3.h - host-side small vector type (Eigen) used outside the hot loops.
#pragma once
#include <Eigen/Core>

namespace ff {
using Vec3 = Eigen::Vector3f;
using Vec3d = Eigen::Vector3d;
}  // namespace ff
