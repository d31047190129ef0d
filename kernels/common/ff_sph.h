// ff_sph.h - SPH formulas of Mueller, Charypar & Gross 2003, plus the analytic
// planar-wall boundary. Shared by the OpenMP backend and the OpenCL kernels.
#ifndef FF_SPH_H
#define FF_SPH_H
#include "ff_compat.h"

/* Kernel constants for support radius h (precomputed once per run). */
FF_FN float ff_poly6_coef(float h) {
  return 315.0f / (64.0f * FF_PI * h * h * h * h * h * h * h * h * h);
}
FF_FN float ff_spiky_grad_coef(float h) {
  return 45.0f / (FF_PI * h * h * h * h * h * h);
}
FF_FN float ff_visc_lap_coef(float h) {
  return 45.0f / (FF_PI * h * h * h * h * h * h);
}

/* W_poly6 from the squared distance r2 (0 outside the support). */
#define FF_POLY6_DEF(T, name)                          \
  FF_FN T name(T r2, float h2, float coef) {           \
    T d = h2 - r2;                                     \
    return r2 < h2 ? coef * d * d * d : FF_ZERO_OF(T); \
  }
FF_GENERIC(FF_POLY6_DEF, ff_poly6)

/* Magnitude factor g of the spiky gradient: grad W(r_ij) = -g * r_ij
 * where r_ij = x_i - x_j and g = coef * (h - r)^2 / r. Zero for r = 0 or r >= h. */
#define FF_SPIKY_GRAD_FACTOR_DEF(T, name)                               \
  FF_FN T name(T r, float h, float coef) {                              \
    T d = h - r;                                                        \
    return ((r > 1e-12f) & (r < h)) ? coef * d * d / r : FF_ZERO_OF(T); \
  }
FF_GENERIC(FF_SPIKY_GRAD_FACTOR_DEF, ff_spiky_grad_factor)

/* Laplacian of the viscosity kernel. */
#define FF_VISC_LAP_DEF(T, name)                   \
  FF_FN T name(T r, float h, float coef) {         \
    return r < h ? coef * (h - r) : FF_ZERO_OF(T); \
  }
FF_GENERIC(FF_VISC_LAP_DEF, ff_visc_lap)

/* Muller et al. 2003 pair terms of fluid particle i from neighbour j, with the
 * spiky gradient factor g (grad W = -g r_ij) and the viscosity Laplacian lap:
 *   pressure:  a_i += c r_ij,          c = m (p_i + p_j) / (2 rho_j) g
 *   viscosity: a_i += c_v (v_j - v_i), c_v = m lap / rho_j
 * (divided by rho_i once the sums are done). c is exactly 0 where g is. */
#define FF_PRESSURE_PAIR_DEF(T, name)                                        \
  FF_FN T name(T g, T pi, float pj, float rhoj, float mass) {                \
    return g != 0.0f ? mass * (pi + pj) / (2.0f * rhoj) * g : FF_ZERO_OF(T); \
  }
FF_GENERIC(FF_PRESSURE_PAIR_DEF, ff_pressure_pair)

#define FF_VISC_PAIR_DEF(T, name)               \
  FF_FN T name(T lap, float rhoj, float mass) { \
    return mass * lap / rhoj;                   \
  }
FF_GENERIC(FF_VISC_PAIR_DEF, ff_visc_pair)

/* Equation of state p = k (rho - rho0). */
FF_FN float ff_pressure(float rho, float rho0, float k) {
  return k * (rho - rho0);
}

/* ---------------------------------------------------------------------------
 * Planar wall boundary.
 *
 * Akinci et al. 2012 sample the wall with boundary particles b of volume-weighted
 * mass Psi_b = rho0 V_b and add rho0 * sum_b V_b W(x - x_b) to the density. For a
 * flat wall sampled finely this sum converges to rho0 times the part of the
 * kernel that lies beyond the wall. For an axis-aligned box the integral has a
 * closed form, so we evaluate it exactly instead of storing wall particles.
 * d is the distance from the particle to the wall plane (d >= h: no effect).
 * ------------------------------------------------------------------------- */

/* Fraction of the poly6 kernel's mass that lies beyond a plane at distance d:
 * F(d) = (pi K / 4) * int_d^h (h^2 - z^2)^4 dz, with F(0) = 1/2. */
FF_FN float ff_poly6_wall_fraction(float d, float h, float coef) {
  d = ff_clampf(d, 0.0f, h);
  float h2 = h * h, h4 = h2 * h2, h6 = h4 * h2, h8 = h4 * h4;
  float d2 = d * d, d3 = d2 * d, d5 = d3 * d2, d7 = d5 * d2, d9 = d7 * d2;
  float ph = h8 * h * (128.0f / 315.0f);
  float pd = h8 * d - (4.0f / 3.0f) * h6 * d3 + (6.0f / 5.0f) * h4 * d5 - (4.0f / 7.0f) * h2 * d7 + d9 / 9.0f;
  return 0.25f * FF_PI * coef * (ph - pd);
}

