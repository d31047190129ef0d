// target_shape.h - what the user wants the fluid to become: a voxelised shape
// whose inside voxel centres are the reference particles (paper Fig. 6).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/vec3.h"

namespace ff {

enum class TargetKind { Mesh, Sphere, Box, Torus, Capsule };

// What a scene (or the API) asks for. Analytic shapes give proportions only:
// like meshes they are scaled to `volume` (default: the controlled fluid's rest
// volume) before voxelising.
struct TargetSpec {
  TargetKind kind = TargetKind::Sphere;
  std::string mesh;                                    // for Mesh: the path as the user wrote it
  std::string resolved_path;                           // for Mesh: the file actually read
  Vec3 box_size{1.0f, 1.0f, 1.0f};                     // Box: edge lengths (proportions)
  float torus_major = 1.0f, torus_minor = 0.4f;        // Torus around the y axis
  float capsule_radius = 0.5f, capsule_length = 1.0f;  // Capsule along y; length of the cylinder part
  Vec3 rotation_deg{0.0f, 0.0f, 0.0f};  // applied to the shape before voxelising (x, then y, then z)
  int control_count = 0;    // > 0: choose the voxel size so the reference count is within 3% of this
  float voxel_size = 0.0f;  // > 0: this voxel size (control_count must then be 0)
  float volume = 0.0f;      // > 0: scale to this volume instead of the fluid's rest volume
  // Where the spec was written, for messages: "FILE: KEY.PATH" (e.g.
  // "scene.json: schedule[1].target"); empty for targets made in code.
  std::string origin;

  // A short human-readable name: "sphere", "bunny.obj", ...
  std::string label() const;
  // Where a message about `key` (e.g. "control_count"; "" for the whole spec)
  // points: "FILE: PATH.key" for a spec from a file, else
  // "target 'LABEL' (MESH): key".
  std::string where(const std::string& key = "") const;
  // A key that identifies the voxelisation (used by the cache).
  std::string cacheKey(float volume_used) const;
};

// A regular grid of voxels. Voxel (i, j, k) spans origin + [i, i+1) * voxel etc.
// Index of (i, j, k) is i + nx * (j + ny * k).
struct VoxelGrid {
  Vec3 origin{0.0f, 0.0f, 0.0f};
  float voxel = 0.0f;
  int nx = 0, ny = 0, nz = 0;
  std::vector<uint8_t> inside;  // 1 = inside the shape

  size_t index(int i, int j, int k) const {
    return size_t(i) + size_t(nx) * (size_t(j) + size_t(ny) * size_t(k));
  }
  Vec3 center(int i, int j, int k) const {
    return origin + voxel * Vec3(float(i) + 0.5f, float(j) + 0.5f, float(k) + 0.5f);
  }
  size_t countInside() const;
};

struct TargetShape {
  std::string label;
  VoxelGrid grid;               // shape frame: the shape's bounding box is centred at the origin
  std::vector<Vec3> reference;  // centres of the inside voxels, in grid index order
  double shape_volume = 0.0;    // volume of the scaled continuous shape (analytic, or by divergence theorem)
  double voxel_volume() const {
    return double(reference.size()) * double(grid.voxel) * grid.voxel * grid.voxel;
  }
  Vec3 boundsMin() const;  // bounding box of the reference particles (voxel extents included)
  Vec3 boundsMax() const;
};

// Builds the target: loads/creates the shape, scales it to `volume` (or
// spec.volume), voxelises it and places the reference particles.
// Throws ff::Error naming the spec's origin (file and key), the mesh file and
// the problem. Before voxelising, the voxel grid and the control particles are
// estimated and refused over the limits of core/resource_limits.h.
TargetShape buildTarget(const TargetSpec& spec, double fluid_rest_volume, float default_voxel_size);

// Keeps the voxelisations made during a run, so that switching back to a
// target costs nothing. It is bounded (a long interactive session or a soak
// makes hundreds of targets, each region a new volume): past kMaxEntries
// shapes or kMaxBytes bytes, the least recently used shapes are dropped,
// never the one just returned nor `keep` (the shape the caller still uses).
// A reference from get() stays valid until a later get() that does not keep it.
//
// A voxelisation scales exactly with the volume: every length by
// (V'/V)^(1/3), the same voxels. So when the same shape is asked for at
// another volume (a target change regenerates from the fluid that forms the
// current shape, whose volume varies), the cached voxelisation is rescaled,
// not redone. Only a spec with an explicit voxel_size is voxelised anew,
// since rescaling would change its voxel size.
class TargetCache {
 public:
  static constexpr size_t kMaxEntries = 32;
  static constexpr size_t kMaxBytes = size_t(256) << 20;

  const TargetShape& get(const TargetSpec& spec, double fluid_rest_volume, float default_voxel_size,
                         const TargetShape* keep = nullptr);
  size_t size() const { return entries_.size(); }
  size_t bytes() const;
  // How many voxelisations were actually computed (rescaled copies excluded).
  size_t voxelisations() const { return voxelisations_; }

 private:
  struct Entry {
    std::string key;       // spec and volume
    std::string base_key;  // spec only: the same shape at any volume
    double volume = 0.0;
    std::unique_ptr<TargetShape> shape;  // references handed out stay valid as entries are added
    uint64_t last_use = 0;
  };
  const TargetShape& use(Entry& e, const TargetShape* keep);
  std::vector<Entry> entries_;
  size_t voxelisations_ = 0;
  uint64_t clock_ = 0;
};

// The most voxels one voxel grid may have, in all and along one axis
// (makeVoxelGrid enforces them; buildTarget estimates before voxelising).
constexpr double kMaxVoxels = 2.0e8;
constexpr double kMaxVoxelsPerAxis = 4096.0;

// Resolves a mesh path: as given if absolute; else relative to `scene_dir`
// (when not empty); else along FLOWFORM_MESH_PATH (colon-separated folders).
// Throws ff::Error listing every place tried, or saying that the path is a
// folder.
std::string resolveMeshPath(const std::string& name, const std::string& scene_dir);

}  // namespace ff
