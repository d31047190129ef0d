// target_shape.cpp - TargetSpec naming, buildTarget, TargetCache and
// resolveMeshPath.
#include "target/target_shape.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "core/resource_limits.h"
#include "target/analytic_shapes.h"
#include "target/euler_rotation.h"
#include "target/mesh_io.h"
#include "target/voxel_size_search.h"
#include "target/voxelize.h"

namespace ff {
namespace {

namespace fs = std::filesystem;

constexpr double kCountTolerance = 0.03;   // control_count: within 3%
constexpr double kVolumeTolerance = 0.01;  // default voxel: inside voxels hold the volume within 1%
constexpr size_t kMinInside = 8;

const char* kindName(TargetKind kind) {
  switch (kind) {
    case TargetKind::Mesh:
      return "mesh";
    case TargetKind::Sphere:
      return "sphere";
    case TargetKind::Box:
      return "box";
    case TargetKind::Torus:
      return "torus";
    case TargetKind::Capsule:
      return "capsule";
  }
  return "?";
}

std::string where(const TargetSpec& spec, const std::string& key = "") {
  return spec.where(key);
}

// The key that sets the voxel size; without one, the voxel is the fluid's
// default and the shape's size is what the user set: its volume, if given.
std::string voxelKey(const TargetSpec& spec) {
  return spec.voxel_size > 0.0f   ? "voxel_size"
         : spec.control_count > 0 ? "control_count"
         : spec.volume > 0.0f     ? "volume"
                                  : "";
}

// The key that sets the proportions of the shape.
std::string shapeKey(const TargetSpec& spec) {
  switch (spec.kind) {
    case TargetKind::Mesh:
      return "mesh";
    case TargetKind::Box:
      return "size";
    case TargetKind::Torus:
      return "minor";
    case TargetKind::Capsule:
      return "radius";
    case TargetKind::Sphere:
      break;
  }
  return "";
}

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(v == std::floor(v) && std::abs(v) < 1e9 ? 10 : 3);
  os << v;
  return os.str();
}

// Before voxelising: the voxel grid and the control particles must fit. A
// voxel grid has at most 4096 voxels per axis, so a shape more than 4096
// times longer than thick cannot have an inside voxel; and a shape thinner
// than the voxel has none, so the control_count search shrinks the voxel to
// the shape's thickness.
void checkVoxelWork(const TargetSpec& spec, const Vec3& lo, const Vec3& hi, double volume,
                    double default_voxel) {
  const Eigen::Vector3d extent = (hi - lo).cast<double>();
  const double thinnest = extent.minCoeff(), ratio = extent.maxCoeff() / thinnest;
  const std::string shape = fmt(extent[0]) + " x " + fmt(extent[1]) + " x " + fmt(extent[2]) + " m";
  if (!(ratio <= kMaxVoxelsPerAxis))
    throw Error(where(spec, shapeKey(spec)) + ": the shape (" + shape + " at volume " + fmt(volume) +
                " m^3) is " + fmt(ratio) + " times longer than thick; at most " + fmt(kMaxVoxelsPerAxis) +
                " (the voxels per axis of a voxel grid)");
  const double voxel = spec.voxel_size > 0.0f   ? double(spec.voxel_size)
                       : spec.control_count > 0 ? std::cbrt(volume / double(spec.control_count))
                                                : default_voxel;
  const double v = spec.control_count > 0 ? std::min(voxel, thinnest) : voxel;
  double voxels = 1.0, longest = 0.0;
  for (int a = 0; a < 3; ++a) {
    voxels *= std::ceil(extent[a] / v) + 3.0;
    longest = std::max(longest, std::ceil(extent[a] / v) + 3.0);
  }
  const std::string key = v < voxel ? shapeKey(spec) : voxelKey(spec);
  if (!(voxels <= kMaxVoxels) || !(longest <= kMaxVoxelsPerAxis))
    throw Error(where(spec, key) + ": voxels of " + fmt(v) + " m over a shape of " + shape + " make " +
                fmt(voxels) + " voxels (" + fmt(longest) + " along the longest axis), over the limit of " +
                fmt(kMaxVoxels) + " (" + fmt(kMaxVoxelsPerAxis) + " per axis)");
  checkMemory(voxels * kBytesPerVoxel, where(spec, key), "",
              "voxels of " + fmt(v) + " m over a shape of " + shape + " (" + fmt(voxels) + " voxels)");
  const double controls = volume / (voxel * voxel * voxel);
  checkMemory(controls * kBytesPerControlParticle, where(spec, key), "",
              "about " + fmt(controls) + " control particles");
}

// The shape, ready to voxelise: its bounding box centred at the origin and
// scaled to the requested volume.
struct PreparedShape {
  bool is_mesh = false;
  TriangleMesh mesh;
  AnalyticShape analytic;
  Vec3 lo{0, 0, 0}, hi{0, 0, 0};
  double volume = 0.0;
};

PreparedShape prepareMesh(const TargetSpec& spec, double volume) {
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(spec.rotation_deg[a])) throw Error(where(spec, "rotation") + ": must be finite");
  }
  const std::string path = spec.resolved_path.empty() ? resolveMeshPath(spec.mesh, "") : spec.resolved_path;
  PreparedShape out;
  out.is_mesh = true;
  try {
    out.mesh = loadMesh(path);
  } catch (const Error& e) {
    if (spec.origin.empty()) throw;
    throw Error(where(spec, "mesh") + ": " + e.what());  // e names the mesh file
  }
  TriangleMesh& mesh = out.mesh;

  // Rotate about the bounding-box centre, then centre the rotated box at the origin.
  Vec3 lo, hi;
  meshBounds(mesh, lo, hi);
  const Eigen::Vector3d centre = 0.5 * (lo + hi).cast<double>();
  const Eigen::Matrix3d rotation = eulerRotationXYZ(spec.rotation_deg);
  std::vector<Eigen::Vector3d> points(mesh.vertices.size());
  Eigen::AlignedBox3d rotated;
  for (size_t i = 0; i < points.size(); ++i) {
    points[i] = rotation * (mesh.vertices[i].cast<double>() - centre);
    rotated.extend(points[i]);
  }
  for (size_t i = 0; i < points.size(); ++i) mesh.vertices[i] = (points[i] - rotated.center()).cast<float>();

  double mesh_volume = meshVolume(mesh);
  // Inside-out meshes (all faces wound inwards) are accepted: the winding is
  // flipped. Ray parity ignores the winding anyway, so only the sign of the
  // volume matters. (loadMesh already rejected meshes with ~zero volume.)
  if (mesh_volume < 0.0) {
    for (auto& tri : mesh.triangles) std::swap(tri[1], tri[2]);
    mesh_volume = -mesh_volume;
  }
  const float scale = float(std::cbrt(volume / mesh_volume));
  for (Vec3& v : mesh.vertices) v *= scale;
  meshBounds(mesh, out.lo, out.hi);
  out.volume = meshVolume(mesh);
  return out;
}

