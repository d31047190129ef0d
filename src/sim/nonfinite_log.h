// nonfinite_log.h - which phase first wrote a NaN or Inf, for
// Backend::firstNonFinite. A phase run gets a tag (its phase and the substep,
// counted by the grid phases since the last take()); the first failing tag is
// kept: by the OpenCL kernels in a device word (atomic_cmpxchg from 0), by the
// OpenMP backend here.
#pragma once
#include <cstdint>

#include "sim/backend.h"

namespace ff {

class NonFiniteLog {
 public:
  // Registers a phase run and returns its tag (never 0).
  uint32_t begin(Phase p) {
    if (p == Phase::Grid && grids_ < kMaxSubstep) ++grids_;
    current_ = tag(p, grids_ > 0 ? grids_ - 1 : 0);
    return current_;
  }
  // The phase begun last wrote a non-finite value (the first one is kept).
  void fail() {
    if (!first_) first_ = current_;
  }
  // The phase and substep of `device_tag` if it is not 0, else of the first
  // fail(); Phase::Count when neither. Starts a new record.
  Phase take(uint32_t device_tag, int* substep) {
    const uint32_t t = device_tag ? device_tag : first_;
    first_ = 0, grids_ = 0;
    if (substep) *substep = t ? int(t >> 4) : 0;
    return t ? Phase(int(t & 15u) - 1) : Phase::Count;
  }

 private:
  static constexpr uint32_t kMaxSubstep = (1u << 27) - 1;
  static uint32_t tag(Phase p, uint32_t substep) { return (uint32_t(p) + 1u) | (substep << 4); }
  uint32_t grids_ = 0, current_ = 0, first_ = 0;
};

}  // namespace ff
