// The parts the solver's walks split the lane groups into
// (NeighbourCache::split) and the walk over them (forEachGroupInParts):
// consecutive parts that cover every group once, each within one group's
// work of an equal share, however unevenly the work lies.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <numeric>
#include <thread>
#include <vector>

#include "cpu/lane_group.h"
#include "cpu/neighbour_cache.h"

namespace {

using ff::NeighbourCache;

// A cache whose group g keeps counts[g] candidates.
void fill(NeighbourCache& c, const std::vector<uint32_t>& counts) {
  c.reset(counts.size(), 1.0f);
  for (size_t g = 0; g < counts.size(); ++g) {
    NeighbourCache::Writer w = c.open(counts[g]);
    for (uint32_t q = 0; q < counts[g]; ++q) w.put(q, true);
    c.close(g, w);
  }
}

uint64_t work(uint32_t count) {
  return count + NeighbourCache::kGroupShare;
}

// Checks the parts of `counts` split `k` ways: they run from 0 to the last
// group without going back, and each part's work differs from the total's
// k-th by at most the largest single group's (a part ends at the first group
// that takes it to its share).
void expectBalanced(const std::vector<uint32_t>& counts, int k) {
  NeighbourCache c;
  fill(c, counts);
  c.split(k);
  const std::vector<size_t>& b = c.parts();
  ASSERT_EQ(b.size(), size_t(k) + 1);
  EXPECT_EQ(b.front(), 0u);
  EXPECT_EQ(b.back(), counts.size());
  uint64_t total = 0, largest = 0;
  for (uint32_t n : counts) total += work(n), largest = std::max(largest, work(n));
  const double share = double(total) / k;
  for (int p = 0; p < k; ++p) {
    ASSERT_LE(b[size_t(p)], b[size_t(p) + 1]) << "part " << p;
    uint64_t w = 0;
    for (size_t g = b[size_t(p)]; g < b[size_t(p) + 1]; ++g) w += work(counts[g]);
    EXPECT_LE(std::abs(double(w) - share), double(largest)) << "part " << p << " of " << k;
  }
}

TEST(GroupParts, EvenWorkSplitsEvenly) {
  expectBalanced(std::vector<uint32_t>(1000, 100), 2);
  expectBalanced(std::vector<uint32_t>(1000, 100), 3);
  expectBalanced(std::vector<uint32_t>(7, 100), 16);  // more parts than groups: some are empty
}

// The first half of the groups with 4 times the candidates of the second
// (a bulk beside a thin layer): split by group count, the first of two
// threads would take 80 % of the work; these parts take 50 % each.
TEST(GroupParts, UnevenWorkSplitsByWork) {
  std::vector<uint32_t> counts(1000, 25);
  std::fill(counts.begin(), counts.begin() + 500, 100);
  expectBalanced(counts, 2);
  NeighbourCache c;
  fill(c, counts);
  c.split(2);
  // Half of 500 x 116 + 500 x 41 is 39250, which 339 groups of 116 reach.
  EXPECT_EQ(c.parts()[1], 339u);
  std::vector<uint32_t> ramp(2000);
  std::iota(ramp.begin(), ramp.end(), 0u);
  expectBalanced(ramp, 2);
  expectBalanced(ramp, 5);
}

TEST(GroupParts, NoGroups) {
  expectBalanced({}, 2);
}

// Every group is walked once, whatever the parts and the threads.
TEST(GroupParts, TheWalkVisitsEachGroupOnce) {
  std::vector<uint32_t> groups;
  for (uint32_t g = 0; g < 300; ++g) groups.push_back(8 * g), groups.push_back(8 * g + 8);
  for (const std::vector<size_t>& bounds :
       std::vector<std::vector<size_t>>{{0, 300}, {0, 150, 300}, {0, 10, 10, 290, 300}, {0, 100, 200, 300}}) {
    std::vector<std::atomic<int>> seen(300);
    const bool all = ff::forEachGroupInParts(bounds, groups, [&](size_t gi, uint32_t b, uint32_t e) {
      seen[gi].fetch_add(1);
      return b == 8 * gi && e == b + 8;
    });
    EXPECT_TRUE(all);
    for (size_t g = 0; g < seen.size(); ++g) EXPECT_EQ(seen[g].load(), 1) << "group " << g;
  }
  // A false from any call is reported.
  const std::vector<size_t> two = {0, 150, 300};
  EXPECT_FALSE(ff::forEachGroupInParts(two, groups, [](size_t gi, uint32_t, uint32_t) { return gi != 200; }));
}

// A thread that is held up has its part finished by the others: thread 0
// waits on its first group until some other thread has walked a group of
// part 0 (at most 20 s; without the help it would wait them out and fail).
TEST(GroupParts, AHeldUpThreadsPartIsFinishedByTheOthers) {
  std::vector<uint32_t> groups;
  for (uint32_t g = 0; g < 400; ++g) groups.push_back(8 * g), groups.push_back(8 * g + 8);
  const std::vector<size_t> bounds = {0, 200, 400};
  std::atomic<int> helped{0}, threads{0};
  std::vector<std::atomic<int>> seen(400);
  ff::forEachGroupInParts(bounds, groups, [&](size_t gi, uint32_t, uint32_t) {
    const int t = omp_get_thread_num();
    if (gi == 0) threads = omp_get_num_threads();
    if (gi < 200 && t != 0) helped = 1;
    if (gi == 0 && t == 0 && omp_get_num_threads() > 1) {
      const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      while (!helped && std::chrono::steady_clock::now() < until) std::this_thread::yield();
    }
    seen[gi].fetch_add(1);
    return true;
  });
  if (threads < 2) GTEST_SKIP() << "one thread: nobody to help";
  EXPECT_EQ(helped.load(), 1);
  for (size_t g = 0; g < seen.size(); ++g) EXPECT_EQ(seen[g].load(), 1) << "group " << g;
}

}  // namespace
