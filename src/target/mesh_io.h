// mesh_io.h - triangle meshes read from OBJ, PLY, STL or OFF files (through
// assimp), and their enclosed volume.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace ff {

struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;  // indices into `vertices`
};

// Reads every mesh of the file (node transforms applied), triangulated and
// merged into one. Throws ff::Error "PATH: problem" for a missing, empty,
// unreadable or garbled file, a file without triangles, NaN/Inf coordinates,
// or a degenerate mesh (flat: zero extent along an axis, or zero volume).
TriangleMesh loadMesh(const std::string& path);

// Signed volume by the divergence theorem: sum of det(v0, v1, v2) / 6, in
// double. Positive for a closed, outward-wound mesh.
double meshVolume(const TriangleMesh& mesh);

// Axis-aligned bounds of the vertices used by triangles (zero if none).
// Edges that only one triangle uses (0 for a watertight mesh).
size_t openEdgeCount(const TriangleMesh& mesh);

void meshBounds(const TriangleMesh& mesh, Vec3& lo, Vec3& hi);

}  // namespace ff
