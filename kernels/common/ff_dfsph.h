/* ff_dfsph.h - Divergence-free SPH (Bender & Koschier 2015, 2017): its kernel,
 * its analytic wall and the per-particle bodies of its two solves, written
 * once for the OpenMP backend and the OpenCL kernels.
 *
 * One kernel for everything: DFSPH is only stable when the density change it
 * predicts is the exact time derivative of the density it corrects. So the
 * density, its gradient, the solver's diagonal and the pressure acceleration
 * all use the cubic spline W (Monaghan 1992, support H = the smoothing
 * radius), and the container walls all use the gradient of one wall density
 * share S(x) (the same closed form as in the density).
 *
 * Units: densities in units of rho0 (rho_hat = rho / rho0); V is the volume of
 * a particle in the rest lattice (1 / sum over the lattice of W, so that the
 * rest lattice has rho_hat = 1 exactly). grad W_ij = -g r_ij with
 * r_ij = x_i - x_j and g >= 0 (ff_cubic_grad_factor).
 *
 *   rho_hat_i     = V sum_j W_ij + S(x_i)
 *   d rho_hat_i/dt = -V sum_j g (u_i - u_j).r_ij + grad S(x_i).u_i   (ff_dfsph_rate)
 *
 * A solve looks for k_i >= 0 whose velocity change
 *   du_i = V sum_j g (k_i + k_j) r_ij - k_i grad S(x_i)               (ff_dfsph_velocity_change)
 * (over dt: the divergence solve applies du, the density solve du / dt;
 * near a wall the density solve takes grad S and alpha at x + dt u, where
 * its source measures the walls' share: ff_dfsph_density_source_wall)
 * removes the compression b_i >= 0 that the velocities still cause. As
 * SPlisHSPlasH's DFSPH it iterates Jacobi increments dk_i = alpha_i b_i >= 0
 * (ff_dfsph_increment), applies each increment's velocity change at once and
 * recomputes b from the new velocities, so the stopping test measures what the
 * velocities will do; alpha_i = 1 / (|V sum_j grad W_ij + grad S_i|^2 +
 * sum_j |V grad W_ij|^2) (ff_dfsph_factor_parts). The wall acts as a static boundary
 * with the particle's
 * own k_i, in the diagonal as in du. Only compressions are corrected. */
#ifndef FF_DFSPH_H
#define FF_DFSPH_H
#include "ff_compat.h"

/* The cubic spline's normalisation 8 / (pi H^3); W(0) = coef. */
FF_FN float ff_cubic_coef(float H) {
  return 8.0f / (FF_PI * H * H * H);
}

/* W(r), r the distance, inv_h = 1 / H, k = ff_cubic_coef(H). 0 for r >= H. */
#define FF_CUBIC_DEF(T, name)                                                     \
  FF_FN T name(T r, float inv_h, float k) {                                       \
    T q = r * inv_h;                                                              \
    T a = 1.0f - q;                                                               \
    return (q <= 0.5f ? k * (6.0f * q * q * (q - 1.0f) + 1.0f) : FF_ZERO_OF(T)) + \
           (((q > 0.5f) & (q < 1.0f)) ? 2.0f * k * a * a * a : FF_ZERO_OF(T));    \
  }
FF_GENERIC(FF_CUBIC_DEF, ff_cubic)

/* g of the gradient grad W_ij = -g r_ij, with kg = k / H^2:
 * g = kg (12 - 18 q) for q <= 1/2, 6 kg (1 - q)^2 / q for 1/2 < q < 1, else 0.
 * Finite at r = 0, where r_ij = 0 makes the gradient 0. */
#define FF_CUBIC_GRAD_DEF(T, name)                                              \
  FF_FN T name(T r, float inv_h, float kg) {                                    \
    T q = r * inv_h;                                                            \
    T a = 1.0f - q;                                                             \
    return (q <= 0.5f ? kg * (12.0f - 18.0f * q) : FF_ZERO_OF(T)) +             \
           (((q > 0.5f) & (q < 1.0f)) ? 6.0f * kg * a * a / q : FF_ZERO_OF(T)); \
  }
FF_GENERIC(FF_CUBIC_GRAD_DEF, ff_cubic_grad_factor)

/* Share of the cubic kernel's mass beyond a plane at distance d,
 * F(d) = 2 pi int_d^H W(r) r (r - d) dr (the spherical cap of each shell r),
 * in u = d / H: F = 16 int_u^1 w(t) t (t - u) dt, w the kernel over k.
 * F(0) = 1/2, F(H) = 0. */
