// surface_mesh.h - a triangle mesh of the liquid's surface: shared vertices
// (y-up, metres) and triangles wound outwards, with its enclosed volume.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

namespace ff {

struct SurfaceMesh {
  std::vector<std::array<float, 3>> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;  // indices into vertices

  // Signed enclosed volume (divergence theorem, in double): positive for a
  // closed mesh wound outwards.
  double volume() const {
    double v = 0.0;
    for (const auto& t : triangles) {
      const auto &a = vertices[t[0]], &b = vertices[t[1]], &c = vertices[t[2]];
      v += double(a[0]) * (double(b[1]) * c[2] - double(b[2]) * c[1]) -
           double(a[1]) * (double(b[0]) * c[2] - double(b[2]) * c[0]) +
           double(a[2]) * (double(b[0]) * c[1] - double(b[1]) * c[0]);
    }
    return v / 6.0;
  }
};

}  // namespace ff
