// ff_compat.h - the tiny vocabulary that lets one header compile both as C++
// (the OpenMP backend, tests) and as OpenCL C 1.2 (the kernels).
//
// Rules for code in kernels/common/:
//   * only `float`, `int`, `uint`, the ff_float3 / ff_quat helpers below and
//     the value type T of FF_GENERIC formulas;
//   * every function is FF_FN (inline, no state);
//   * math goes through FF_SQRT / FF_FABS / FF_FMIN / FF_FMAX / FF_FMOD (and
//     FF_ISFINITE) so both
//     sides call the single-precision functions, each correctly rounded (sqrt
//     where the device has -cl-fp32-correctly-rounded-divide-sqrt); sin and
//     cos, which OpenCL does not round correctly, are written out in float
//     arithmetic (ff_trig.h), and so are dot and cross (below). FF_CBRT is
//     for the host only (not correctly rounded in OpenCL).
#ifndef FF_COMPAT_H
#define FF_COMPAT_H

#ifdef __OPENCL_VERSION__
#define FF_FN inline
#define FF_GLOBAL __global /* a pointer parameter into device memory; nothing in C++ */
typedef float3 ff_float3;
typedef float4 ff_quat; /* (x, y, z, w) */
#define FF_F3(a, b, c) ((float3)((a), (b), (c)))
#define FF_Q(x, y, z, w) ((float4)((x), (y), (z), (w)))
#define FF_SQRT(a) sqrt(a)
#define FF_CBRT(a) cbrt(a)
#define FF_FMOD(a, b) fmod((a), (b))
#define FF_FABS(a) fabs(a)
#define FF_FLOOR(a) floor(a)
#define FF_FMIN(a, b) fmin((a), (b))
#define FF_FMAX(a, b) fmax((a), (b))
#define FF_ISFINITE(a) isfinite(a)
#define FF_ZERO_OF(T) ((T)(0.0f))
#define FF_GENERIC(def, name) def(float, name) def(float8, name##_8)
#define FF_GENERIC_S(def, name) def(float, name, ) def(float8, name##_8, _8)
#else
#include <cmath>
#include <cstdint>
typedef unsigned int uint;
struct ff_float3 {
  float x, y, z;
};
struct ff_quat {
  float x, y, z, w;
};
inline ff_float3 operator+(ff_float3 a, ff_float3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline ff_float3 operator-(ff_float3 a, ff_float3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline ff_float3 operator-(ff_float3 a) {
  return {-a.x, -a.y, -a.z};
}
inline ff_float3 operator*(ff_float3 a, float s) {
  return {a.x * s, a.y * s, a.z * s};
}
inline ff_float3 operator*(float s, ff_float3 a) {
  return {a.x * s, a.y * s, a.z * s};
}
inline ff_float3 operator/(ff_float3 a, float s) {
  return {a.x / s, a.y / s, a.z / s};
}
inline ff_float3& operator+=(ff_float3& a, ff_float3 b) {
  a = a + b;
  return a;
}
inline ff_float3& operator-=(ff_float3& a, ff_float3 b) {
  a = a - b;
  return a;
}
#define FF_FN inline
#define FF_GLOBAL
#define FF_F3(a, b, c) (ff_float3{(a), (b), (c)})
#define FF_Q(x, y, z, w) (ff_quat{(x), (y), (z), (w)})
#define FF_SQRT(a) std::sqrt((float)(a))
#define FF_CBRT(a) std::cbrt((float)(a))
#define FF_FMOD(a, b) std::fmod((float)(a), (float)(b))
#define FF_FABS(a) std::fabs((float)(a))
#define FF_FLOOR(a) std::floor((float)(a))
/* fmin / fmax inline: std::fmin / std::fmax are calls into libm on x86-64
 * (minss / maxss do not treat NaN as C does). These return what glibc's do,
 * bit for bit: the non-NaN operand where one is NaN, the first where both are
 * equal (so also the first of +0 and -0). */
inline float ff_fmin_c(float a, float b) {
  return (a <= b || b != b) ? a : b;
}
inline float ff_fmax_c(float a, float b) {
  return (a >= b || b != b) ? a : b;
}
#define FF_FMIN(a, b) ff_fmin_c((float)(a), (float)(b))
#define FF_FMAX(a, b) ff_fmax_c((float)(a), (float)(b))
#define FF_ISFINITE(a) std::isfinite((float)(a))
#define FF_ZERO_OF(T) (T{})
/* Always inlined: an instance on 8-lane vectors is compiled for the default
 * target, and its caller (an FF_SIMD_BODY) for AVX2 or AVX-512. Called out of
 * line, a 32-byte vector argument would pass between the two ABIs (GCC's
 * -Wpsabi note): the sanitizer build, which inlined less, wrote through a
 * garbage pointer there (UBSan: store to misaligned address 0x6 in
 * ff_dfsph_wall_of, CI on ab20df9). */
#define FF_GENERIC(def, name) \
  template <class FF_T>       \
  [[gnu::always_inline]] def(FF_T, name)
#define FF_GENERIC_S(def, name) \
  template <class FF_T>         \
  [[gnu::always_inline]] def(FF_T, name, )
#endif
/* Whether some lane of a comparison's result is true: one value is its own
 * lane (int in OpenCL C, bool in C++); a vector mask has all bits set in a
 * true lane (OpenCL's int8, the C++ backend's i8). Lets a formula skip work
 * that adds exact zeros in every lane (called as FF_OF(ff_any_lane, S)). */
#ifdef __OPENCL_VERSION__
FF_FN int ff_any_lane(int m) {
  return m != 0;
}
FF_FN int ff_any_lane_8(int8 m) {
  return any(m);
}
#else
inline bool ff_any_lane(bool m) {
  return m;
}
template <class M>
[[gnu::always_inline]] inline bool ff_any_lane(M m) {
  static_assert(sizeof(M) % sizeof(unsigned long long) == 0, "a vector mask");
  unsigned long long w[sizeof(M) / sizeof(unsigned long long)], bits = 0;
  __builtin_memcpy(w, &m, sizeof w);
  for (unsigned long long v : w) bits |= v;
  return bits != 0;
}
#endif

/* A formula that calls other FF_GENERIC formulas is a def(T, name, S),
 * stamped out by FF_GENERIC_S: S is the suffix of its instance (nothing, or
 * _8 for OpenCL's float8, which has no overloading), and it calls them as
 * FF_OF(other, S). */
#define FF_OF(name, S) FF_CAT_(name, S)
#define FF_CAT_(a, b) a##b

/* Formulas that the neighbour loops evaluate are written once, as a macro
 * def(T, name) for a value type T, and stamped out by FF_GENERIC(def, name):
 * in OpenCL C as name (float) and name_8 (float8); in C++ as the template
 * name<T>, on float and on the OpenMP backend's 8-lane vectors
 * (src/parallel/simd8.h). Vectors evaluate them lane by lane with the same
 * operations. Such a body uses only + - * /, comparisons combined with & and
 * the selection c ? a : FF_ZERO_OF(T) (for vectors both sides are computed
 * and the unselected lanes dropped, so those must not trap: IEEE floats do not). */

/* dot and cross written out, the same on both sides: OpenCL's dot() and
 * cross() builtins may sum in another order or fuse the products (on a GPU
 * they do), so the kernels would round differently from the C++ backend. */
#define FF_DOT(a, b) ((a).x * (b).x + (a).y * (b).y + (a).z * (b).z)
#define FF_CROSS(a, b) \
  FF_F3((a).y*(b).z - (a).z * (b).y, (a).z * (b).x - (a).x * (b).z, (a).x * (b).y - (a).y * (b).x)

#define FF_PI 3.14159265358979323846f

FF_FN float ff_length(ff_float3 a) {
  return FF_SQRT(FF_DOT(a, a));
}
FF_FN float ff_clampf(float v, float lo, float hi) {
  return FF_FMIN(FF_FMAX(v, lo), hi);
}

#endif /* FF_COMPAT_H */
