// The uniform grid finds exactly the neighbours a brute-force search finds.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "grid/uniform_grid.h"

namespace {

void checkAgainstBruteForce(size_t n, float extent, float radius, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-extent, extent);
  std::vector<float> x(n), y(n), z(n);
  for (size_t i = 0; i < n; ++i) x[i] = u(rng), y[i] = u(rng), z[i] = u(rng) * 0.3f;
  ff::UniformGrid g;
  g.build(n, x.data(), y.data(), z.data(), radius);
  const auto& order = g.order();
  // order is a permutation
  std::vector<uint32_t> sorted(order.begin(), order.end());
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(sorted[i], i);
  const float r2 = radius * radius;
  for (size_t i = 0; i < n; ++i) {
    std::vector<uint32_t> found, expect;
    g.forEachRange(x[i], y[i], z[i], [&](uint32_t b, uint32_t e) {
      for (uint32_t k = b; k < e; ++k) {
        uint32_t j = order[k];
        float dx = x[i] - x[j], dy = y[i] - y[j], dz = z[i] - z[j];
        if (dx * dx + dy * dy + dz * dz < r2) found.push_back(j);
      }
    });
    for (size_t j = 0; j < n; ++j) {
      float dx = x[i] - x[j], dy = y[i] - y[j], dz = z[i] - z[j];
      if (dx * dx + dy * dy + dz * dz < r2) expect.push_back(uint32_t(j));
    }
    std::sort(found.begin(), found.end());
    ASSERT_EQ(found, expect) << "point " << i;
  }
}

TEST(NeighborGrid, EqualsBruteForceOnRandomSets) {
  checkAgainstBruteForce(2000, 0.1f, 0.012f, 1);
  checkAgainstBruteForce(1500, 0.05f, 0.03f, 2);
  checkAgainstBruteForce(300, 1.0f, 0.5f, 3);
}

TEST(NeighborGrid, HandlesOutliersByGrowingCells) {
  // One far-away point would need a huge grid: the cell size grows instead,
  // and the answer must still be exact.
  std::vector<float> x = {0, 0.01f, 1e4f}, y = {0, 0, 0}, z = {0, 0, 0};
  ff::UniformGrid g;
  g.build(3, x.data(), y.data(), z.data(), 0.02f, 1 << 16);
  EXPECT_GE(g.cellSize(), 0.02f);
  int n = 0;
  g.forEachRange(0, 0, 0, [&](uint32_t b, uint32_t e) {
    for (uint32_t k = b; k < e; ++k) {
      uint32_t j = g.order()[k];
      if (std::abs(x[j]) < 0.02f) ++n;
    }
  });
  EXPECT_EQ(n, 2);
}

TEST(NeighborGrid, SortIsStableAndGroupsCells) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 0.2f);
  const size_t n = 5000;
  std::vector<float> x(n), y(n), z(n);
  for (size_t i = 0; i < n; ++i) x[i] = u(rng), y[i] = u(rng), z[i] = u(rng);
  ff::UniformGrid g;
  g.build(n, x.data(), y.data(), z.data(), 0.012f);
  const auto& st = g.cellStart();
  for (size_t c = 0; c + 1 < st.size(); ++c)
    for (uint32_t k = st[c] + 1; k < st[c + 1]; ++k) EXPECT_LT(g.order()[k - 1], g.order()[k]);
  EXPECT_EQ(st.back(), n);
}

}  // namespace
