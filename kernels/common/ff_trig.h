// ff_trig.h - sine and cosine in plain float arithmetic, so that the OpenMP
// backend and the kernels round them alike. OpenCL's sin and cos builtins
// may differ from the C library's by up to 4 ulp (the OpenCL 1.2 full
// profile's bound) and round differently on each device; these use only + - * and the exact fmod.
//
// The argument is reduced by fmod to [0, 2 pi) (an exact operation; for
// |x| >= 2 pi the float 2 pi exceeds 2 pi by 1.7e-7, per turn), then by the
// nearest even multiple of pi / 4 with a three-part constant (Cody & Waite),
// and the polynomials of Cephes' sinf / cosf (S. Moshier) evaluate the
// result on [-pi / 4, pi / 4]. Error: at most 1.2e-7 (2 ulp of 1) absolute
// against the sine of the reduced argument (measured: 7.7e-8 over 2^22
// arguments in one turn either way; tests/test_trig.cpp checks the bound).
#ifndef FF_TRIG_H
#define FF_TRIG_H
#include "ff_compat.h"

/* sin (want_cos = 0) or cos (want_cos = 1) of x; NaN for an infinite or NaN x. */
FF_FN float ff_sin_cos(float x, int want_cos) {
  float sign = 1.0f;
  if (x < 0.0f) {
    x = -x;
    if (!want_cos) sign = -1.0f;
  }
  if (!(x <= 3.0e38f)) return x - x; /* (int) below must not see inf or NaN */
  x = FF_FMOD(x, 6.28318530717958647692f);
  int j = (int)(x * 1.27323954473516f); /* x / (pi / 4) */
  float y = (float)j;
  if (j & 1) { /* to the even multiple: the reduced x lies in [-pi / 4, pi / 4] */
    j += 1;
    y += 1.0f;
  }
  j &= 7;
  if (want_cos) j += 2; /* cos x = sin(x + pi / 2) */
  j &= 7;
  if (j > 3) {
    sign = -sign;
    j -= 4;
  }
  x = ((x - y * 0.78515625f) - y * 2.4187564849853515625e-4f) - y * 3.77489497744594108e-8f;
  const float z = x * x;
  float r;
  if (j == 2) { /* j is even here: 0 or 2 */
    r = ((2.443315711809948e-5f * z - 1.388731625493765e-3f) * z + 4.166664568298827e-2f) * z * z - 0.5f * z +
        1.0f;
  } else {
    r = ((-1.9515295891e-4f * z + 8.3321608736e-3f) * z - 1.6666654611e-1f) * z * x + x;
  }
  return sign * r;
}

FF_FN float ff_sin(float x) {
  return ff_sin_cos(x, 0);
}
FF_FN float ff_cos(float x) {
  return ff_sin_cos(x, 1);
}

#endif /* FF_TRIG_H */