FF_FN float ff_cubic_wall_fraction(float d, float inv_h) {
  const float u = ff_clampf(d * inv_h, 0.0f, 1.0f);
  if (u >= 0.5f) {
    const float s = 1.0f - u, s5 = s * s * s * s * s;
    return 16.0f * (0.1f * s5 - s5 * s / 15.0f);
  }
  const float u2 = u * u, u3 = u2 * u;
  const float p1 = u3 * u3 - 1.2f * u3 * u2 + u3 / 3.0f;        /* int_0^u w t^2 */
  const float q1 = 1.2f * u3 * u2 - 1.5f * u2 * u2 + 0.5f * u2; /* int_0^u w t */
  return 16.0f * ((1.0f / 32.0f - p1) - u * (7.0f / 80.0f - q1));
}

/* dF/dd = -(16 / H) int_u^1 w(t) t dt (<= 0), per lane: u = d / H clamped
 * to [0, 1] as fmin(fmax(u, 0), 1) (a NaN gives 0), both polynomials
 * evaluated and one selected. */
#define FF_CUBIC_WALL_SLOPE_DEF(T, name)                                              \
  FF_FN T name(T d, float inv_h) {                                                    \
    const T v = d * inv_h;                                                            \
    const T v0 = v >= 0.0f ? v : FF_ZERO_OF(T);                                       \
    const T u = v0 <= 1.0f ? v0 : FF_ZERO_OF(T) + 1.0f;                               \
    const T s = 1.0f - u, s4 = s * s * s * s;                                         \
    const T u2 = u * u;                                                               \
    const T outer = 0.5f * s4 - 0.4f * s4 * s;                                        \
    const T inner = 7.0f / 80.0f - (1.2f * u2 * u2 * u - 1.5f * u2 * u2 + 0.5f * u2); \
    return -16.0f * inv_h * (u >= 0.5f ? outer : inner);                              \
  }
FF_GENERIC(FF_CUBIC_WALL_SLOPE_DEF, ff_cubic_wall_slope)

/* The volume of a particle of the cubic lattice of `spacing`: 1 / sum over
 * the lattice points within H of W, so that the rest lattice has rho_hat = 1
 * exactly (the lattice sum differs from the integral of W by a few per cent). */
FF_FN float ff_dfsph_lattice_volume(float spacing, float H) {
  const float inv_h = 1.0f / H, k = ff_cubic_coef(H);
  const int n = (int)(H / spacing) + 1;
  float sum = 0.0f;
  for (int z = -n; z <= n; ++z)
    for (int y = -n; y <= n; ++y)
      for (int x = -n; x <= n; ++x) {
        const float r = spacing * FF_SQRT((float)(x * x + y * y + z * z));
        sum += ff_cubic(r, inv_h, k);
      }
  return 1.0f / sum;
}

/* Whether every layer of a wall at distance d is out of reach (the nearest,
 * at max(d, -spacing / 2) + spacing / 2, at H or beyond): 1 or 0 per lane.
 * max as fmax: d where d >= -spacing / 2, else (NaN too) -spacing / 2. */
#define FF_DFSPH_WALL_NEAREST_DEF(T, name)                               \
  FF_FN T name(T d, float spacing) {                                     \
    return d >= -0.5f * spacing ? d : FF_ZERO_OF(T) + (-0.5f * spacing); \
  }
FF_GENERIC(FF_DFSPH_WALL_NEAREST_DEF, ff_dfsph_wall_nearest)
#define FF_DFSPH_WALL_OUT_OF_REACH_DEF(T, name, S)                                                  \
  FF_FN T name(T d, float spacing, float H) {                                                       \
    return FF_OF(ff_dfsph_wall_nearest, S)(d, spacing) + 0.5f * spacing >= H ? FF_ZERO_OF(T) + 1.0f \
                                                                             : FF_ZERO_OF(T);       \
  }
FF_GENERIC_S(FF_DFSPH_WALL_OUT_OF_REACH_DEF, ff_dfsph_wall_out_of_reach)

/* One wall at distance d as its layers of boundary particles (Akinci et al.
 * 2012), spaced as the rest lattice and spread evenly over their plane: the
 * layer at z_m = d + (m + 1/2) spacing adds (vol / spacing^2) A(z_m), where
 * A(z) = 2 pi int_z^H W(r) r dr = -ff_cubic_wall_slope(z) is W integrated
 * over a plane at distance z. So a particle of the rest lattice half a
 * spacing from the wall sees the wall in place of exactly the missing layers
 * (the continuous F(d) of ff_cubic_wall_fraction counts 3.8 % of rho0 more
 * there). Returns the share and sets *slope to its derivative in d,
 * (vol / spacing^2) sum_m -2 pi z_m W(z_m). Per lane: a layer at H or beyond
 * adds an exact 0 (so a wall out of reach, ff_dfsph_wall_out_of_reach, gives
 * share and slope +0). */
