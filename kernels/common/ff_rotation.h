// ff_rotation.h - 3x3 matrices as three columns, unit quaternions, and the
// robust rotation extraction of Mueller, Bender, Chentanez & Macklin 2016
// ("A Robust Method to Extract the Rotational Part of Deformations").
// Shared by the OpenMP backend and the OpenCL kernels.
#ifndef FF_ROTATION_H
#define FF_ROTATION_H
#include "ff_compat.h"
#include "ff_trig.h"

typedef struct {
  ff_float3 c0, c1, c2; /* columns */
} ff_mat3;

FF_FN ff_mat3 ff_mat3_zero(void) {
  ff_mat3 m;
  m.c0 = FF_F3(0.0f, 0.0f, 0.0f);
  m.c1 = m.c0;
  m.c2 = m.c0;
  return m;
}

/* m += a b^T */
FF_FN ff_mat3 ff_mat3_add_outer(ff_mat3 m, ff_float3 a, ff_float3 b) {
  m.c0 = m.c0 + a * b.x;
  m.c1 = m.c1 + a * b.y;
  m.c2 = m.c2 + a * b.z;
  return m;
}

FF_FN ff_float3 ff_mat3_mul_vec(ff_mat3 m, ff_float3 v) {
  return m.c0 * v.x + m.c1 * v.y + m.c2 * v.z;
}

FF_FN float ff_mat3_det(ff_mat3 m) {
  return FF_DOT(m.c0, FF_CROSS(m.c1, m.c2));
}

/* Hamilton product a (x) b. */
FF_FN ff_quat ff_quat_mul(ff_quat a, ff_quat b) {
  return FF_Q(a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
              a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z);
}

FF_FN ff_quat ff_quat_normalize(ff_quat q) {
  float n = FF_SQRT(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (!(n > 1e-20f)) return FF_Q(0.0f, 0.0f, 0.0f, 1.0f);
  float inv = 1.0f / n;
  return FF_Q(q.x * inv, q.y * inv, q.z * inv, q.w * inv);
}

FF_FN ff_mat3 ff_quat_to_mat3(ff_quat q) {
  float xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
  float xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
  float wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
  ff_mat3 r;
  r.c0 = FF_F3(1.0f - 2.0f * (yy + zz), 2.0f * (xy + wz), 2.0f * (xz - wy));
  r.c1 = FF_F3(2.0f * (xy - wz), 1.0f - 2.0f * (xx + zz), 2.0f * (yz + wx));
  r.c2 = FF_F3(2.0f * (xz + wy), 2.0f * (yz - wx), 1.0f - 2.0f * (xx + yy));
  return r;
}

/* Rotation part R(q) of A, warm-started from q. Each iteration rotates q about
 * omega = sum_k r_k x a_k / (|sum_k r_k . a_k| + eps), the axis that best aligns
 * the columns r_k of R(q) with the columns a_k of A. q stays a unit quaternion,
 * so the result is a proper rotation (det = +1) for any A: flat, collinear,
 * zero or inverted. A zero A returns q unchanged. */
FF_FN ff_quat ff_extract_rotation(ff_mat3 a, ff_quat q, int max_iter) {
  for (int it = 0; it < max_iter; ++it) {
    ff_mat3 r = ff_quat_to_mat3(q);
    ff_float3 num = FF_CROSS(r.c0, a.c0) + FF_CROSS(r.c1, a.c1) + FF_CROSS(r.c2, a.c2);
    float den = FF_FABS(FF_DOT(r.c0, a.c0) + FF_DOT(r.c1, a.c1) + FF_DOT(r.c2, a.c2)) + 1.0e-9f;
    ff_float3 omega = num * (1.0f / den);
    float w = ff_length(omega);
    if (w < 1.0e-9f) break;
    float half_angle = 0.5f * w; /* not `half`: a type name in OpenCL C */
    float s = ff_sin(half_angle) / w;
    ff_quat dq = FF_Q(omega.x * s, omega.y * s, omega.z * s, ff_cos(half_angle));
    q = ff_quat_normalize(ff_quat_mul(dq, q));
  }
  return q;
}

#endif /* FF_ROTATION_H */
