// neighbour_cache.h - for each lane group of the fluid (CpuFluid::groups), the
// neighbour candidates that at least one of its lanes reaches, in the order the
// density phase's grid walk visits them, with one value per lane and pair (the
// DFSPH solver keeps the kernel gradient's factor g; 0 where that lane does
// not reach the candidate). Built once per substep while the density phase
// searches the grid, so the solver's Jacobi passes and the viscosity force
// walk a short list instead of searching 27 cells with a square root and a
// kernel per candidate. "Reaches" is r^2 < kReachSlack H^2 for some lane
// (H: radius()): a superset of every kernel's support r < H however r, q =
// r / H and r^2 round, so a candidate left out adds exactly 0 to every lane's
// sum. Each lane adds the same terms in the same order as the grid walk (a
// kept candidate a lane does not reach adds only zeros there), so the sums
// are unchanged bit for bit. Each thread appends to its own buffer.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "parallel/simd8.h"

namespace ff {

class NeighbourCache {
 public:
  // A candidate is kept where some lane has r^2 < kReachSlack H^2.
  static constexpr float kReachSlack = 1.0001f;
  // A group's own work in a walk (loading its lanes, the per-particle
  // epilogue), in candidates, for split(): an estimate, not measured (a
  // peer dam break group has 100-150 candidates, so it moves a split by a
  // few groups; the parts' helping absorbs that).
  static constexpr uint64_t kGroupShare = 16;

  // Forgets every list and sizes the index for `groups` groups of radius H
  // (outside a parallel region; the buffers keep their capacity). Returns
  // the most threads that may fill it: the filling region's num_threads.
  int reset(size_t groups, float radius);

  // Group gi's list as it is written, from inside the filling region: room
  // for `most` candidates; put() writes one at the current end and keeps it
  // if `keep` (branch-free); then value() sets the q-th kept one's 8 lane
  // values (valueAt() reads them back); close() stores the list.
  class Writer {
   public:
    void put(uint32_t j, bool keep) {
      j_[n_] = j;
      n_ += keep ? 1 : 0;
    }
    size_t size() const { return n_; }
    uint32_t index(size_t q) const { return j_[q]; }
    void value(size_t q, const simd::f8& g) { std::memcpy(g_ + 8 * q, &g, sizeof g); }
    simd::f8 valueAt(size_t q) const {
      simd::f8 g;
      std::memcpy(&g, g_ + 8 * q, sizeof g);
      return g;
    }

   private:
    friend class NeighbourCache;
    uint32_t* j_ = nullptr;
    float* g_ = nullptr;
    size_t n_ = 0;
  };
  Writer open(size_t most);
  void close(size_t gi, const Writer& w);

  size_t groups() const { return count_.size(); }
  float radius() const { return radius_; }
  // r^2 below which a lane reaches a candidate (kReachSlack H^2).
  float reach2() const { return kReachSlack * radius_ * radius_; }
  uint32_t count(size_t gi) const { return count_[gi]; }
  const uint32_t* neighbours(size_t gi) const { return buffers_[owner_[gi]].j.get() + offset_[gi]; }
  // 8 lane values per candidate (load them with memcpy: no alignment).
  const float* values(size_t gi) const { return buffers_[owner_[gi]].g.get() + 8 * size_t(offset_[gi]); }
  // After filling: the groups split into `count` consecutive parts of about
  // equal work (their candidates plus kGroupShare each), for
  // forEachGroupInParts; part k is groups parts()[k] .. parts()[k+1] - 1.
  void split(int count);
  const std::vector<size_t>& parts() const { return parts_; }
  size_t memoryBytes() const;

 private:
  struct Buffer {  // uninitialised storage: each substep overwrites it
    std::unique_ptr<uint32_t[]> j;
    std::unique_ptr<float[]> g;
    size_t size = 0, capacity = 0;
    void reserve(size_t n);
  };
  std::vector<Buffer> buffers_;                   // one per thread
  std::vector<uint32_t> offset_, count_, owner_;  // per group
  std::vector<size_t> parts_;                     // split()'s bounds
  float radius_ = 0.0f;
};

}  // namespace ff