#define FF_DFSPH_WALL_LAYERS_DEF(T, name, S)                                             \
  FF_FN T name(T d, float spacing, float vol, float H, float inv_h, float k, T* slope) { \
    const float c = vol / (spacing * spacing);                                           \
    const T dm = FF_OF(ff_dfsph_wall_nearest, S)(d, spacing);                            \
    const int layers = (int)(H / spacing) + 1;                                           \
    T f = FF_ZERO_OF(T), s = FF_ZERO_OF(T);                                              \
    for (int m = 0; m < layers; ++m) {                                                   \
      const T z = dm + ((float)m + 0.5f) * spacing;                                      \
      f -= z < H ? FF_OF(ff_cubic_wall_slope, S)(z, inv_h) : FF_ZERO_OF(T);              \
      s -= z < H ? 2.0f * FF_PI * z * FF_OF(ff_cubic, S)(z, inv_h, k) : FF_ZERO_OF(T);   \
    }                                                                                    \
    *slope = c * s;                                                                      \
    return c * f;                                                                        \
  }
FF_GENERIC_S(FF_DFSPH_WALL_LAYERS_DEF, ff_dfsph_wall_layers)

/* The distance of the wall of axis `a` ((px, py, pz) the position; hi: the
 * high wall) as ff_dfsph_wall's layers see it: d' = 2 d - spacing / 2. */
#define FF_DFSPH_WALL_DISTANCE_DEF(T, name)                                             \
  FF_FN T name(T p, const float* lo, const float* hi, int a, int high, float spacing) { \
    return (high ? 2.0f * (hi[a] - p) : 2.0f * (p - lo[a])) - 0.5f * spacing;           \
  }
FF_GENERIC(FF_DFSPH_WALL_DISTANCE_DEF, ff_dfsph_wall_distance)

/* 1 where some wall is in reach of (px, py, pz) (ff_dfsph_wall), else 0; per lane. */
#define FF_DFSPH_WALL_REACH_DEF(T, name, S)                                                       \
  FF_FN T name(T px, T py, T pz, const float* lo, const float* hi, float spacing, float H) {      \
    const T p[3] = {px, py, pz};                                                                  \
    T out = FF_ZERO_OF(T) + 1.0f;                                                                 \
    for (int w = 0; w < 6; ++w)                                                                   \
      out *= FF_OF(ff_dfsph_wall_out_of_reach, S)(                                                \
          FF_OF(ff_dfsph_wall_distance, S)(p[w / 2], lo, hi, w / 2, w % 2, spacing), spacing, H); \
    return 1.0f - out;                                                                            \
  }
FF_GENERIC_S(FF_DFSPH_WALL_REACH_DEF, ff_dfsph_wall_reach)

/* The walls' density share S = 1 - prod_w (1 - F_w) (an edge or a corner
 * counts the region beyond two walls once) and its exact gradient
 * dS/dx_a = sum over the two walls w of axis a of F'_w (dd_w/dx_a) prod_{o != w} (1 - F_o),
 * dd/dx = +2 for the low wall and -2 for the high one. Walls are taken x, y, z,
 * low then high.
 *
 * Each wall's F_w is ff_dfsph_wall_layers at the distance d' = 2 d - spacing / 2,
 * i.e. the layers squeezed to half their depth about the rest lattice's
 * distance d = spacing / 2: there F_w is unchanged (the rest lattice keeps
 * rho0 at the walls) and its slope doubles. The doubling is what holds a
 * particle at the wall under pressure: in the solve, a particle with k
 * feels -k (grad S + 2 V sum_j grad W_ij) from its own density and its
 * neighbours' (the symmetric k_i + k_j), and the sum over the fluid side of
 * grad W is minus the gradient of the missing fluid's share. So with S as
 * the missing share, a uniform pressure pushes a wall particle into the wall
 * with half its pressure (measured: columns 3-4 % short, their particles
 * within 0.2 spacings of the walls); the doubled slope balances it, and
 * the force stays the gradient of the density (a wall term of 2 k_i grad S
 * instead, the pressure mirroring of IISPH, is not: measured, a resting
 * column blew apart within 0.03 s). The wall reaches one spacing into the
 * fluid and grows up to the wall itself (d' = -spacing / 2).
 *
 * Per lane (ff_dfsph_wall_of: the position (px, py, pz), grad: 3 values):
 * out of reach of every wall (ff_dfsph_wall_reach 0) it gives S = +0 and
 * grad S = +0 (1 - 1, and +0 + -0 for each axis). ff_dfsph_wall, one
 * particle, returns those at once there (most particles). A wall that no
 * lane reaches skips its layers: side 1 and slope +-0, the bits its layers
 * give there (share and slope +0), so a group near one wall pays for that
 * wall alone. */
