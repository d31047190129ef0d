// analytic_shapes.cpp - inside tests, volumes and bounds of the analytic targets.
#include "target/analytic_shapes.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "target/euler_rotation.h"

namespace ff {
namespace {

constexpr double kPi = 3.14159265358979323846;

void requirePositive(double value, const char* field, const std::string& label) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    std::ostringstream msg;
    msg << "target '" << label << "': " << field << " must be a positive number (got " << value << ")";
    throw Error(msg.str());
  }
}

}  // namespace

bool AnalyticShape::inside(const Eigen::Vector3d& p_target) const {
  const Eigen::Vector3d p = rotation.transpose() * p_target;
  switch (kind) {
    case TargetKind::Sphere:
      return p.squaredNorm() <= radius * radius;
    case TargetKind::Box:
      return std::abs(p.x()) <= half_size.x() && std::abs(p.y()) <= half_size.y() &&
             std::abs(p.z()) <= half_size.z();
    case TargetKind::Torus: {
      const double ring = std::hypot(p.x(), p.z()) - major;
      return ring * ring + p.y() * p.y() <= minor * minor;
    }
    case TargetKind::Capsule: {
      const double axial = std::max(0.0, std::abs(p.y()) - 0.5 * length);
      return p.x() * p.x() + p.z() * p.z() + axial * axial <= radius * radius;
    }
    case TargetKind::Mesh:
      break;
  }
  return false;
}

double AnalyticShape::volume() const {
  switch (kind) {
    case TargetKind::Sphere:
      return 4.0 / 3.0 * kPi * radius * radius * radius;
    case TargetKind::Box:
      return 8.0 * half_size.prod();
    case TargetKind::Torus:
      return 2.0 * kPi * kPi * major * minor * minor;
    case TargetKind::Capsule:
      return kPi * radius * radius * length + 4.0 / 3.0 * kPi * radius * radius * radius;
    case TargetKind::Mesh:
      break;
  }
  return 0.0;
}

Eigen::Vector3d AnalyticShape::halfExtent() const {
  // Support function along each target axis e: the shape-frame direction is
  // d = R^T e (row of R); y-axis symmetric shapes only need d.y.
  Eigen::Vector3d half;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d d = rotation.row(a).transpose();
    const double along_y = std::min(1.0, std::abs(d.y()));
    switch (kind) {
      case TargetKind::Sphere:
        half[a] = radius;
        break;
      case TargetKind::Box:
        half[a] = d.cwiseAbs().dot(half_size);
        break;
      case TargetKind::Torus:
        half[a] = major * std::sqrt(1.0 - along_y * along_y) + minor;
        break;
      case TargetKind::Capsule:
        half[a] = 0.5 * length * along_y + radius;
        break;
      case TargetKind::Mesh:
        half[a] = 0.0;
        break;
    }
  }
  return half;
}

AnalyticShape makeAnalyticShape(const TargetSpec& spec) {
  const std::string label = spec.label();
  AnalyticShape shape;
  shape.kind = spec.kind;
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(spec.rotation_deg[a])) {
      throw Error("target '" + label + "': rotation_deg must be finite");
    }
  }
  shape.rotation = eulerRotationXYZ(spec.rotation_deg);
  switch (spec.kind) {
    case TargetKind::Sphere:
      shape.radius = 1.0;
      break;
    case TargetKind::Box:
      requirePositive(spec.box_size.x(), "box_size x", label);
      requirePositive(spec.box_size.y(), "box_size y", label);
      requirePositive(spec.box_size.z(), "box_size z", label);
      shape.half_size = 0.5 * spec.box_size.cast<double>();
      break;
    case TargetKind::Torus:
      requirePositive(spec.torus_major, "torus_major", label);
      requirePositive(spec.torus_minor, "torus_minor", label);
      if (!(spec.torus_minor < spec.torus_major)) {
        std::ostringstream msg;
        msg << "target '" << label << "': torus_minor (" << spec.torus_minor
            << ") must be smaller than torus_major (" << spec.torus_major << ")";
        throw Error(msg.str());
      }
      shape.major = spec.torus_major;
      shape.minor = spec.torus_minor;
      break;
    case TargetKind::Capsule:
      requirePositive(spec.capsule_radius, "capsule_radius", label);
      if (!(spec.capsule_length >= 0.0f) || !std::isfinite(spec.capsule_length)) {
        std::ostringstream msg;
        msg << "target '" << label << "': capsule_length must be zero or positive (got "
            << spec.capsule_length << ")";
        throw Error(msg.str());
      }
      shape.radius = spec.capsule_radius;
      shape.length = spec.capsule_length;
      break;
    case TargetKind::Mesh:
      throw Error("target '" + label + "': a mesh is not an analytic shape");
  }
  return shape;
}

AnalyticShape scaledToVolume(const AnalyticShape& shape, double volume) {
  const double s = std::cbrt(volume / shape.volume());
  AnalyticShape out = shape;
  out.radius *= s;
  out.half_size *= s;
  out.major *= s;
  out.minor *= s;
  out.length *= s;
  return out;
}

void voxelizeAnalytic(const AnalyticShape& shape, VoxelGrid& grid) {
  grid.inside.assign(size_t(grid.nx) * size_t(grid.ny) * size_t(grid.nz), 0);
#pragma omp parallel for schedule(static)
  for (int k = 0; k < grid.nz; ++k) {
    for (int j = 0; j < grid.ny; ++j) {
      for (int i = 0; i < grid.nx; ++i) {
        grid.inside[grid.index(i, j, k)] = uint8_t(shape.inside(grid.center(i, j, k).cast<double>()));
      }
    }
  }
}

}  // namespace ff
