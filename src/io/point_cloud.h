// point_cloud.h - a borrowed view of particles for the file writers:
// positions, named per-point attributes (structure of arrays) and the
// simulated time the snapshot belongs to.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "io/byte_order.h"

namespace ff {

struct PointAttribute {
  enum class Type { Float32, Int32 };
  std::string name;
  Type type = Type::Float32;
  int components = 1;                                 // 1 or 3
  const void* data[3] = {nullptr, nullptr, nullptr};  // one array of n values per component

  static PointAttribute scalar(std::string name, const float* v) {
    return {std::move(name), Type::Float32, 1, {v}};
  }
  static PointAttribute integer(std::string name, const int32_t* v) {
    return {std::move(name), Type::Int32, 1, {v}};
  }
  static PointAttribute vector(std::string name, const float* a, const float* b, const float* c) {
    return {std::move(name), Type::Float32, 3, {a, b, c}};
  }
  // The raw 32 bits of component c of point i (floats by their bit pattern).
  uint32_t bits(int c, size_t i) const {
    return type == Type::Int32 ? uint32_t(static_cast<const int32_t*>(data[c])[i])
                               : bitsOf(static_cast<const float*>(data[c])[i]);
  }
};

struct PointCloud {
  size_t n = 0;
  const float* x = nullptr;
  const float* y = nullptr;
  const float* z = nullptr;
  std::vector<PointAttribute> attributes;
  double time = 0.0;  // simulated seconds
  std::string what;   // e.g. "flowform fluid particles", for file comments
};

}  // namespace ff