#define FF_DFSPH_WALL_DEF(T, name, S)                                                                 \
  FF_FN T name(T px, T py, T pz, const float* lo, const float* hi, float spacing, float vol, float H, \
               float inv_h, T* grad) {                                                                \
    const float k = ff_cubic_coef(H);                                                                 \
    const T p[3] = {px, py, pz};                                                                      \
    T side[6], slope[6];                                                                              \
    for (int w = 0; w < 6; ++w) {                                                                     \
      const T d = FF_OF(ff_dfsph_wall_distance, S)(p[w / 2], lo, hi, w / 2, w % 2, spacing);          \
      T s = FF_ZERO_OF(T);                                                                            \
      side[w] = FF_ZERO_OF(T) + 1.0f;                                                                 \
      if (FF_OF(ff_any_lane, S)(FF_OF(ff_dfsph_wall_out_of_reach, S)(d, spacing, H) == 0.0f))         \
        side[w] = 1.0f - FF_OF(ff_dfsph_wall_layers, S)(d, spacing, vol, H, inv_h, k, &s);            \
      slope[w] = (w % 2 ? -2.0f : 2.0f) * s;                                                          \
    }                                                                                                 \
    T prod = FF_ZERO_OF(T) + 1.0f;                                                                    \
    for (int w = 0; w < 6; ++w) prod *= side[w];                                                      \
    for (int a = 0; a < 3; ++a) {                                                                     \
      T others_lo = FF_ZERO_OF(T) + 1.0f, others_hi = FF_ZERO_OF(T) + 1.0f;                           \
      for (int w = 0; w < 6; ++w) {                                                                   \
        if (w != 2 * a) others_lo *= side[w];                                                         \
        if (w != 2 * a + 1) others_hi *= side[w];                                                     \
      }                                                                                               \
      grad[a] = slope[2 * a] * others_lo + slope[2 * a + 1] * others_hi;                              \
    }                                                                                                 \
    return 1.0f - prod;                                                                               \
  }
FF_GENERIC_S(FF_DFSPH_WALL_DEF, ff_dfsph_wall_of)
FF_FN float ff_dfsph_wall(const float* pos, const float* lo, const float* hi, float spacing, float vol,
                          float H, float inv_h, float* grad) {
  if (ff_dfsph_wall_reach(pos[0], pos[1], pos[2], lo, hi, spacing, H) == 0.0f) {
    for (int a = 0; a < 3; ++a) grad[a] = 0.0f;
    return 0.0f;
  }
  return ff_dfsph_wall_of(pos[0], pos[1], pos[2], lo, hi, spacing, vol, H, inv_h, grad);
}

/* The support a wall gives a particle in a pressure gradient. The wall
 * stands for the fluid beyond it with the particle's own pressure, which
 * carries no gradient, so a particle near a wall lacks the share
 * M = V sum_b g r_ib r_ib^T of the normalisation of its pressure gradient
 * (sum over the missing fluid b; 1/2 along the normal for a particle of the
 * rest lattice half a spacing from a wall). Extrapolating the pressure of the
 * missing fluid hydrostatically, p_b = p_i + rho0 f.(x_b - x_i) with f the
 * non-pressure acceleration, adds the acceleration -M f (Band et al. 2018).
 * For the layers of ff_dfsph_wall_layers, per layer at z_m: along the normal
 * c 2 pi z_m^2 W(z_m), along each tangent c A(z_m), c = vol / spacing^2.
 * Several walls add up. Writes -M f into out. */
