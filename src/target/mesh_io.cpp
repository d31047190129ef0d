// mesh_io.cpp - loadMesh (assimp) and meshVolume.
#include "target/mesh_io.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Geometry>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <unordered_map>

#include "core/error.h"
#include "core/warning.h"
#include "target/mesh_file_checks.h"

namespace ff {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(path + ": " + what);
}

// Checks the freshly read meshes and recomputes their primitive-type flags
// from the faces: a garbled file can leave flags that do not match the faces,
// and assimp's (Debian: assertion-enabled) Triangulate step aborts the whole
// program on such a mismatch. Returns a problem description, or "".
std::string checkRawScene(const aiScene* scene) {
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    aiMesh* mesh = scene->mMeshes[m];
    if (!mesh) return "a mesh is missing";
    unsigned types = 0;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices == 0 || !face.mIndices)
        return "face " + std::to_string(f + 1) + " has no vertices";
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh->mNumVertices) {
          return "face " + std::to_string(f + 1) + " refers to vertex " +
                 std::to_string(face.mIndices[k] + 1) + " but there are only " +
                 std::to_string(mesh->mNumVertices);
        }
      }
      types |= face.mNumIndices == 1   ? aiPrimitiveType_POINT
               : face.mNumIndices == 2 ? aiPrimitiveType_LINE
               : face.mNumIndices == 3 ? aiPrimitiveType_TRIANGLE
                                       : aiPrimitiveType_POLYGON;
    }
    mesh->mPrimitiveTypes = types;
  }
  return "";
}

void collectNode(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent, std::vector<bool>& used,
                 TriangleMesh& out, const std::string& path) {
  const aiMatrix4x4 transform = parent * node->mTransformation;
  for (unsigned m = 0; m < node->mNumMeshes; ++m) {
    const unsigned mesh_index = node->mMeshes[m];
    if (mesh_index >= scene->mNumMeshes) fail(path, "garbled file: a node refers to a missing mesh");
    used[mesh_index] = true;
    const aiMesh* mesh = scene->mMeshes[mesh_index];
    const int base = int(out.vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D p = transform * mesh->mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        fail(path, "vertex " + std::to_string(v + 1) + " has a NaN or infinite coordinate");
      }
      out.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines enclose nothing
      std::array<int, 3> tri{};
      for (int k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= mesh->mNumVertices) {
          fail(path, "face " + std::to_string(f + 1) + " refers to vertex " +
                         std::to_string(face.mIndices[k] + 1) + " but there are only " +
                         std::to_string(mesh->mNumVertices));
        }
        tri[k] = base + int(face.mIndices[k]);
      }
      out.triangles.push_back(tri);
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c)
    collectNode(scene, node->mChildren[c], transform, used, out, path);
}

// Keeps only the vertices that triangles use, so stray points do not widen the bounds.
void dropUnusedVertices(TriangleMesh& mesh) {
  std::vector<int> remap(mesh.vertices.size(), -1);
  std::vector<Vec3> kept;
  for (auto& tri : mesh.triangles) {
    for (int& index : tri) {
      if (remap[size_t(index)] < 0) {
        remap[size_t(index)] = int(kept.size());
        kept.push_back(mesh.vertices[size_t(index)]);
      }
      index = remap[size_t(index)];
    }
  }
  mesh.vertices.swap(kept);
}

void checkNotDegenerate(const TriangleMesh& mesh, const std::string& path) {
  Vec3 lo, hi;
  meshBounds(mesh, lo, hi);
  const Eigen::Vector3d extent = (hi - lo).cast<double>();
  const double largest = extent.maxCoeff();
  static const char* kAxis[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    if (!(extent[a] > 1e-6 * largest))
      fail(path, std::string("degenerate mesh: it is flat along ") + kAxis[a]);
  }
  const double volume = meshVolume(mesh);
  if (!(std::abs(volume) > 1e-6 * extent.prod())) {
    std::ostringstream msg;
    msg << "degenerate mesh: it encloses (almost) no volume (" << volume
        << " by the divergence theorem); is the surface open or inconsistently wound?";
    fail(path, msg.str());
  }
}

}  // namespace

