// surface_mesh_writer.h - the liquid's surface mesh as Wavefront OBJ (text:
// `v x y z` and 1-based `f a b c`) or as binary little-endian PLY (float
// x y z vertices, `list uchar int vertex_indices` faces), with the simulated
// time in a comment. Written atomically; errors throw ff::Error naming the path.
#pragma once
#include <string>

#include "surface/surface_mesh.h"

namespace ff {

void writeSurfaceObj(const std::string& path, const SurfaceMesh& mesh, double time);
void writeSurfacePly(const std::string& path, const SurfaceMesh& mesh, double time);

}  // namespace ff
