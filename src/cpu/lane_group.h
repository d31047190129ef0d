// lane_group.h - up to 8 consecutive grid-sorted particles as the lanes of
// one neighbour walk (the OpenMP backend's counterpart of ff_lanes.h).
#pragma once
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/fluid_state.h"
#include "grid/uniform_grid.h"
#include "parallel/simd8.h"

namespace ff {

// Unused lanes sit this far away: out of every neighbour's reach.
constexpr float kLaneFar = 1.0e18f;

// The neighbour ranges of one group, reused by each thread.
inline std::vector<uint32_t>& threadSpans() {
  static thread_local std::vector<uint32_t> spans;
  return spans;
}

// The particles b .. e-1 (at most 8) as lanes, their bounding box, and the
// grid ranges within `radius` of it.
struct Group {
  simd::f8 x, y, z;
  int n;
};
// The particles b .. e-1 (at most 8) as lanes.
inline Group lanesOf(const FluidState& s, uint32_t b, uint32_t e) {
  Group g;
  g.n = int(e - b);
  g.x = simd::loadN(&s.x[b], g.n, kLaneFar), g.y = simd::loadN(&s.y[b], g.n, kLaneFar);
  g.z = simd::loadN(&s.z[b], g.n, kLaneFar);
  return g;
}
inline void loadGroup(const FluidState& s, uint32_t b, uint32_t e, float radius, const UniformGrid& grid,
                      Group& g, std::vector<uint32_t>& spans) {
  g = lanesOf(s, b, e);
  const float lo[3] = {simd::hmin(g.x, g.n), simd::hmin(g.y, g.n), simd::hmin(g.z, g.n)};
  const float hi[3] = {simd::hmax(g.x, g.n), simd::hmax(g.y, g.n), simd::hmax(g.z, g.n)};
  grid.rangesNear(lo, hi, radius, spans);
}

// Runs body(gi, b, e) over the lane groups of `groups` (pairs [b, e), see
// CpuFluid::groups; gi: the group's index) in parallel, each group on one
// thread.
template <class Body>
void forEachGroupIndex(const std::vector<uint32_t>& groups, Body&& body) {
  const long n = long(groups.size() / 2);
#pragma omp parallel for schedule(dynamic, 16)
  for (long gi = 0; gi < n; ++gi) body(size_t(gi), groups[2 * size_t(gi)], groups[2 * size_t(gi) + 1]);
}

// The next group to take of each part of forEachGroupInParts, on its own
// cache line.
struct alignas(64) PartCursor {
  std::atomic<size_t> at{0};
};
// `parts` cursors at 0, kept by the calling thread from call to call (no
// allocation per walk once they suffice); so a body must not start
// another forEachGroupInParts.
inline PartCursor* partCursors(int parts) {
  static thread_local std::unique_ptr<PartCursor[]> cursors;
  static thread_local int room = 0;
  if (parts > room) cursors.reset(new PartCursor[size_t(parts)]), room = parts;
  for (int k = 0; k < parts; ++k) cursors[size_t(k)].at.store(0, std::memory_order_relaxed);
  return cursors.get();
}

// Runs body(gi, b, e) over the groups of each part k of `bounds` (groups
// bounds[k] .. bounds[k+1] - 1, in order), thread k first taking its own
// part a few groups at a time, then helping with the others' rest: a part's
// particles and neighbour lists stay in the cache of the core that walked
// them last, where forEachGroupIndex's chunks went to whichever thread was
// free, and a thread that the machine holds up has its part finished by
// the others (docs/PERFORMANCE.md, "Each thread its own part of the
// groups"). Returns whether every call returned true.
template <class Body>
bool forEachGroupInParts(const std::vector<size_t>& bounds, const std::vector<uint32_t>& groups,
                         Body&& body) {
  const int parts = int(bounds.size()) - 1;
  if (parts < 1) return true;
  constexpr size_t kTake = 4;  // groups per take
  PartCursor* const next = partCursors(parts);
  int bad = 0;
#pragma omp parallel num_threads(parts) reduction(| : bad)
  {
    const int t = omp_get_thread_num();
    for (int r = 0; r < parts; ++r) {
      const size_t k = size_t((t + r) % parts), b = bounds[k], e = bounds[k + 1];
      for (size_t at = next[k].at.fetch_add(kTake, std::memory_order_relaxed); b + at < e;
           at = next[k].at.fetch_add(kTake, std::memory_order_relaxed))
        for (size_t gi = b + at; gi < std::min(e, b + at + kTake); ++gi)
          bad |= body(gi, groups[2 * gi], groups[2 * gi + 1]) ? 0 : 1;
    }
  }
  return !bad;
}

// As forEachGroupIndex, with body(b, e).
template <class Body>
void forEachGroup(const std::vector<uint32_t>& groups, Body&& body) {
  forEachGroupIndex(groups, [&](size_t, uint32_t b, uint32_t e) { body(b, e); });
}

// As forEachGroupIndex, with body(gi, b, e) returning whether every value it
// wrote is finite: true if every call did.
template <class Body>
bool forEachGroupIndexFinite(const std::vector<uint32_t>& groups, Body&& body) {
  const long n = long(groups.size() / 2);
  int bad = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(| : bad)
  for (long gi = 0; gi < n; ++gi)
    bad |= body(size_t(gi), groups[2 * size_t(gi)], groups[2 * size_t(gi) + 1]) ? 0 : 1;
  return !bad;
}

// As forEachGroupIndexFinite, with body(b, e).
template <class Body>
bool forEachGroupFinite(const std::vector<uint32_t>& groups, Body&& body) {
  return forEachGroupIndexFinite(groups, [&](size_t, uint32_t b, uint32_t e) { return body(b, e); });
}

}  // namespace ff
