#include "grid/uniform_grid.h"

#include <algorithm>
#include <cmath>

namespace ff {

void UniformGrid::build(size_t n, const float* x, const float* y, const float* z, float cell,
                        size_t max_cells) {
  float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  if (n > 0) {
    lo[0] = hi[0] = x[0], lo[1] = hi[1] = y[0], lo[2] = hi[2] = z[0];
    for (size_t i = 1; i < n; ++i) {
      lo[0] = std::min(lo[0], x[i]), hi[0] = std::max(hi[0], x[i]);
      lo[1] = std::min(lo[1], y[i]), hi[1] = std::max(hi[1], y[i]);
      lo[2] = std::min(lo[2], z[i]), hi[2] = std::max(hi[2], z[i]);
    }
  }
  build(n, x, y, z, cell, lo, hi, max_cells);
}

void UniformGrid::build(size_t n, const float* x, const float* y, const float* z, float cell,
                        const float lo[3], const float hi[3], size_t max_cells) {
  cell_ = cell;
  auto dims = [&](float c, int d) { return int(std::floor((hi[d] - lo[d]) / c)) + 3; };
  while (true) {
    nx_ = dims(cell_, 0), ny_ = dims(cell_, 1), nz_ = dims(cell_, 2);
    if (size_t(nx_) * ny_ * nz_ <= max_cells) break;
    cell_ *= 1.25f;
  }
  inv_cell_ = 1.0f / cell_;
  ox_ = lo[0] - cell_, oy_ = lo[1] - cell_, oz_ = lo[2] - cell_;
  sort(n, x, y, z);
}

void UniformGrid::sort(size_t n, const float* x, const float* y, const float* z) {
  const size_t ncells = size_t(nx_) * ny_ * nz_;
  // Counting sort: count, exclusive scan, scatter (start_ doubles as the fill
  // pointer and is shifted back afterwards).
  start_.assign(ncells + 1, 0);
  cell_of_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    size_t c = ff_cell_index(cellCoord(x[i], ox_, nx_), cellCoord(y[i], oy_, ny_), cellCoord(z[i], oz_, nz_),
                             nx_, ny_);
    cell_of_[i] = uint32_t(c);
    ++start_[c + 1];
  }
  for (size_t c = 0; c < ncells; ++c) start_[c + 1] += start_[c];
  order_.resize(n);
  for (size_t i = 0; i < n; ++i) order_[start_[cell_of_[i]]++] = uint32_t(i);
  for (size_t c = ncells; c > 0; --c) start_[c] = start_[c - 1];
  start_[0] = 0;
}

void UniformGrid::rangesNear(const float lo[3], const float hi[3], float radius,
                             std::vector<uint32_t>& out) const {
  const float reach = ff_query_reach(radius, cell_), r2 = reach * reach;
  const int z0 = cellCoord(lo[2] - reach, oz_, nz_), z1 = cellCoord(hi[2] + reach, oz_, nz_);
  const int y0 = cellCoord(lo[1] - reach, oy_, ny_), y1 = cellCoord(hi[1] + reach, oy_, ny_);
  constexpr int kRows = 64;  // y rows whose gaps are kept; beyond that they are recomputed
  float gy2[kRows];
  for (int y = y0; y <= y1 && y - y0 < kRows; ++y) {
    const float g = ff_slab_gap(lo[1], hi[1], y, ny_, oy_, cell_);
    gy2[y - y0] = g * g;
  }
  // Room for every row up front, written through a pointer (push_back's
  // stores could alias the grid's members and the box, so they were
  // reloaded per row); the members as locals. The same rows, tests and
  // ranges in the same order.
  const size_t most = z1 >= z0 && y1 >= y0 ? 2 * size_t(z1 - z0 + 1) * size_t(y1 - y0 + 1) : 0;
  if (out.size() < most) out.resize(most);
  uint32_t* o = out.data();
  size_t k = 0;
  const uint32_t* start = start_.data();
  const float lox = lo[0], hix = hi[0], ox = ox_, inv_cell = inv_cell_;
  const int nx = nx_, ny = ny_;
  for (int z = z0; z <= z1; ++z) {
    const float gz = ff_slab_gap(lo[2], hi[2], z, nz_, oz_, cell_), gz2 = gz * gz;
    if (gz2 > r2) continue;
    for (int y = y0; y <= y1; ++y) {
      float g2;
      if (y - y0 < kRows) {
        g2 = gy2[y - y0] + gz2;
      } else {
        const float g = ff_slab_gap(lo[1], hi[1], y, ny, oy_, cell_);
        g2 = g * g + gz2;
      }
      int x0, x1;
      if (!ff_row_cells(lox, hix, g2, reach, ox, inv_cell, nx, &x0, &x1)) continue;
      const size_t row = ff_cell_index(0, y, z, nx, ny);
      const uint32_t b = start[row + size_t(x0)], e = start[row + size_t(x1) + 1];
      if (b < e) o[k] = b, o[k + 1] = e, k += 2;
    }
  }
  out.resize(k);
}

void UniformGrid::rowGroups(uint32_t width, std::vector<uint32_t>& out) const {
  out.clear();
  const size_t rows = size_t(ny_) * nz_;
  for (size_t r = 0; r < rows; ++r) {
    const uint32_t b = start_[r * size_t(nx_)], e = start_[(r + 1) * size_t(nx_)];
    for (uint32_t g = b; g < e; g += width) out.push_back(g), out.push_back(std::min(e, g + width));
  }
}

size_t UniformGrid::memoryBytes() const {
  return (start_.capacity() + order_.capacity() + cell_of_.capacity()) * sizeof(uint32_t);
}

void permute(std::vector<float>& a, const std::vector<uint32_t>& order, std::vector<float>& scratch) {
  scratch.resize(a.size());
  const long n = long(order.size());
#pragma omp parallel for schedule(static) if (n > 65536)
  for (long k = 0; k < n; ++k) scratch[size_t(k)] = a[order[size_t(k)]];
  a.swap(scratch);
}

void permute(std::vector<uint32_t>& a, const std::vector<uint32_t>& order, std::vector<uint32_t>& scratch) {
  scratch.resize(a.size());
  const long n = long(order.size());
#pragma omp parallel for schedule(static) if (n > 65536)
  for (long k = 0; k < n; ++k) scratch[size_t(k)] = a[order[size_t(k)]];
  a.swap(scratch);
}

}  // namespace ff
