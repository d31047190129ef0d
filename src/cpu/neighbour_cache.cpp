#include "cpu/neighbour_cache.h"

#include <omp.h>

#include <algorithm>

namespace ff {

void NeighbourCache::Buffer::reserve(size_t n) {
  if (n <= capacity) return;
  const size_t c = std::max(n, capacity + capacity / 2);
  std::unique_ptr<uint32_t[]> nj(new uint32_t[c]);
  std::unique_ptr<float[]> ng(new float[8 * c]);
  if (size) {
    std::memcpy(nj.get(), j.get(), size * sizeof(uint32_t));
    std::memcpy(ng.get(), g.get(), 8 * size * sizeof(float));
  }
  j = std::move(nj), g = std::move(ng), capacity = c;
}

int NeighbourCache::reset(size_t groups, float radius) {
  radius_ = radius;
  const int threads = omp_get_max_threads();
  if (buffers_.size() < size_t(threads)) buffers_.resize(size_t(threads));
  for (Buffer& b : buffers_) b.size = 0;
  offset_.assign(groups, 0), count_.assign(groups, 0), owner_.assign(groups, 0);
  return threads;
}

NeighbourCache::Writer NeighbourCache::open(size_t most) {
  Buffer& b = buffers_[size_t(omp_get_thread_num())];
  b.reserve(b.size + most);
  Writer w;
  w.j_ = b.j.get() + b.size, w.g_ = b.g.get() + 8 * b.size;
  return w;
}

void NeighbourCache::close(size_t gi, const Writer& w) {
  const size_t t = size_t(omp_get_thread_num());
  Buffer& b = buffers_[t];
  offset_[gi] = uint32_t(b.size), count_[gi] = uint32_t(w.n_), owner_[gi] = uint32_t(t);
  b.size += w.n_;
}

void NeighbourCache::split(int count) {
  const size_t n = count_.size();
  uint64_t total = 0;
  for (const uint32_t c : count_) total += c + kGroupShare;
  parts_.assign(size_t(std::max(count, 1)) + 1, n);
  parts_[0] = 0;
  // Part k ends at the first group where the work so far reaches k / count of the total.
  uint64_t sum = 0;
  size_t k = 1;
  for (size_t gi = 0; gi < n && k + 1 < parts_.size(); ++gi) {
    sum += count_[gi] + kGroupShare;
    while (k + 1 < parts_.size() && sum * uint64_t(parts_.size() - 1) >= total * k) parts_[k++] = gi + 1;
  }
}

size_t NeighbourCache::memoryBytes() const {
  size_t bytes = (offset_.capacity() + count_.capacity() + owner_.capacity()) * sizeof(uint32_t) +
                 parts_.capacity() * sizeof(size_t);
  for (const Buffer& b : buffers_) bytes += b.capacity * (sizeof(uint32_t) + 8 * sizeof(float));
  return bytes;
}

}  // namespace ff
