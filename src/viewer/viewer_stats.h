// viewer_stats.h - numbers the panel shows: a fixed-size history of a value
// (for ImGui::PlotLines) and exponentially smoothed timings.
#pragma once
#include <cstddef>
#include <vector>

namespace ff::viewer {

// The last `capacity` values pushed, oldest first from offset().
class History {
 public:
  explicit History(size_t capacity) : values_(capacity, 0.0f) {}
  void push(float v) {
    values_[head_] = v;
    head_ = (head_ + 1) % values_.size();
    if (count_ < values_.size()) ++count_;
  }
  void clear() { head_ = count_ = 0; }
  size_t count() const { return count_; }
  // PlotLines(values, count, offset) walks from offset, wrapping around.
  const float* data() const { return values_.data(); }
  size_t offset() const { return count_ < values_.size() ? 0 : head_; }
  float latest() const { return count_ ? values_[(head_ + values_.size() - 1) % values_.size()] : 0.0f; }

 private:
  std::vector<float> values_;
  size_t head_ = 0, count_ = 0;
};

// Exponential moving average; the first sample sets the value.
struct Smoothed {
  double value = 0.0;
  bool primed = false;
  void add(double v, double weight = 0.05) {
    value = primed ? value + weight * (v - value) : v;
    primed = true;
  }
};

}  // namespace ff::viewer