FF_FN void ff_dfsph_wall_support(const float* pos, const float* lo, const float* hi, float spacing, float vol,
                                 float H, float inv_h, const float* f, float* out) {
  const float k = ff_cubic_coef(H), c = vol / (spacing * spacing);
  const int layers = (int)(H / spacing) + 1;
  float m[3] = {0.0f, 0.0f, 0.0f};
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const float d = FF_FMAX(side ? hi[a] - pos[a] : pos[a] - lo[a], 0.0f);
      if (d + 0.5f * spacing >= H) continue; /* no layer in reach: adds 0 */
      float nn = 0.0f, tt = 0.0f;
      for (int l = 0; l < layers; ++l) {
        const float z = d + ((float)l + 0.5f) * spacing;
        if (z < H) {
          nn += 2.0f * FF_PI * z * z * ff_cubic(z, inv_h, k);
          tt -= ff_cubic_wall_slope(z, inv_h);
        }
      }
      for (int b = 0; b < 3; ++b) m[b] += c * (b == a ? nn : tt);
    }
  for (int b = 0; b < 3; ++b) out[b] = -m[b] * f[b];
}

/* alpha_i = 1 / (q + |wgrad - va|^2) from the fluid's parts of the diagonal,
 * va = V sum_j g r_ij and q = V^2 sum_j g^2 |r_ij|^2, and a wall gradient
 * (0 where the diagonal is at most eps). Per lane (wgrad, va: 3 values). */
#define FF_DFSPH_FACTOR_AT_DEF(T, name)                       \
  FF_FN T name(const T* wgrad, const T* va, T q, float eps) { \
    T d = q;                                                  \
    for (int c = 0; c < 3; ++c) {                             \
      const T gc = wgrad[c] - va[c];                          \
      d += gc * gc;                                           \
    }                                                         \
    return d > eps ? 1.0f / d : FF_ZERO_OF(T);                \
  }
FF_GENERIC(FF_DFSPH_FACTOR_AT_DEF, ff_dfsph_factor_at)

/* alpha's floor eps (ff_dfsph_factor_at) for the support H = 1 / inv_h. */
FF_FN float ff_dfsph_eps(float inv_h) {
  return 1e-6f * inv_h * inv_h;
}

/* The density phase at one particle from its neighbour sums (self
 * included): w = sum_j W_ij, a = sum_j g r_ij, ssq = sum_j g^2 |r_ij|^2,
 * and the walls' share `share` = S(x_i) and gradient wgrad
 * (ff_dfsph_wall). Gives rho_hat and the fluid's parts of the diagonal, va
 * and q (ff_dfsph_factor_at), for the density solve's factor at the
 * predicted position (ff_dfsph_density_source_at); returns alpha_i (0 where
 * the diagonal is below eps: nothing around to push against). Per lane (a,
 * wgrad, va: 3 values); ff_dfsph_factor_parts: one particle, with its walls. */
#define FF_DFSPH_FACTOR_OF_DEF(T, name, S)                                                               \
  FF_FN T name(T share, const T* wgrad, float vol, T w, const T* a, T ssq, float eps, T* rho_hat, T* va, \
               T* q) {                                                                                   \
    *rho_hat = vol * w + share;                                                                          \
    *q = vol * vol * ssq;                                                                                \
    for (int c = 0; c < 3; ++c) va[c] = vol * a[c];                                                      \
    return FF_OF(ff_dfsph_factor_at, S)(wgrad, va, *q, eps);                                             \
  }
FF_GENERIC_S(FF_DFSPH_FACTOR_OF_DEF, ff_dfsph_factor_of)
FF_FN float ff_dfsph_factor_parts(const float* pos, const float* lo, const float* hi, float spacing, float H,
                                  float inv_h, float vol, float w, const float* a, float ssq, float eps,
                                  float* rho_hat, float* wgrad, float* wall_share, float* va, float* q) {
  const float share = ff_dfsph_wall(pos, lo, hi, spacing, vol, H, inv_h, wgrad);
  *wall_share = share;
  return ff_dfsph_factor_of(share, wgrad, vol, w, a, ssq, eps, rho_hat, va, q);
}

/* The rate of rho_hat_i from rs = sum_j g (u_i - u_j).r_ij and the wall,
 * per lane (ff_dfsph_rate_of: u = (ux, uy, uz), wgrad = (gx, gy, gz)) and on
 * arrays. */
#define FF_DFSPH_RATE_DEF(T, name)                                    \
  FF_FN T name(T rs, float vol, T ux, T uy, T uz, T gx, T gy, T gz) { \
    return gx * ux + gy * uy + gz * uz - vol * rs;                    \
  }
FF_GENERIC(FF_DFSPH_RATE_DEF, ff_dfsph_rate_of)
FF_FN float ff_dfsph_rate(float rs, float vol, const float* u, const float* wgrad) {
  return ff_dfsph_rate_of(rs, vol, u[0], u[1], u[2], wgrad[0], wgrad[1], wgrad[2]);
}

