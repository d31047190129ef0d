// bgeo_writer.cpp - classic binary Houdini geometry (points only).
#include "io/bgeo_writer.h"

#include <climits>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/byte_order.h"

namespace ff {
namespace {

enum HoudiniType : uint32_t { kFloat = 0, kInt = 1, kVector = 5 };

void putDefinition(std::string& out, const std::string& name, int size, HoudiniType type) {
  putBE16(out, uint16_t(name.size()));
  out += name;
  putBE16(out, uint16_t(size));
  putBE32(out, type);
  for (int k = 0; k < size; ++k) putBE32(out, 0);  // default value 0
}

}  // namespace

void writeBgeo(const std::string& path, const PointCloud& c) {
  if (c.n > size_t(INT_MAX)) throw Error(path + ": too many points for a BGEO file");
  std::string head = "BgeoV";
  putBE32(head, 5);
  for (uint32_t v : {uint32_t(c.n), 0u, 0u, 0u, uint32_t(c.attributes.size()), 0u, 0u, 1u}) putBE32(head, v);
  size_t per_point = 4;
  for (const PointAttribute& a : c.attributes) {
    const HoudiniType type =
        a.type == PointAttribute::Type::Int32 ? kInt : (a.components == 3 ? kVector : kFloat);
    putDefinition(head, a.name, a.components, type);
    per_point += size_t(a.components);
  }
  std::string body;
  body.reserve(c.n * per_point * 4 + 64);
  const uint32_t one = bitsOf(1.0f);
  for (size_t i = 0; i < c.n; ++i) {
    for (const float* p : {c.x, c.y, c.z}) putBE32(body, bitsOf(p[i]));
    putBE32(body, one);
    for (const PointAttribute& a : c.attributes)
      for (int k = 0; k < a.components; ++k) putBE32(body, a.bits(k, i));
  }
  putDefinition(body, "time", 1, kFloat);
  putBE32(body, bitsOf(float(c.time)));
  body += '\0';
  body += '\xff';
  writeFileAtomically(path, "BGEO file", {head, body});
}

}  // namespace ff
