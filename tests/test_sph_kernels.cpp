// Kernel normalisation and the analytic wall integrals, against numerical
// quadrature done here in double precision.
#include <gtest/gtest.h>

#include <cmath>

#include "ff_sph.h"

namespace {

const double kPi = 3.14159265358979323846;

// integral over the ball of radius h of f(r) dV, by the midpoint rule in r.
template <class F>
double radialIntegral(F f, double h, int n = 20000) {
  double sum = 0.0, dr = h / n;
  for (int i = 0; i < n; ++i) {
    double r = (i + 0.5) * dr;
    sum += f(r) * 4.0 * kPi * r * r * dr;
  }
  return sum;
}

TEST(SphKernels, Poly6IsNormalised) {
  for (float h : {0.012f, 0.03f, 1.0f}) {
    const float coef = ff_poly6_coef(h);
    double integral =
        radialIntegral([&](double r) { return double(ff_poly6(float(r * r), h * h, coef)); }, h);
    EXPECT_NEAR(integral, 1.0, 1e-4) << "h=" << h;
    EXPECT_EQ(ff_poly6(h * h * 1.0001f, h * h, coef), 0.0f);
  }
}

TEST(SphKernels, SpikyGradientMatchesDerivativeOfNormalisedKernel) {
  const double h = 0.012;
  const float coef = ff_spiky_grad_coef(float(h));
  auto w = [&](double r) { return 15.0 / (kPi * std::pow(h, 6)) * std::pow(h - r, 3); };
  EXPECT_NEAR(radialIntegral(w, h), 1.0, 1e-4);
  for (double r : {0.001, 0.004, 0.008, 0.0115}) {
    double dw = (w(r + 1e-7) - w(r - 1e-7)) / 2e-7;  // dW/dr (negative)
    // grad W = -g * r_vec, so |grad W| along r_hat = -g r
    double g = ff_spiky_grad_factor(float(r), float(h), coef);
    EXPECT_NEAR(-g * r, dw, 1e-3 * std::fabs(dw)) << "r=" << r;
  }
}

TEST(SphKernels, ViscosityLaplacianMatchesKernel) {
  const double h = 0.012;
  const float coef = ff_visc_lap_coef(float(h));
  auto w = [&](double r) {
    return 15.0 / (2.0 * kPi * h * h * h) *
           (-r * r * r / (2 * h * h * h) + r * r / (h * h) + h / (2 * r) - 1.0);
  };
  EXPECT_NEAR(radialIntegral(w, h), 1.0, 1e-3);
  for (double r : {0.002, 0.006, 0.01}) {
    const double e = 1e-5;
    double d1 = (w(r + e) - w(r - e)) / (2 * e), d2 = (w(r + e) - 2 * w(r) + w(r - e)) / (e * e);
    double lap = d2 + 2.0 / r * d1;
    EXPECT_NEAR(ff_visc_lap(float(r), float(h), coef), lap, 2e-3 * std::fabs(lap)) << "r=" << r;
  }
}

// Fraction of the kernel's mass beyond a plane at distance d, integrated
// numerically over z slices of the ball.
template <class W>
double halfSpaceFraction(W w, double h, double d) {
  const int nz = 400, nr = 400;
  double sum = 0.0;
  for (int iz = 0; iz < nz; ++iz) {
    double z = d + (h - d) * (iz + 0.5) / nz, dz = (h - d) / nz;
    double rmax = std::sqrt(std::max(0.0, h * h - z * z));
    for (int ir = 0; ir < nr; ++ir) {
      double rho = rmax * (ir + 0.5) / nr, drho = rmax / nr;
      sum += w(std::sqrt(z * z + rho * rho)) * 2.0 * kPi * rho * drho * dz;
    }
  }
  return sum;
}

TEST(SphKernels, WallFractionOfPoly6MatchesQuadrature) {
  const float h = 0.012f, coef = ff_poly6_coef(h);
  EXPECT_NEAR(ff_poly6_wall_fraction(0.0f, h, coef), 0.5f, 1e-5f);
  EXPECT_NEAR(ff_poly6_wall_fraction(h, h, coef), 0.0f, 1e-6f);
  EXPECT_NEAR(ff_poly6_wall_fraction(2 * h, h, coef), 0.0f, 1e-6f);
  for (double d : {0.001, 0.003, 0.006, 0.009}) {
    double ref =
        halfSpaceFraction([&](double r) { return double(ff_poly6(float(r * r), h * h, coef)); }, h, d);
    EXPECT_NEAR(ff_poly6_wall_fraction(float(d), h, coef), ref, 2e-4) << "d=" << d;
  }
}

TEST(SphKernels, WallSliceOfSpikyIsTheDerivativeOfItsHalfSpaceMass) {
  const double h = 0.012;
  auto w = [&](double r) { return r < h ? 15.0 / (kPi * std::pow(h, 6)) * std::pow(h - r, 3) : 0.0; };
  for (double d : {0.001, 0.004, 0.008}) {
    const double e = 2e-5;
    double slope = -(halfSpaceFraction(w, h, d + e) - halfSpaceFraction(w, h, d - e)) / (2 * e);
    EXPECT_NEAR(ff_spiky_wall_slice(float(d), float(h)), slope, 2e-2 * slope) << "d=" << d;
  }
}

}  // namespace
