// kernels/common/ff_trig.h: sine and cosine written out in float arithmetic
// (the kernels use them instead of OpenCL's builtins), against the C
// library's double-precision sin and cos.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "ff_trig.h"

namespace {

// Largest |ff - exact| over n arguments evenly spread over [lo, hi]; `exact`
// gets the argument as ff_trig.h reduces it (fmod by the float 2 pi, exact).
template <class Ff, class Exact>
double maxError(float lo, float hi, int n, Ff ff, Exact exact) {
  double worst = 0.0;
  for (int i = 0; i <= n; ++i) {
    const float x = lo + (hi - lo) * float(i) / float(n);
    const double reduced = std::copysign(std::fmod(std::fabs(double(x)), double(6.28318530717958647692f)), x);
    worst = std::max(worst, std::fabs(double(ff(x)) - exact(reduced)));
  }
  return worst;
}

TEST(Trig, SineAndCosineWithinTheStatedErrorOverOneTurnEachWay) {
  const int n = 1 << 20;
  const auto s = [](float x) { return ff_sin(x); };
  const auto c = [](float x) { return ff_cos(x); };
  const auto ds = [](double x) { return std::sin(x); };
  const auto dc = [](double x) { return std::cos(x); };
  const double es = maxError(-6.2831f, 6.2831f, n, s, ds), ec = maxError(-6.2831f, 6.2831f, n, c, dc);
  std::printf("  |x| < 2 pi: max error sin %.3g, cos %.3g\n", es, ec);
  EXPECT_LE(es, 1.2e-7);
  EXPECT_LE(ec, 1.2e-7);
  // Beyond one turn: the sine of the argument reduced by the float 2 pi.
  EXPECT_LE(maxError(6.3f, 1000.0f, n / 16, s, ds), 1.2e-7);
  EXPECT_LE(maxError(-1000.0f, -6.3f, n / 16, c, dc), 1.2e-7);
}

TEST(Trig, SmallAnglesKeepTheirRelativePrecision) {
  // The rotation extraction's half angles are mostly tiny: sin x = x (1 - x^2/6).
  for (float x = 1e-30f; x < 1e-2f; x *= 1.7f) {
    const double exact = std::sin(double(x));
    EXPECT_LE(std::fabs(ff_sin(x) - exact), 1.2e-7 * exact) << x;
    EXPECT_LE(std::fabs(ff_cos(x) - std::cos(double(x))), 6e-8) << x;
    EXPECT_EQ(ff_sin(-x), -ff_sin(x));
    EXPECT_EQ(ff_cos(-x), ff_cos(x));
  }
  EXPECT_EQ(ff_sin(0.0f), 0.0f);
  EXPECT_EQ(ff_cos(0.0f), 1.0f);
}

TEST(Trig, NonFiniteArgumentsGiveNaN) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  for (float x : {inf, -inf, nan}) {
    EXPECT_TRUE(std::isnan(ff_sin(x))) << x;
    EXPECT_TRUE(std::isnan(ff_cos(x))) << x;
  }
}

}  // namespace
