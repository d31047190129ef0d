// ply_writer.cpp - binary little-endian PLY output, written atomically.
#include "io/ply_writer.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <vector>

#include "core/error.h"

namespace ff {
namespace {

void putU32(std::vector<char>& out, uint32_t v) {
  // Byte by byte, so the file is little-endian whatever the host's order.
  for (int b = 0; b < 4; ++b) out.push_back(char((v >> (8 * b)) & 0xffu));
}

void putF32(std::vector<char>& out, float v) {
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  putU32(out, bits);
}

std::string header(size_t n, const char* comment, std::initializer_list<const char*> properties) {
  std::string h = "ply\nformat binary_little_endian 1.0\ncomment ";
  h += comment;
  h += "\nelement vertex " + std::to_string(n) + "\n";
  for (const char* p : properties) h += std::string("property ") + p + "\n";
  h += "end_header\n";
  return h;
}

[[noreturn]] void fail(const std::string& path, const char* what, int err) {
  throw Error(path + ": " + what + " (" + std::strerror(err) + ")");
}

// Writes header + body to path.tmp, then renames it to path.
void writeAtomically(const std::string& path, const std::string& head, const std::vector<char>& body) {
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) fail(path, "cannot create PLY file", errno);
  bool ok = std::fwrite(head.data(), 1, head.size(), f) == head.size() &&
            std::fwrite(body.data(), 1, body.size(), f) == body.size();
  int err = ok ? 0 : errno;
  if (std::fclose(f) != 0 && ok) {
    ok = false;
    err = errno;
  }
  if (!ok) {
    std::remove(tmp.c_str());
    fail(path, "cannot write PLY file", err);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    err = errno;
    std::remove(tmp.c_str());
    fail(path, "cannot rename the PLY file into place", err);
  }
}

}  // namespace

void writeFluidPly(const std::string& path, size_t n, const float* x, const float* y, const float* z,
                   const float* vx, const float* vy, const float* vz, const uint32_t* id) {
  const std::string head =
      header(n, "flowform fluid particles",
             {"float x", "float y", "float z", "float vx", "float vy", "float vz", "uint id"});
  std::vector<char> body;
  body.reserve(n * 28);
  for (size_t i = 0; i < n; ++i) {
    for (const float* a : {x, y, z, vx, vy, vz}) putF32(body, a[i]);
    putU32(body, id ? id[i] : uint32_t(i));
  }
  writeAtomically(path, head, body);
}

void writeControlPly(const std::string& path, size_t n, const float* x, const float* y, const float* z,
                     const float* x0, const float* y0, const float* z0, const float* s) {
  const std::string head =
      header(n, "flowform control particles",
             {"float x", "float y", "float z", "float x0", "float y0", "float z0", "float s"});
  std::vector<char> body;
  body.reserve(n * 28);
  for (size_t i = 0; i < n; ++i)
    for (const float* a : {x, y, z, x0, y0, z0, s}) putF32(body, a[i]);
  writeAtomically(path, head, body);
}

}  // namespace ff
