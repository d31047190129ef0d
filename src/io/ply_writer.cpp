// ply_writer.cpp - binary little-endian PLY output.
#include "io/ply_writer.h"

#include <cstdio>

#include "io/atomic_file.h"
#include "io/byte_order.h"

namespace ff {

void writePly(const std::string& path, const PointCloud& c) {
  char time[64];
  std::snprintf(time, sizeof time, "%.9g", c.time);
  std::string head = "ply\nformat binary_little_endian 1.0\ncomment " + c.what + "\ncomment time " + time +
                     "\nelement vertex " + std::to_string(c.n) +
                     "\nproperty float x\nproperty float y\nproperty float z\n";
  static const char* const suffix[3] = {"_x", "_y", "_z"};
  size_t per_point = 3;
  for (const PointAttribute& a : c.attributes) {
    const char* type = a.type == PointAttribute::Type::Int32 ? "int" : "float";
    for (int k = 0; k < a.components; ++k)
      head += std::string("property ") + type + " " + a.name + (a.components > 1 ? suffix[k] : "") + "\n";
    per_point += size_t(a.components);
  }
  head += "end_header\n";
  std::string body;
  body.reserve(c.n * per_point * 4);
  for (size_t i = 0; i < c.n; ++i) {
    for (const float* p : {c.x, c.y, c.z}) putLE32(body, bitsOf(p[i]));
    for (const PointAttribute& a : c.attributes)
      for (int k = 0; k < a.components; ++k) putLE32(body, a.bits(k, i));
  }
  writeFileAtomically(path, "PLY file", {head, body});
}

}  // namespace ff