TriangleMesh loadMesh(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) fail(path, "file not found");
  if (fs::is_directory(status)) fail(path, "is a folder, not a mesh file");
  const uintmax_t size = fs::file_size(path, ec);
  if (ec) fail(path, "cannot read the file: " + ec.message());
  if (size == 0) fail(path, "the file is empty");
  Assimp::Importer importer;
  // The name decides the reader: assimp would otherwise guess the format from
  // the first bytes, and a garbled file could then reach a reader that no
  // check of mesh_file_checks.cpp has vetted.
  const std::string extension = fs::path(path).extension().string();
  if (extension.empty() || !importer.IsExtensionSupported(extension.c_str())) {
    fail(path,
         "unknown mesh format '" + extension +
             "': name the file for its format (.obj, .stl, .ply, .off, .gltf, .glb, .fbx, .dae or another "
             "extension assimp reads)");
  }
  checkMeshFileStructure(path, size);

  const aiScene* scene = nullptr;
  std::string problem;
  try {
    // Two stages: read and validate (out-of-range indices are rejected before
    // anything else touches them), repair what the post-processing steps
    // trust, then triangulate and join identical vertices.
    scene = importer.ReadFile(path, aiProcess_ValidateDataStructure);
    if (scene) {
      problem = checkRawScene(scene);
      if (problem.empty())
        scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
    }
  } catch (const std::exception& e) {
    fail(path, std::string("cannot read the mesh (assimp: ") + e.what() + ")");
  }
  if (!problem.empty()) fail(path, "garbled file: " + problem);
  if (!scene) fail(path, std::string("cannot read the mesh (assimp: ") + importer.GetErrorString() + ")");
  if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)
    fail(path, "cannot read the mesh (assimp: incomplete scene)");

  TriangleMesh mesh;
  std::vector<bool> used(scene->mNumMeshes, false);
  if (scene->mRootNode) collectNode(scene, scene->mRootNode, aiMatrix4x4(), used, mesh, path);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {  // meshes no node places: take them as they are
    if (used[m]) continue;
    aiNode lone;
    lone.mNumMeshes = 1;
    lone.mMeshes = new unsigned[1]{m};
    collectNode(scene, &lone, aiMatrix4x4(), used, mesh, path);
  }
  if (mesh.triangles.empty()) fail(path, "no triangles in the file");
  dropUnusedVertices(mesh);
  checkNotDegenerate(mesh, path);
  if (const size_t open = openEdgeCount(mesh))
    warn(path + ": the mesh is not watertight (" + std::to_string(open) +
         " edges belong to one triangle only); using it anyway: voxels are inside where 2 of 3 axis rays "
         "say so, which tolerates small holes");
  return mesh;
}

size_t openEdgeCount(const TriangleMesh& mesh) {
  std::unordered_map<uint64_t, int> uses;
  uses.reserve(mesh.triangles.size() * 3);
  for (const auto& tri : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const uint64_t a = uint32_t(tri[k]), b = uint32_t(tri[(k + 1) % 3]);
      ++uses[a < b ? (a << 32 | b) : (b << 32 | a)];
    }
  size_t open = 0;
  for (const auto& e : uses) open += e.second == 1;
  return open;
}

double meshVolume(const TriangleMesh& mesh) {
  double six_volume = 0.0;
  for (const auto& tri : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[size_t(tri[0])].cast<double>();
    const Eigen::Vector3d b = mesh.vertices[size_t(tri[1])].cast<double>();
    const Eigen::Vector3d c = mesh.vertices[size_t(tri[2])].cast<double>();
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

void meshBounds(const TriangleMesh& mesh, Vec3& lo, Vec3& hi) {
  if (mesh.vertices.empty()) {
    lo = hi = Vec3::Zero();
    return;
  }
  lo = hi = mesh.vertices.front();
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
}

}  // namespace ff