/* The velocity change of k from ks = sum_j g (k_i + k_j) r_ij and the wall. */
FF_FN void ff_dfsph_velocity_change(const float* ks, float ki, float vol, const float* wgrad, float* du) {
  for (int c = 0; c < 3; ++c) du[c] = vol * ks[c] - ki * wgrad[c];
}

/* The compression the density solve removes: rho_hat predicted after dt with
 * the rate `rate` of the velocities that every other acceleration gave,
 * clamped at rest density (expansion is left alone): max(s, 1) - 1 with
 * s = rho_hat + dt rate, as a selection (0 where s < 1 or s is NaN, as
 * fmax(s, 1) - 1). Per lane. */
#define FF_DFSPH_DENSITY_SOURCE_DEF(T, name)     \
  FF_FN T name(T rho_hat, T rate, float dt) {    \
    const T s = rho_hat + dt * rate;             \
    return s >= 1.0f ? s - 1.0f : FF_ZERO_OF(T); \
  }
FF_GENERIC(FF_DFSPH_DENSITY_SOURCE_DEF, ff_dfsph_density_source)

/* What the linear prediction rho_hat + dt rate misses of the walls' share:
 * S(x + dt u) - S(x) - dt grad S(x).u, the exact share at the position the
 * integration will give (x + dt u) less its linear part. The squeezed wall
 * layers rise from 0 to their full share within H / 2 of a wall, and a
 * particle that hits a wall at a few m/s crosses a good part of that in one
 * substep: measured on the peer dam break at cfl 0.2 / 5 ms, every single
 * particle squeezed by 5-22 % sat 0.15-0.5 spacings from a wall, moving into
 * it, and the squeeze stayed at a density tolerance of 1e-6 (the solve had
 * converged; its prediction was wrong). Exactly 0 where neither x nor
 * x + dt u is within H / 2 of a wall (ff_dfsph_wall_near). The solves
 * compute it with the S(x) and grad S(x) of their density phase
 * (ff_dfsph_density_source_wall, ff_dfsph_density_source_at). */

/* Along one axis, per lane: 1 where x = p or x + dt u is within H / 2 of
 * the wall at lo or at hi, else 0. */
#define FF_DFSPH_WALL_NEAR_AXIS_DEF(T, name)                                                    \
  FF_FN T name(T p, T u, float dt, float lo, float hi, float H) {                               \
    const T p1 = p + dt * u;                                                                    \
    const float r = 0.5f * H;                                                                   \
    return ((p - lo < r) | (hi - p < r) | (p1 - lo < r) | (hi - p1 < r)) ? FF_ZERO_OF(T) + 1.0f \
                                                                         : FF_ZERO_OF(T);       \
  }
FF_GENERIC(FF_DFSPH_WALL_NEAR_AXIS_DEF, ff_dfsph_wall_near_axis)
/* Whether x = pos or x + dt u (set into p1) is within H / 2 of a wall. */
FF_FN int ff_dfsph_wall_near(const float* pos, const float* u, float dt, const float* lo, const float* hi,
                             float H, float* p1) {
  int near = 0;
  for (int a = 0; a < 3; ++a) {
    p1[a] = pos[a] + dt * u[a];
    near |= ff_dfsph_wall_near_axis(pos[a], u[a], dt, lo[a], hi[a], H) != 0.0f;
  }
  return near;
}

/* The density solve at a particle near a wall (ff_dfsph_wall_near): the
 * remainder from the share s0 = S(x) and gradient g0 = grad S(x) (the
 * density phase's) and p1 = x + dt u, and the walls' gradient g1 at
 * the predicted position p1 = x + dt u, which the solve's velocity change
 * and factor take in place of grad S(x): the source measures the walls'
 * share at p1, so the push that removes it is that share's gradient there.
 * With grad S(x) (weaker: S steepens towards the wall) a particle that its
 * neighbours push into a wall gained more squeeze at p1 than its own k took
 * away, and the Jacobi iteration diverged (measured, a 10 x 16 x 8 water
 * dam break at one 4 ms substep: a particle 0.47 spacings above the floor
 * and 0.77 from a side wall, moving into it at 0.48 m/s; its remainder grew
 * from 0.40 to 0.66, 1.06, 1.63, 2.17 in the first iterations and the solve
 * hit its cap with 10^10 Pa; docs/PRESETS.md). Returns the source
 * (ff_dfsph_density_source) with that remainder; sets g1 and *alpha, the
 * factor with g1. Per lane: the position (px, py, pz), its velocity (ux,
 * uy, uz), the density phase's s0 = S(x), g0 (3 values), va (3 values) and
 * q. ff_dfsph_density_source_at takes it where ff_dfsph_wall_near. */
