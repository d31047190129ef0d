#include "cpu/uniform_grid.h"

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
  cell_ = cell;
  auto dims = [&](float c, int d) { return int(std::floor((hi[d] - lo[d]) / c)) + 3; };
  while (true) {
    nx_ = dims(cell_, 0), ny_ = dims(cell_, 1), nz_ = dims(cell_, 2);
    if (size_t(nx_) * ny_ * nz_ <= max_cells) break;
    cell_ *= 1.25f;
  }
  inv_cell_ = 1.0f / cell_;
  ox_ = lo[0] - cell_, oy_ = lo[1] - cell_, oz_ = lo[2] - cell_;
  size_t ncells = size_t(nx_) * ny_ * nz_;

  // Counting sort: count, exclusive scan, scatter.
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
  fill_.assign(start_.begin(), start_.end() - 1);
  for (size_t i = 0; i < n; ++i) order_[fill_[cell_of_[i]]++] = uint32_t(i);
}

void permute(std::vector<float>& a, const std::vector<uint32_t>& order, std::vector<float>& scratch) {
  scratch.resize(a.size());
#pragma omp parallel for schedule(static)
  for (long k = 0; k < long(order.size()); ++k) scratch[k] = a[order[k]];
  a.swap(scratch);
}

void permute(std::vector<uint32_t>& a, const std::vector<uint32_t>& order, std::vector<uint32_t>& scratch) {
  scratch.resize(a.size());
#pragma omp parallel for schedule(static)
  for (long k = 0; k < long(order.size()); ++k) scratch[k] = a[order[k]];
  a.swap(scratch);
}

}  // namespace ff
