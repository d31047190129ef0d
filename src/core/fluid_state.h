// fluid_state.h - the fluid particles, structure of arrays. After every grid
// build the arrays are sorted by grid cell; `id` is the stable identity of a
// particle across reorderings.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ff {

struct FluidState {
  std::vector<float> x, y, z;
  std::vector<float> vx, vy, vz;
  std::vector<uint32_t> id;

  size_t size() const { return x.size(); }
  void resize(size_t n) {
    for (auto* a : {&x, &y, &z, &vx, &vy, &vz}) a->resize(n);
    id.resize(n);
  }
  void push(float px, float py, float pz, float ux, float uy, float uz) {
    id.push_back(uint32_t(x.size()));
    x.push_back(px), y.push_back(py), z.push_back(pz);
    vx.push_back(ux), vy.push_back(uy), vz.push_back(uz);
  }
};

}  // namespace ff
