// surface_mesh_writer.cpp - OBJ and PLY triangle meshes.
#include "io/surface_mesh_writer.h"

#include <charconv>
#include <cstdio>

#include "io/atomic_file.h"
#include "io/byte_order.h"

namespace ff {
namespace {

std::string timeText(double time) {
  char t[64];
  std::snprintf(t, sizeof t, "%.9g", time);
  return t;
}

template <class T>
void append(std::string& out, T v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

}  // namespace

void writeSurfaceObj(const std::string& path, const SurfaceMesh& m, double time) {
  std::string text = "# flowform liquid surface\n# time " + timeText(time) + "\n";
  text.reserve(text.size() + m.vertices.size() * 36 + m.triangles.size() * 24);
  for (const auto& v : m.vertices) {
    text += 'v';
    for (float c : v) {
      text += ' ';
      append(text, c);  // shortest text that reads back to the same float
    }
    text += '\n';
  }
  for (const auto& t : m.triangles) {
    text += 'f';
    for (uint32_t i : t) {
      text += ' ';
      append(text, i + 1);
    }
    text += '\n';
  }
  writeFileAtomically(path, "OBJ file", {text});
}

void writeSurfacePly(const std::string& path, const SurfaceMesh& m, double time) {
  const std::string head =
      "ply\nformat binary_little_endian 1.0\ncomment flowform liquid surface\ncomment time " +
      timeText(time) + "\nelement vertex " + std::to_string(m.vertices.size()) +
      "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
      std::to_string(m.triangles.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  std::string body;
  body.reserve(m.vertices.size() * 12 + m.triangles.size() * 13);
  for (const auto& v : m.vertices)
    for (float c : v) putLE32(body, bitsOf(c));
  for (const auto& t : m.triangles) {
    body += char(3);
    for (uint32_t i : t) putLE32(body, i);
  }
  writeFileAtomically(path, "PLY file", {head, body});
}

}  // namespace ff