#define FF_DFSPH_DENSITY_SOURCE_WALL_DEF(T, name, S)                                                        \
  FF_FN T name(T px, T py, T pz, T ux, T uy, T uz, T rho_hat, T rate, float dt, const T* g0, T s0,          \
               const T* va, T q, float eps, const float* lo, const float* hi, float spacing, float vol,     \
               float H, float inv_h, T* g1, T* alpha) {                                                     \
    const T s1 = FF_OF(ff_dfsph_wall_of, S)(px + dt * ux, py + dt * uy, pz + dt * uz, lo, hi, spacing, vol, \
                                            H, inv_h, g1);                                                  \
    const T rem = s1 - s0 - dt * (g0[0] * ux + g0[1] * uy + g0[2] * uz);                                    \
    *alpha = FF_OF(ff_dfsph_factor_at, S)(g1, va, q, eps);                                                  \
    return FF_OF(ff_dfsph_density_source, S)(rho_hat + rem, rate, dt);                                      \
  }
FF_GENERIC_S(FF_DFSPH_DENSITY_SOURCE_WALL_DEF, ff_dfsph_density_source_wall)

/* The density solve's source at particle i, the body of
 * DfsphSolver::sources and of the kernel dfsph_source: the compression after
 * dt (ff_dfsph_density_source) of rho_hat = rho / rho0 moving at the rate
 * `rate`, with the walls' share at x + dt u where x or x + dt u is near a
 * wall (ff_dfsph_wall_near, ff_dfsph_density_source_wall: the remainder
 * S(x + dt u) - S(x) - dt grad S(x).u). g0 = grad S(x) and
 * alpha0, and the arrays wall (S(x)), va (vax, vay, vaz) and q: the density
 * phase's (ff_dfsph_factor_parts); the arrays are read only near a wall.
 * Writes the walls' gradient the solve pushes with into g1 (g0, or
 * grad S(x + dt u) near a wall) and the factor there into *alpha (alpha0,
 * or ff_dfsph_factor_at with g1). */
FF_FN float ff_dfsph_density_source_at(uint i, const float* pos, const float* u, float rho_hat, float rate,
                                       float dt, const float* g0, float alpha0, FF_GLOBAL const float* wall,
                                       FF_GLOBAL const float* vax, FF_GLOBAL const float* vay,
                                       FF_GLOBAL const float* vaz, FF_GLOBAL const float* q, float eps,
                                       const float* lo, const float* hi, float spacing, float vol, float H,
                                       float inv_h, float* g1, float* alpha) {
  float p1[3];
  if (ff_dfsph_wall_near(pos, u, dt, lo, hi, H, p1)) {
    const float va[3] = {vax[i], vay[i], vaz[i]};
    return ff_dfsph_density_source_wall(pos[0], pos[1], pos[2], u[0], u[1], u[2], rho_hat, rate, dt, g0,
                                        wall[i], va, q[i], eps, lo, hi, spacing, vol, H, inv_h, g1, alpha);
  }
  for (int c = 0; c < 3; ++c) g1[c] = g0[c];
  *alpha = alpha0;
  return ff_dfsph_density_source(rho_hat + 0.0f, rate, dt);
}

/* The compression rate the divergence solve removes: only compressing flow,
 * and only where the support is filled (`bulk`, 1 or 0: ff_dfsph_bulk): a
 * particle at a free surface has too few neighbours for a meaningful
 * divergence. max(rate, 0) as a selection (0 where rate is NaN, as fmax).
 * Per lane. */
#define FF_DFSPH_DIVERGENCE_SOURCE_DEF(T, name)                      \
  FF_FN T name(T rate, T bulk) {                                     \
    return ((bulk != 0.0f) & (rate >= 0.0f)) ? rate : FF_ZERO_OF(T); \
  }
FF_GENERIC(FF_DFSPH_DIVERGENCE_SOURCE_DEF, ff_dfsph_divergence_source)

/* The warm start of a solve: `warm` times the last substep's k where the
 * particle compresses (b > 0), else 0. */
FF_FN float ff_dfsph_warm_start(float k, float b, float warm) {
  return b > 0.0f ? warm * k : 0.0f;
}

/* One Jacobi increment of k (Bender & Koschier 2017, as SPlisHSPlasH): the k
 * that would remove the particle's remaining compression b >= 0 if its
 * neighbours stood still. Never negative, as b is clamped. */