PreparedShape prepareAnalytic(const TargetSpec& spec, double volume) {
  PreparedShape out;
  out.analytic = scaledToVolume(makeAnalyticShape(spec), volume);
  const Eigen::Vector3d half = out.analytic.halfExtent();
  out.hi = half.cast<float>();
  out.lo = -out.hi;
  out.volume = out.analytic.volume();
  return out;
}

VoxelGrid voxelizePrepared(const PreparedShape& shape, float voxel, const Vec3& shift) {
  VoxelGrid grid = makeVoxelGrid(shape.lo, shape.hi, voxel, shift);
  if (shape.is_mesh) {
    voxelizeMesh(shape.mesh, grid);
  } else {
    voxelizeAnalytic(shape.analytic, grid);
  }
  return grid;
}

double volumeToUse(const TargetSpec& spec, double fluid_rest_volume) {
  const double volume = spec.volume > 0.0f ? double(spec.volume) : fluid_rest_volume;
  if (!(volume > 0.0) || !std::isfinite(volume)) {
    std::ostringstream msg;
    msg << where(spec, spec.volume > 0.0f ? "volume" : "") << ": the target volume must be positive (volume "
        << spec.volume << ", fluid rest volume " << fluid_rest_volume << ")";
    throw Error(msg.str());
  }
  return volume;
}

}  // namespace

std::string TargetSpec::label() const {
  if (kind != TargetKind::Mesh) return kindName(kind);
  const std::string& name = mesh.empty() ? resolved_path : mesh;
  const std::string base = fs::path(name).filename().string();
  return base.empty() ? name : base;
}

