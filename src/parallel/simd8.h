// simd8.h - eight floats as one value (GCC/Clang vector extensions), for the
// OpenMP backend's neighbour loops. They run eight query particles at once
// against one neighbour at a time: each lane adds its own terms in the
// neighbours' order, exactly as a scalar loop (and an OpenCL work-item) does,
// so vectorising changes no result. Compiled for AVX2 where the CPU has it
// (FF_SIMD_CLONES: function multi-versioning), else as pairs of SSE operations.
#pragma once
#include <cstring>

#pragma GCC diagnostic ignored "-Wpsabi"
namespace ff::simd {

typedef float f8 __attribute__((vector_size(32)));
typedef int i8 __attribute__((vector_size(32)));

inline f8 splat(float v) {
  return f8{v, v, v, v, v, v, v, v};
}

// Lanes 0..n-1 from p, the rest `fill`.
inline f8 loadN(const float* p, int n, float fill) {
  f8 v;
  if (n == 8) {
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  v = splat(fill);
  for (int l = 0; l < n; ++l) v[l] = p[l];
  return v;
}

inline void storeN(float* p, f8 v, int n) {
  if (n == 8) {
    std::memcpy(p, &v, sizeof v);
    return;
  }
  for (int l = 0; l < n; ++l) p[l] = v[l];
}

inline f8 sqrt8(f8 v) {
  f8 r;
  for (int l = 0; l < 8; ++l) r[l] = __builtin_sqrtf(v[l]);
  return r;
}

// m ? a : 0, lane by lane (m from a comparison: all bits set or none).
inline f8 keep(i8 m, f8 a) {
  i8 bits;
  std::memcpy(&bits, &a, sizeof bits);
  bits &= m;
  f8 r;
  std::memcpy(&r, &bits, sizeof r);
  return r;
}

inline bool any(i8 m) {
  unsigned long long w[4];
  std::memcpy(w, &m, sizeof w);
  return ((w[0] | w[1]) | (w[2] | w[3])) != 0;
}

inline float hmin(f8 v, int n) {
  float r = v[0];
  for (int l = 1; l < n; ++l) r = v[l] < r ? v[l] : r;
  return r;
}
inline float hmax(f8 v, int n) {
  float r = v[0];
  for (int l = 1; l < n; ++l) r = v[l] > r ? v[l] : r;
  return r;
}

// All of lanes 0..n-1 finite.
inline bool finiteN(f8 v, int n) {
  bool ok = true;
  for (int l = 0; l < n; ++l) ok = ok && __builtin_isfinite(v[l]);
  return ok;
}

}  // namespace ff::simd

// Multi-versioning for the hot loops: an AVX2 clone picked at load time where
// the CPU has it, and the portable default.
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define FF_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#define FF_SIMD_AVX2 1
#else
#define FF_SIMD_CLONES
#define FF_SIMD_AVX2 0
#endif

// Lane tests by instruction set, for a hot loop whose lane test is most of
// its work: the loop is written once as an always-inline template on one of
// these and instantiated in a plain function and in one built for AVX2
// (target("avx2")), called where simd::hasAvx2(). PortableLanes compiles
// anywhere; Avx2Lanes::any is one vmovmskps (simd::any goes through four
// general-purpose registers) and may only run inside AVX2 code. Both test the
// same bits, so the results are the same.
namespace ff::simd {
struct PortableLanes {
  static bool any(i8 m) { return simd::any(m); }
};
#if FF_SIMD_AVX2
#pragma GCC push_options
#pragma GCC target("avx2")
struct Avx2Lanes {
  static inline bool any(i8 m) { return __builtin_ia32_movmskps256((f8)m) != 0; }
};
#pragma GCC pop_options
inline bool hasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
inline bool hasAvx512() {
  static const bool has = __builtin_cpu_supports("avx512f");
  return has;
}
#define FF_TARGET_AVX2 __attribute__((target("avx2")))
#else
inline bool hasAvx2() {
  return false;
}
inline bool hasAvx512() {
  return false;
}
#endif
}  // namespace ff::simd
