// simd8.h - eight floats as one value (GCC/Clang vector extensions), for the
// OpenMP backend's neighbour loops. They run eight query particles at once
// against one neighbour at a time: each lane adds its own terms in the
// neighbours' order, exactly as a scalar loop (and an OpenCL work-item) does,
// so vectorising changes no result. Run as AVX2 where the CPU has it (and
// FLOWFORM_SIMD allows it: FF_SIMD_DISPATCH below), else as pairs of SSE
// operations.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/error.h"
#include "ff_compat.h"

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

// m ? a : 0, lane by lane (m from a comparison: all bits set or none), for
// float vectors of any width and int masks of the same size (f8 and i8, or
// the 16 lanes of the control scale sums' AVX-512 walk).
template <class I, class F>
[[gnu::always_inline]] inline F keep(I m, F a) {
  static_assert(sizeof(I) == sizeof(F), "the mask has a lane per float");
  I bits;
  std::memcpy(&bits, &a, sizeof bits);
  bits &= m;
  F r;
  std::memcpy(&r, &bits, sizeof r);
  return r;
}

// Lanes 0..n-1 set (all bits), the rest 0.
inline i8 liveLanes(int n) {
  const i8 lane = {0, 1, 2, 3, 4, 5, 6, 7};
  return lane < n;
}

inline bool any(i8 m) {
  return ff_any_lane(m);
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

// Instruction sets of the hot loops. Each is written once as an
// always-inline template on its lane test (FF_SIMD_BODY) and instantiated in a
// portable function, in one built for AVX2 and in one built for AVX-512F
// and VL, on the same 8 lanes (FF_SIMD_DISPATCH); a few have a 16-lane
// AVX-512 loop of their own too. PortableLanes compiles anywhere; Avx2Lanes::any is
// one vmovmskps (simd::any goes through four general-purpose registers) and
// may only run inside AVX2 code. Every instance rounds the same operations in
// the same order (no contraction: -ffp-contract=off) and tests the same bits,
// so they give the same results bit for bit (tests/test_simd_paths.cpp).
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define FF_SIMD_AVX2 1
#else
#define FF_SIMD_AVX2 0
#endif

namespace ff::simd {

// The widest instance a loop may run: the CPU's, capped by $FLOWFORM_SIMD
// (read once: `portable`, `avx2`, or `native`, the default: no cap) and by
// capIsa(). The cap changes only the speed, never a result.
enum class Isa { Portable = 0, Avx2 = 1, Avx512 = 2 };

namespace detail {
inline Isa cpuIsa() {
#if FF_SIMD_AVX2
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl")) return Isa::Avx512;
  if (__builtin_cpu_supports("avx2")) return Isa::Avx2;
#endif
  return Isa::Portable;
}
inline Isa environmentCap() {
  const char* v = std::getenv("FLOWFORM_SIMD");
  const std::string s = v ? v : "";
  if (s.empty() || s == "native") return Isa::Avx512;
  if (s == "avx2") return Isa::Avx2;
  if (s == "portable") return Isa::Portable;
  throw Error("FLOWFORM_SIMD: unknown instruction set '" + s + "' (known: native, avx2, portable)");
}
// The CPU's, capped by the environment; capIsa() lowers it further.
inline std::atomic<int>& allowed() {
  static std::atomic<int> a{std::min(int(cpuIsa()), int(environmentCap()))};
  return a;
}
}  // namespace detail

// Throws ff::Error on a bad $FLOWFORM_SIMD (the first call reads it).
inline Isa isa() {
  return Isa(detail::allowed().load(std::memory_order_relaxed));
}
// Caps isa() for the rest of the process (the tests run each instance so);
// Isa::Avx512 restores the CPU's and the environment's cap. Not while a step runs.
inline void capIsa(Isa cap) {
  detail::allowed().store(std::min(int(detail::cpuIsa()), std::min(int(detail::environmentCap()), int(cap))),
                          std::memory_order_relaxed);
}
// As FLOWFORM_SIMD names it ("avx512" for the widest).
inline const char* isaName(Isa i) {
  return i == Isa::Avx512 ? "avx512" : i == Isa::Avx2 ? "avx2" : "portable";
}
inline bool hasAvx2() {
  return isa() >= Isa::Avx2;
}
inline bool hasAvx512() {
  return isa() >= Isa::Avx512;
}

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
// The AVX-512 instances' lane test: AVX2's, inlined into AVX-512 code.
struct Avx512Lanes : Avx2Lanes {};
#define FF_TARGET_AVX2 __attribute__((target("avx2")))
#define FF_TARGET_AVX512 __attribute__((target("avx2,avx512f,avx512vl")))
#endif
}  // namespace ff::simd

// A hot loop's body: `template <class Lanes> FF_SIMD_BODY R nameOf(...)`.
#define FF_SIMD_BODY [[gnu::always_inline]] inline
// Defines name(...) for the body nameOf: its AVX-512 instance where
// simd::hasAvx512(), else its AVX2 one where simd::hasAvx2(), else its
// portable one. The AVX-512 instance runs the same 8 lanes as the AVX2 one,
// with AVX-512VL's encodings: 32 vector registers instead of 16, so fewer
// sums and loop constants go to the stack (docs/PERFORMANCE.md). Not
// inlined, so that its loop's other inlining stays as it was with GCC's
// target_clones before.
#if FF_SIMD_AVX2
#define FF_SIMD_DISPATCH(name)                                               \
  template <class... A>                                                      \
  auto name##Portable(A&&... a) {                                            \
    return name##Of<::ff::simd::PortableLanes>(static_cast<A&&>(a)...);      \
  }                                                                          \
  template <class... A>                                                      \
  FF_TARGET_AVX2 auto name##Avx2(A&&... a) {                                 \
    return name##Of<::ff::simd::Avx2Lanes>(static_cast<A&&>(a)...);          \
  }                                                                          \
  template <class... A>                                                      \
  FF_TARGET_AVX512 auto name##Avx512(A&&... a) {                             \
    return name##Of<::ff::simd::Avx512Lanes>(static_cast<A&&>(a)...);        \
  }                                                                          \
  template <class... A>                                                      \
  [[gnu::noinline]] auto name(A&&... a) {                                    \
    return ::ff::simd::hasAvx512() ? name##Avx512(static_cast<A&&>(a)...)    \
           : ::ff::simd::hasAvx2() ? name##Avx2(static_cast<A&&>(a)...)      \
                                   : name##Portable(static_cast<A&&>(a)...); \
  }
#else
#define FF_SIMD_DISPATCH(name)                                          \
  template <class... A>                                                 \
  inline auto name(A&&... a) {                                          \
    return name##Of<::ff::simd::PortableLanes>(static_cast<A&&>(a)...); \
  }
#endif