std::string TargetSpec::where(const std::string& key) const {
  if (!origin.empty()) return key.empty() ? origin : origin + "." + key;
  std::string s = "target '" + label() + "'";
  if (kind == TargetKind::Mesh) s += " (" + (resolved_path.empty() ? mesh : resolved_path) + ")";
  return key.empty() ? s : s + ": " + key;
}

std::string TargetSpec::cacheKey(float volume_used) const {
  std::ostringstream key;
  key.precision(9);
  key << kindName(kind);
  switch (kind) {
    case TargetKind::Mesh:
      key << "|path=" << (resolved_path.empty() ? mesh : resolved_path);
      break;
    case TargetKind::Sphere:
      break;
    case TargetKind::Box:
      key << "|box=" << box_size.x() << "," << box_size.y() << "," << box_size.z();
      break;
    case TargetKind::Torus:
      key << "|torus=" << torus_major << "," << torus_minor;
      break;
    case TargetKind::Capsule:
      key << "|capsule=" << capsule_radius << "," << capsule_length;
      break;
  }
  key << "|rot=" << rotation_deg.x() << "," << rotation_deg.y() << "," << rotation_deg.z();
  key << "|count=" << control_count << "|voxel=" << voxel_size << "|volume=" << volume_used;
  return key.str();
}

size_t VoxelGrid::countInside() const {
  size_t n = 0;
  for (uint8_t v : inside) n += v != 0;
  return n;
}

Vec3 TargetShape::boundsMin() const {
  if (reference.empty()) return Vec3::Zero();
  Vec3 lo = reference.front();
  for (const Vec3& p : reference) lo = lo.cwiseMin(p);
  return lo - Vec3::Constant(0.5f * grid.voxel);
}

Vec3 TargetShape::boundsMax() const {
  if (reference.empty()) return Vec3::Zero();
  Vec3 hi = reference.front();
  for (const Vec3& p : reference) hi = hi.cwiseMax(p);
  return hi + Vec3::Constant(0.5f * grid.voxel);
}

TargetShape buildTarget(const TargetSpec& spec, double fluid_rest_volume, float default_voxel_size) {
  const double volume = volumeToUse(spec, fluid_rest_volume);
  if (spec.control_count < 0 || spec.voxel_size < 0.0f || !std::isfinite(spec.voxel_size)) {
    throw Error(where(spec) + ": control_count and voxel_size must not be negative");
  }
  if (spec.control_count > 0 && spec.voxel_size > 0.0f) {
    throw Error(where(spec) + ": give either control_count or voxel_size, not both");
  }
  if (spec.control_count > 0 && size_t(spec.control_count) < kMinInside) {
    throw Error(where(spec, "control_count") + ": must be at least " + std::to_string(kMinInside) + " (got " +
                std::to_string(spec.control_count) + ")");
  }
  const PreparedShape shape =
      spec.kind == TargetKind::Mesh ? prepareMesh(spec, volume) : prepareAnalytic(spec, volume);
  checkVoxelWork(spec, shape.lo, shape.hi, volume, default_voxel_size);

  TargetShape target;
  target.label = spec.label();
  target.shape_volume = shape.volume;
  const std::string context = where(spec, voxelKey(spec));
  auto voxelize = [&shape, &context](float voxel, const Vec3& shift) {
    try {
      return voxelizePrepared(shape, voxel, shift);
    } catch (const Error& e) {
      throw Error(context + ": " + e.what());
    }
  };
  if (spec.voxel_size > 0.0f) {
    target.grid = voxelize(spec.voxel_size, Vec3::Zero());
  } else if (spec.control_count > 0) {
    target.grid = searchVoxelSize(spec.control_count, kCountTolerance, volume, voxelize, context);
  } else {
    // Near the default size, a voxel whose inside voxels hold the shape's
    // volume: the fluid that is to fill them.
    target.grid = searchVoxelVolume(default_voxel_size, volume, kVolumeTolerance, voxelize);
  }

  const VoxelGrid& g = target.grid;
  target.reference.reserve(g.countInside());
  for (int k = 0; k < g.nz; ++k) {
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        if (g.inside[g.index(i, j, k)]) target.reference.push_back(g.center(i, j, k));
      }
    }
  }
  if (target.reference.size() < kMinInside) {
    std::ostringstream msg;
    msg << where(spec, voxelKey(spec)) << ": only " << target.reference.size()
        << " voxel(s) inside at voxel size " << g.voxel << " (at least " << kMinInside
        << " needed): the shape (volume " << volume
        << ") is too small for the voxel size; use a smaller voxel_size or a control_count";
    throw Error(msg.str());
  }
  return target;
}

