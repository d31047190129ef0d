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

size_t NeighbourCache::memoryBytes() const {
  size_t bytes = (offset_.capacity() + count_.capacity() + owner_.capacity()) * sizeof(uint32_t);
  for (const Buffer& b : buffers_) bytes += b.capacity * (sizeof(uint32_t) + 8 * sizeof(float));
  return bytes;
}

}  // namespace ff