/* Share of the kernel beyond any of several walls, from the product of the
 * shares on the fluid side of each: 1 - prod_w (1 - F_w). Exact for one wall;
 * at an edge or a corner it counts the region beyond two walls once, where a
 * plain sum of the F_w would count it twice (measured: +16% density in a
 * corner of a lattice at rest with the sum, see test_fluid_physics.cpp). */
FF_FN float ff_combine_wall_fractions(float fluid_side_product) {
  return 1.0f - fluid_side_product;
}

/* Integral of the spiky kernel over the slice at distance d from the particle,
 * S(d) = 2 pi K_spiky int_d^h (h - r)^3 r dr with K_spiky = 15/(pi h^6).
 * The half-space integral of grad_x W_spiky is -S(d) n, with n the wall's
 * inward normal. */
FF_FN float ff_spiky_wall_slice(float d, float h) {
  d = ff_clampf(d, 0.0f, h);
  float u = h - d, u2 = u * u, u4 = u2 * u2;
  float h6 = h * h * h * h * h * h;
  return (30.0f / h6) * (h * u4 * 0.25f - u4 * u * 0.2f);
}

/* Acceleration that the mirrored wall pressure exerts along the inward normal.
 * From f_i = -sum_j m_j (p_i + p_j)/(2 rho_j) grad W with the wall carrying
 * p_j = p_i and m_j / rho_j = dV: f_i = p_i S(d) n, a_i = f_i / rho_i.
 * Negative pressure is not mirrored (a wall never pulls fluid onto itself). */
FF_FN float ff_wall_pressure_accel(float d, float h, float p, float rho) {
  return FF_FMAX(p, 0.0f) * ff_spiky_wall_slice(d, h) / rho;
}

/* ---------------------------------------------------------------------------
 * Per-particle wall bodies, shared by the OpenMP loops and the kernels. pos,
 * lo and hi are the particle and the container's corners; the walls are taken
 * x, y, z, low then high (the summation order of both backends).
 * ------------------------------------------------------------------------- */

/* The walls' share of the density, in units of rho0: 1 - prod_w (1 - F_w). */
FF_FN float ff_wall_density_share(const float* pos, const float* lo, const float* hi, float h, float coef) {
  float fluid_side = 1.0f; /* the kernel's share on the fluid side of every wall within h */
  for (int d = 0; d < 3; ++d) {
    const float dlo = pos[d] - lo[d], dhi = hi[d] - pos[d];
    if (dlo < h) fluid_side *= 1.0f - ff_poly6_wall_fraction(dlo, h, coef);
    if (dhi < h) fluid_side *= 1.0f - ff_poly6_wall_fraction(dhi, h, coef);
  }
  return ff_combine_wall_fractions(fluid_side);
}

/* WCSPH pressure acceleration of particle i from its pressure sums ps (the
 * pair terms of ff_pressure_pair) and the walls' mirrored pressure. */
FF_FN void ff_wcsph_pressure_accel(const float* pos, const float* lo, const float* hi, float h, float pi,
                                   float rhoi, const float* ps, float* a) {
  for (int d = 0; d < 3; ++d) a[d] = ps[d] / rhoi;
  for (int d = 0; d < 3; ++d) {
    const float dlo = pos[d] - lo[d], dhi = hi[d] - pos[d];
    if (dlo < h) a[d] += ff_wall_pressure_accel(dlo, h, pi, rhoi);
    if (dhi < h) a[d] += -1.0f * ff_wall_pressure_accel(dhi, h, pi, rhoi);
  }
}

/* The non-pressure force plug-ins' bodies (src/cpu/forces/, host/forces/,
 * kernels/forces.cl). The forces phase starts from a = 0 and each plug-in
 * adds its acceleration to a. */
/* Gravity. */
FF_FN void ff_add_gravity_accel(const float* gravity, float* a) {
  for (int d = 0; d < 3; ++d) a[d] = a[d] + gravity[d];
}
/* Viscosity: the sums vs of ff_visc_pair, times mu / rho_i. */
FF_FN void ff_add_viscosity_accel(const float* vs, float mu, float rhoi, float* a) {
  const float inv = mu / rhoi;
  for (int d = 0; d < 3; ++d) a[d] = a[d] + vs[d] * inv;
}

/* The scalars of the SPH kernels other than DFSPH's (density.cl,
 * pressure_wcsph.cl, forces.cl), in one struct of 4-byte fields, as
 * FfDfsphArgs (C++ and OpenCL C lay it out alike). */
typedef struct {
  float lo[4], hi[4];               /* the container's corners (the 4th unused) */
  float h, mass, rho0, gas_k;       /* support, particle mass, rest density, EOS stiffness k */
  float mu, cell, unused0, unused1; /* viscosity, the grid's cell size (the lane kernels) */
} FfSphArgs;

#endif /* FF_SPH_H */