const TargetShape& TargetCache::get(const TargetSpec& spec, double fluid_rest_volume,
                                    float default_voxel_size, const TargetShape* keep) {
  const double volume = volumeToUse(spec, fluid_rest_volume);
  std::string suffix;
  if (spec.control_count <= 0 && spec.voxel_size <= 0.0f) {
    std::ostringstream os;
    os.precision(9);
    os << "|default_voxel=" << default_voxel_size;
    suffix = os.str();
  }
  const std::string key = spec.cacheKey(float(volume)) + suffix;
  const std::string base_key = spec.cacheKey(0.0f) + suffix;
  for (Entry& e : entries_)
    if (e.key == key) return use(e, keep);
  if (spec.voxel_size <= 0.0f) {
    for (const Entry& e : entries_) {
      if (e.base_key != base_key) continue;
      // The same shape at another volume: scale lengths by the cube root.
      const double f = std::cbrt(volume / e.volume);
      auto shape = std::make_unique<TargetShape>(*e.shape);
      shape->grid.origin *= float(f);
      shape->grid.voxel *= float(f);
      for (Vec3& r : shape->reference) r *= float(f);
      shape->shape_volume *= f * f * f;
      entries_.push_back({key, base_key, volume, std::move(shape)});
      return use(entries_.back(), keep);
    }
  }
  auto shape = std::make_unique<TargetShape>(buildTarget(spec, fluid_rest_volume, default_voxel_size));
  ++voxelisations_;
  entries_.push_back({key, base_key, volume, std::move(shape)});
  return use(entries_.back(), keep);
}

namespace {
size_t shapeBytes(const TargetShape& s) {
  return sizeof(TargetShape) + s.grid.inside.capacity() + s.reference.capacity() * sizeof(Vec3);
}
}  // namespace

size_t TargetCache::bytes() const {
  size_t n = 0;
  for (const Entry& e : entries_) n += shapeBytes(*e.shape);
  return n;
}

const TargetShape& TargetCache::use(Entry& chosen, const TargetShape* keep) {
  chosen.last_use = ++clock_;
  const TargetShape* result = chosen.shape.get();
  // Drop the least recently used shapes while over a bound (the shape handed
  // out now and `keep` stay even then).
  for (;;) {
    if (entries_.size() <= kMaxEntries && bytes() <= kMaxBytes) break;
    auto oldest = entries_.end();
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
      if (it->shape.get() == result || it->shape.get() == keep) continue;
      if (oldest == entries_.end() || it->last_use < oldest->last_use) oldest = it;
    }
    if (oldest == entries_.end()) break;
    entries_.erase(oldest);
  }
  return *result;
}

std::string resolveMeshPath(const std::string& name, const std::string& scene_dir) {
  auto isFile = [](const fs::path& p) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) throw Error(p.string() + ": is a folder, not a mesh file");
    return fs::is_regular_file(p, ec);
  };
  if (name.empty()) throw Error("mesh path is empty");
  const fs::path given(name);
  std::vector<std::string> tried;
  if (given.is_absolute()) {
    if (isFile(given)) return given.lexically_normal().string();
    tried.push_back(given.parent_path().string());
  } else {
    if (!scene_dir.empty()) {
      const fs::path candidate = fs::path(scene_dir) / given;
      if (isFile(candidate)) return candidate.lexically_normal().string();
      tried.push_back(scene_dir);
    }
    if (const char* env = std::getenv("FLOWFORM_MESH_PATH")) {
      std::stringstream folders(env);
      std::string folder;
      while (std::getline(folders, folder, ':')) {
        if (folder.empty()) continue;
        const fs::path candidate = fs::path(folder) / given;
        if (isFile(candidate)) return candidate.lexically_normal().string();
        tried.push_back(folder);
      }
    }
  }
  std::string msg = "mesh '" + name + "' not found; looked in: ";
  if (tried.empty()) msg += "no folder (a relative path, no scene folder and FLOWFORM_MESH_PATH empty)";
  for (size_t i = 0; i < tried.size(); ++i) msg += (i ? ", " : "") + tried[i];
  msg += " (set FLOWFORM_MESH_PATH to a colon-separated list of folders holding meshes";
  msg += given.is_absolute() ? ", or fix the absolute path)" : ")";
  throw Error(msg);
}

}  // namespace ff
