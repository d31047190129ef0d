// byte_order.h - appending 32-bit values to a byte buffer in a fixed byte
// order, whatever the host's: little-endian (PLY, VTK) or big-endian (BGEO).
#pragma once
#include <cstdint>
#include <cstring>
#include <string>

namespace ff {

inline uint32_t bitsOf(float v) {
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return bits;
}

inline void putLE32(std::string& out, uint32_t v) {
  const char b[4] = {char(v & 0xffu), char((v >> 8) & 0xffu), char((v >> 16) & 0xffu), char(v >> 24)};
  out.append(b, 4);
}

inline void putBE32(std::string& out, uint32_t v) {
  const char b[4] = {char(v >> 24), char((v >> 16) & 0xffu), char((v >> 8) & 0xffu), char(v & 0xffu)};
  out.append(b, 4);
}

inline void putLE64(std::string& out, uint64_t v) {
  putLE32(out, uint32_t(v & 0xffffffffu));
  putLE32(out, uint32_t(v >> 32));
}

inline void putBE16(std::string& out, uint16_t v) {
  const char b[2] = {char(v >> 8), char(v & 0xffu)};
  out.append(b, 2);
}

}  // namespace ff