#define FF_DFSPH_INCREMENT_DEF(T, name) \
  FF_FN T name(T b, T alpha) {          \
    return b * alpha;                   \
  }
FF_GENERIC(FF_DFSPH_INCREMENT_DEF, ff_dfsph_increment)

/* ---- The per-particle steps of both solvers' outer loop: the OpenMP
 * solver (src/cpu/dfsph_solver.cpp) and the kernels (kernels/dfsph_*.cl). ---- */

/* Whether the divergence solve runs at a particle: its `neighbours` within H
 * plus the walls' density share counted as the neighbours of the full support
 * it stands for (`full`) reach `bulk_share` of a full support. */
FF_FN int ff_dfsph_bulk(float neighbours, float wall_share, float full, float bulk_share) {
  return neighbours + wall_share * full >= bulk_share * full;
}

/* The velocity before the density solve: u + dt (a + the walls' support of
 * ff_dfsph_wall_support), a every other acceleration of the substep. */
FF_FN void ff_dfsph_predict(const float* pos, const float* lo, const float* hi, float spacing, float vol,
                            float H, float inv_h, const float* acc, float dt, float* u) {
  float sup[3];
  ff_dfsph_wall_support(pos, lo, hi, spacing, vol, H, inv_h, acc, sup);
  for (int c = 0; c < 3; ++c) u[c] += dt * (acc[c] + sup[c]);
}

/* The pressure of both solves' k: p = rho0 (kd / dt^2 + kv / dt). */
FF_FN float ff_dfsph_pressure(float kd, float kv, float inv_dt, float rho0) {
  return rho0 * (kd * inv_dt + kv) * inv_dt;
}

/* ---- The pressure the pressure force reads (a readout, not part of a
 * step; src/metrics/force_pressure.cpp, docs/PRESETS.md). ----
 *
 * du_i = 2 V sum_j g_ij kbar_ij r_ij - k_i grad S_i with kbar_ij = (k_i + k_j)
 * / 2: the fluid's part of the force reads k (and p = rho0 (kd / dt^2 +
 * kv / dt), linear in k) only through the pairs' means. For a field linear
 * along a unit direction n, kbar_ij = k_i - (b / 2) r_ij.n and
 * n.du_i = 2 V k_i sum_j g r_ij.n - b V sum_j g (r_ij.n)^2: the gradient is
 * read with the pair weights g (r_ij.n)^2. So the pressure that the force
 * along n reads at particle i is the mean of its pairs' means with these
 * weights, located at their midpoints' mean with the same weights:
 *   p_n,i = (p_i + sum_j w_ij p_j / sum_j w_ij) / 2,
 *   x_n,i = (x_i.n + sum_j w_ij x_j.n / sum_j w_ij) / 2,  w_ij = g_ij (r_ij.n)^2.
 * A k that alternates layer by layer along n has the same mean over every
 * pair of adjacent layers and is not read (pairs in one layer have w = 0,
 * pairs two layers apart are at H or beyond), as the force does not feel
 * it. Exact for a linear field. The walls' term (the particle's own k) is
 * not a pair and is left out: the readout is the fluid's. */

/* The weight of pair ij along n: g (r_ij.n)^2, rn = r_ij.n. */
FF_FN float ff_dfsph_readout_weight(float g, float rn) {
  return g * rn * rn;
}

/* p_n,i from p_i, x_i.n and the pair sums w = sum_j w_ij, wp = sum_j w_ij p_j,
 * wx = sum_j w_ij x_j.n; sets *at = x_n,i. A particle without pairs along n
 * (w = 0) reads its own p at its own place. */
FF_FN float ff_dfsph_force_pressure(float p, float xn, float w, float wp, float wx, float* at) {
  if (!(w > 0.0f)) {
    *at = xn;
    return p;
  }
  *at = 0.5f * (xn + wx / w);
  return 0.5f * (p + wp / w);
}

/* The scalars every DFSPH kernel takes, in one struct of 4-byte fields (C++
 * and OpenCL C lay it out alike). */
typedef struct {
  float lo[4], hi[4];            /* the container's corners (the 4th unused) */
  float h, inv_h, k, kg;         /* support H, 1 / H, ff_cubic_coef(H), k / H^2 */
  float vol, spacing, eps, full; /* V, rest spacing, alpha's floor, neighbours of a full support */
  float bulk_share, rho0, cell, unused;
} FfDfsphArgs;

#endif /* FF_DFSPH_H */
