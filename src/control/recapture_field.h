// recapture_field.h - the recapture's targets (kernels/common/ff_recapture_field.h):
// a coarse field over the control particles' grid that names, per field cell,
// an unfilled control particle near it. The geometry and the flooding steps
// are shared by both backends; RecaptureField builds it for the OpenMP one.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "grid/uniform_grid.h"

namespace ff {

// The field over a grid of n[3] cells of size `cell` at origin o.
struct RecaptureFieldGeom {
  int m[3] = {1, 1, 1};    // field cells per axis
  float o[3] = {0, 0, 0};  // origin (the grid's)
  float fcell = 1.0f, inv_fcell = 1.0f;
  size_t cells() const { return size_t(m[0]) * size_t(m[1]) * size_t(m[2]); }
};
RecaptureFieldGeom recaptureFieldGeom(const int n[3], const float o[3], float cell);
// The jump-flooding steps in order: N/2, N/4, .., 1, then 1 again (held in
// place: building the field every step allocates nothing).
struct RecaptureFloodSteps {
  int step[33] = {};  // a field of at most 2^31 cells per axis: 31 halvings and the last 1
  int count = 0;
  const int* begin() const { return step; }
  const int* end() const { return step + count; }
};
RecaptureFloodSteps recaptureFloodSteps(const RecaptureFieldGeom& g);

class RecaptureField {
 public:
  // Seeds the field from the control particles (sx .. ss: in `grid`'s order)
  // and floods it. Every cell then names an unfilled control particle (a
  // sorted position) if there is one; with `any` (none is unfilled), any
  // control particle.
  void build(const UniformGrid& grid, const float* sx, const float* sy, const float* sz, const float* ss,
             bool any);
  const RecaptureFieldGeom& geom() const { return geom_; }
  const std::vector<uint32_t>& seeds() const { return seeds_; }
  size_t memoryBytes() const { return (seeds_.capacity() + scratch_.capacity()) * sizeof(uint32_t); }

 private:
  RecaptureFieldGeom geom_;
  std::vector<uint32_t> seeds_, scratch_;
};

}  // namespace ff
