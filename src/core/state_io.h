// state_io.h - the byte stream of a saved simulation state (checkpoints): a
// writer that appends values, and a reader that checks every read against the
// bytes left, so a truncated or corrupted state is an ff::Error naming its
// source, never a crash or an unbounded allocation.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.h"
#include "core/vec3.h"

namespace ff {

class StateWriter {
 public:
  void bytes(const void* p, size_t n) {
    const char* c = static_cast<const char*>(p);
    data_.insert(data_.end(), c, c + n);
  }
  template <class T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>, "pod() copies bytes");
    bytes(&v, sizeof(T));
  }
  template <class T>
  void vec(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>, "vec() copies bytes");
    pod(uint64_t(v.size()));
    if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
  }
  void str(const std::string& s) {
    pod(uint64_t(s.size()));
    bytes(s.data(), s.size());
  }
  void vec3(const Vec3& v) {
    const float f[3] = {v.x(), v.y(), v.z()};
    pod(f);
  }
  // A four-letter section name, checked on reading.
  void tag(const char (&t)[5]) { bytes(t, 4); }

  const std::vector<char>& data() const { return data_; }

 private:
  std::vector<char> data_;
};

class StateReader {
 public:
  // `source` names the state in messages (the checkpoint file).
  StateReader(const char* data, size_t size, std::string source)
      : data_(data), size_(size), source_(std::move(source)) {}

  void bytes(void* p, size_t n) {
    if (n > size_ - pos_)
      fail("it ends early (" + std::to_string(n) + " more bytes needed at byte " + std::to_string(pos_) +
           ")");
    std::memcpy(p, data_ + pos_, n);
    pos_ += n;
  }
  template <class T>
  T pod() {
    static_assert(std::is_trivially_copyable_v<T>, "pod() copies bytes");
    T v;
    bytes(&v, sizeof(T));
    return v;
  }
  template <class T>
  void pod(T& v) {
    static_assert(std::is_trivially_copyable_v<T>, "pod() copies bytes");
    bytes(&v, sizeof(T));
  }
  template <class T>
  void vec(std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>, "vec() copies bytes");
    const uint64_t n = pod<uint64_t>();
    if (n > (size_ - pos_) / sizeof(T))
      fail("an array of " + std::to_string(n) + " values at byte " + std::to_string(pos_) +
           " is longer than the file");
    v.resize(size_t(n));
    if (n) bytes(v.data(), size_t(n) * sizeof(T));
  }
  std::string str() {
    const uint64_t n = pod<uint64_t>();
    if (n > size_ - pos_) fail("a text at byte " + std::to_string(pos_) + " is longer than the file");
    std::string s(data_ + pos_, size_t(n));
    pos_ += size_t(n);
    return s;
  }
  Vec3 vec3() {
    float f[3];
    bytes(f, sizeof(f));
    return Vec3(f[0], f[1], f[2]);
  }
  void tag(const char (&t)[5]) {
    char got[4];
    bytes(got, 4);
    if (std::memcmp(got, t, 4) != 0)
      fail(std::string("expected the section '") + t + "' at byte " + std::to_string(pos_ - 4));
  }
  // A count read from the state, checked against a limit the caller knows.
  void check(bool ok, const std::string& what) {
    if (!ok) fail(what);
  }
  bool atEnd() const { return pos_ == size_; }
  const std::string& source() const { return source_; }
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(source_ + ": the saved state is corrupted: " + what);
  }

 private:
  const char* data_;
  size_t size_;
  size_t pos_ = 0;
  std::string source_;
};

}  // namespace ff
