#include "control/controller.h"

#include <algorithm>
#include <cmath>

#include "control/control_args.h"
#include "control/shape_match_args.h"
#include "control/shape_matching.h"
#include "ff_anchor.h"
#include "ff_control.h"
#include "ff_control_pull.h"
#include "ff_recapture_field.h"
#include "ff_sph.h"
#include "parallel/parallel_grain.h"
#include "parallel/simd8.h"

namespace ff {

void Controller::setBounds(const float lo[3], const float hi[3]) {
  bounded_ = true;
  for (int d = 0; d < 3; ++d) lo_[d] = lo[d], hi_[d] = hi[d];
}

void Controller::reset(ControlSet set) {
  set_ = std::move(set);
  anchorAtCentre(set_);
  const size_t n = set_.size();
  if (set_.radius_scale.size() != n) set_.radius_scale.assign(n, 1.0f);
  fields_.s.assign(n, 1.0f);
  fields_.ux.assign(n, 0.0f), fields_.uy.assign(n, 0.0f), fields_.uz.assign(n, 0.0f);
  q_.assign(set_.clusters.count(), FF_Q(0.0f, 0.0f, 0.0f, 1.0f));
  gx_ = set_.x, gy_ = set_.y, gz_ = set_.z;
  clock_ = 0.0;
}

namespace {

using simd::f8;
using simd::i8;

// Unused lanes sit this far away: out of every neighbour's reach.
constexpr float kFar = 1.0e18f;

std::vector<uint32_t>& threadSpans() {
  static thread_local std::vector<uint32_t> spans;
  return spans;
}

std::vector<uint32_t>& threadHits() {
  static thread_local std::vector<uint32_t> hits;
  return hits;
}

struct ScaleSums {
  float w, ux, uy, uz;
};

// The lanes of control scale sums for P control particles at once, particle
// j in lanes 8j .. 8j+7: 8 lanes (f8) for one, 16 (an AVX-512 vector) for two.
template <int P>
struct ScaleLanes;
template <>
struct ScaleLanes<1> {
  typedef f8 F;
  typedef i8 I;
  // spread: a fluid block or its lane mask, in every particle's lanes;
  // each: coordinate d of particle j, in j's lanes.
  [[gnu::always_inline]] static F spread(f8 v) { return v; }
  [[gnu::always_inline]] static I spread(i8 v) { return v; }
  [[gnu::always_inline]] static F each(const float (&p)[1][3], int d) { return simd::splat(p[0][d]); }
};
#if FF_SIMD_AVX2
template <>
struct ScaleLanes<2> {
  typedef float F __attribute__((vector_size(64)));
  typedef int I __attribute__((vector_size(64)));
  [[gnu::always_inline]] static F spread(f8 v) {
    return __builtin_shufflevector(v, v, 0, 1, 2, 3, 4, 5, 6, 7, 0, 1, 2, 3, 4, 5, 6, 7);
  }
  [[gnu::always_inline]] static I spread(i8 v) {
    return __builtin_shufflevector(v, v, 0, 1, 2, 3, 4, 5, 6, 7, 0, 1, 2, 3, 4, 5, 6, 7);
  }
  [[gnu::always_inline]] static F each(const float (&p)[2][3], int d) {
    const float a = p[0][d], b = p[1][d];
    return F{a, a, a, a, a, a, a, a, b, b, b, b, b, b, b, b};
  }
};
#endif

// Control scale sums around the control particles at p[0 .. P-1], all of
// radius r: the fluid in the grid ranges within reach of any of them (rows of
// their bounding box), 8 consecutive sorted positions at a time, loaded into
// every particle's 8 lanes, position k in lane k mod 8 of each
// (kernels/control_scale.cl does the same with float8). Each particle's lanes
// add every fluid particle within its reach in ascending sorted order, and the
// others add exactly 0, so its sums do not depend on P, bit for bit: P = 2
// (scaleSumsPair, AVX-512) is worth it where two particles are close
// (neighbours in the set): one walk over nearly the same blocks serves both.
template <class, int P>
FF_SIMD_BODY void scaleSumsOf(const UniformGrid& grid, size_t n, const float* x, const float* y,
                              const float* z, const float* vx, const float* vy, const float* vz,
                              const float (&p)[P][3], float r, float coef, ScaleSums (&out)[P]) {
  typedef ScaleLanes<P> L;
  typedef typename L::F F;
  typedef typename L::I I;
  std::vector<uint32_t>& spans = threadSpans();
  float lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    lo[d] = hi[d] = p[0][d];
    for (int j = 1; j < P; ++j) lo[d] = std::min(lo[d], p[j][d]), hi[d] = std::max(hi[d], p[j][d]);
  }
  grid.rangesNear(lo, hi, r, spans);
  const float r2 = r * r;
  const F px = L::each(p, 0), py = L::each(p, 1), pz = L::each(p, 2);
  const i8 iota = {0, 1, 2, 3, 4, 5, 6, 7};
  const F zero = {};
  F sum = zero, ux = zero, uy = zero, uz = zero;
  for (size_t s = 0; s < spans.size(); s += 2) {
    const uint32_t b = spans[s], e = spans[s + 1];
    for (uint32_t k = b & ~7u; k < e; k += 8) {
      const int m = int(std::min<size_t>(8, n - k));
      const F fx = L::spread(simd::loadN(x + k, m, kFar)), fy = L::spread(simd::loadN(y + k, m, kFar)),
              fz = L::spread(simd::loadN(z + k, m, kFar));
      const F dx = px - fx, dy = py - fy, dz = pz - fz;
      // The lane test at 8 lanes, then spread: a default-target body's
      // 16-lane int comparison is scalarised even inlined into AVX-512 code.
      const i8 kk = iota + int(k);
      const I in = L::spread((kk >= int(b)) & (kk < int(e)));
      const F w = simd::keep(in, ff_poly6(dx * dx + dy * dy + dz * dz, r2, coef));
      sum += w;
      ux += w * L::spread(simd::loadN(vx + k, m, 0.0f)), uy += w * L::spread(simd::loadN(vy + k, m, 0.0f));
      uz += w * L::spread(simd::loadN(vz + k, m, 0.0f));
    }
  }
  for (int j = 0; j < P; ++j) {
    auto total = [j](F v) {
      const int o = 8 * j;
      return ff_lane_sum8(v[o], v[o + 1], v[o + 2], v[o + 3], v[o + 4], v[o + 5], v[o + 6], v[o + 7]);
    };
    out[j] = {total(sum), total(ux), total(uy), total(uz)};
  }
}
FF_SIMD_DISPATCH(scaleSums)

#if FF_SIMD_AVX2
[[gnu::target("avx512f")]] void scaleSumsPair(const UniformGrid& grid, size_t n, const float* x,
                                              const float* y, const float* z, const float* vx,
                                              const float* vy, const float* vz, const float (&p)[2][3],
                                              float r, float coef, ScaleSums (&out)[2]) {
  scaleSumsOf<simd::PortableLanes>(grid, n, x, y, z, vx, vy, vz, p, r, coef, out);
}
#endif

// Control force sums of the fluid particles b .. e-1 (sorted positions, at
// most 8, one row of the fluid grid) as lanes, the control particles in the
// control grid's ranges within reach broadcast one at a time, in ascending
// order: each lane sums as kernels/control_forces.cl does for its particle.
// First the candidates that some lane reaches (branch-free: Lanes::any, see
// simd8.h), then the sums over those alone: a candidate that no lane reaches
// adds exactly 0 to every lane (as the kernel's any() skips it).
// out: 7 x 8 floats (attraction x, y, z, sum of W, sum of W v x, y, z).
struct ForceSumsArgs {
  const float *x, *y, *z;  // the sorted fluid
  const UniformGrid* cp_grid;
  const float *sx, *sy, *sz, *ss, *svx, *svy, *svz;  // control particles in cp_grid order
  float r, r2, coef;  // every control particle's reach (the control radius), P.r2 and P.coef
};
template <class Lanes>
FF_SIMD_BODY void forceSumsOf(const ForceSumsArgs& A, uint32_t b, uint32_t e, float* out) {
  const int n = int(e - b);
  const f8 xe = simd::loadN(A.x + b, n, kFar), ye = simd::loadN(A.y + b, n, kFar),
           ze = simd::loadN(A.z + b, n, kFar);
  const float lo[3] = {simd::hmin(xe, n), simd::hmin(ye, n), simd::hmin(ze, n)};
  const float hi[3] = {simd::hmax(xe, n), simd::hmax(ye, n), simd::hmax(ze, n)};
  std::vector<uint32_t>& spans = threadSpans();
  A.cp_grid->rangesNear(lo, hi, A.r, spans);
  const float *sx = A.sx, *sy = A.sy, *sz = A.sz, r2 = A.r2;
  std::vector<uint32_t>& hits = threadHits();
  size_t most = 0;
  for (size_t s = 0; s < spans.size(); s += 2) most += spans[s + 1] - spans[s];
  if (hits.size() < most) hits.resize(most);
  uint32_t* hit = hits.data();
  size_t nh = 0;
  for (size_t s = 0; s < spans.size(); s += 2)
    for (uint32_t k = spans[s]; k < spans[s + 1]; ++k) {
      const f8 dx = sx[k] - xe, dy = sy[k] - ye, dz = sz[k] - ze;
      hit[nh] = k;
      nh += Lanes::any(dx * dx + dy * dy + dz * dz < r2) ? 1 : 0;
    }
  const f8 zero = simd::splat(0.0f);
  f8 fax = zero, fay = zero, faz = zero, wsum = zero, vsx = zero, vsy = zero, vsz = zero;
  for (size_t q = 0; q < nh; ++q) {
    const uint32_t k = hit[q];
    const f8 dx = sx[k] - xe, dy = sy[k] - ye, dz = sz[k] - ze;
    const f8 d2 = dx * dx + dy * dy + dz * dz;
    const f8 w = ff_poly6(d2, r2, A.coef);
    const f8 a = ff_attraction_factor(simd::sqrt8(d2), A.ss[k], w);
    fax += dx * a, fay += dy * a, faz += dz * a;
    wsum += w;
    vsx += w * A.svx[k], vsy += w * A.svy[k], vsz += w * A.svz[k];
  }
  const f8 sums[7] = {fax, fay, faz, wsum, vsx, vsy, vsz};
  for (int k = 0; k < 7; ++k) simd::storeN(out + 8 * k, sums[k], n);
}
FF_SIMD_DISPATCH(forceSums)

}  // namespace

Controller::SortedFluid Controller::sorted(const FluidView& f) {
  SortedFluid s;
  if (f.grid && f.groups) {
    s.grid = f.grid, s.groups = f.groups;
    s.x = f.x, s.y = f.y, s.z = f.z, s.vx = f.vx, s.vy = f.vy, s.vz = f.vz;
    return s;
  }
  // A plain particle system: sort a copy by a grid of half the control radius.
  fluid_grid_.build(f.n, f.x, f.y, f.z, 0.5f * cp_.radius, size_t(1) << 22);
  const auto& order = fluid_grid_.order();
  auto gather = [&](const float* in, std::vector<float>& out) {
    out.resize(f.n);
    for (size_t k = 0; k < f.n; ++k) out[k] = in[order[k]];
  };
  gather(f.x, fx_), gather(f.y, fy_), gather(f.z, fz_), gather(f.vx, fvx_), gather(f.vy, fvy_),
      gather(f.vz, fvz_);
  fluid_grid_.rowGroups(8, fluid_groups_);
  s.grid = &fluid_grid_, s.groups = &fluid_groups_, s.order = order.data();
  s.x = fx_.data(), s.y = fy_.data(), s.z = fz_.data(), s.vx = fvx_.data(), s.vy = fvy_.data(),
  s.vz = fvz_.data();
  return s;
}

bool Controller::computeScale(const FluidView& f) {
  const long n = long(set_.size());
  if (n == 0) return true;
  const SortedFluid sf = sorted(f);
  // Neighbours in the set (a pair) share one walk where they have the same
  // radius and lie within half of it of each other (scaleSumsPair).
  [[maybe_unused]] const bool pairs = simd::hasAvx512();
  const long npairs = (n + 1) / 2;
  int bad = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(| : bad)
  for (long q = 0; q < npairs; ++q) {
    const long i0 = 2 * q, i1 = std::min(n, i0 + 2);
    ScaleSums t[2];
    const float ra = ff_control_radius(cp_.radius, set_.radius_scale[size_t(i0)]);
    const long ib = std::min(i0 + 1, n - 1);  // b: the pair's second, if there is one
    const float rb = ff_control_radius(cp_.radius, set_.radius_scale[size_t(ib)]);
    bool done = false;
#if FF_SIMD_AVX2
    const float ab[2][3] = {{set_.x[i0], set_.y[i0], set_.z[i0]}, {set_.x[ib], set_.y[ib], set_.z[ib]}};
    const float near = 0.5f * ra;
    if (pairs && i1 == i0 + 2 && rb == ra && std::fabs(ab[0][0] - ab[1][0]) <= near &&
        std::fabs(ab[0][1] - ab[1][1]) <= near && std::fabs(ab[0][2] - ab[1][2]) <= near) {
      scaleSumsPair(*sf.grid, f.n, sf.x, sf.y, sf.z, sf.vx, sf.vy, sf.vz, ab, ra, ff_poly6_coef(ra), t);
      done = true;
    }
#endif
    auto one = [&](long i, float r) {  // particle i's sums, alone
      const float p[1][3] = {{set_.x[i], set_.y[i], set_.z[i]}};
      ScaleSums o[1];
      scaleSums(*sf.grid, f.n, sf.x, sf.y, sf.z, sf.vx, sf.vy, sf.vz, p, r, ff_poly6_coef(r), o);
      return o[0];
    };
    if (!done) {
      t[0] = one(i0, ra);
      if (i1 == i0 + 2) t[1] = one(ib, rb);
    }
    for (long i = i0; i < i1; ++i) {
      const ScaleSums& ti = t[i - i0];
      ff_float3 u;
      const float s = ff_control_scale_of(ti.w, FF_F3(ti.ux, ti.uy, ti.uz), f.volume, &u);
      fields_.s[i] = s;
      fields_.ux[i] = u.x, fields_.uy[i] = u.y, fields_.uz[i] = u.z;
      bad |= std::isfinite(s) && std::isfinite(u.x) && std::isfinite(u.y) && std::isfinite(u.z) ? 0 : 1;
    }
  }
  return !bad;
}

bool Controller::addForces(const FluidView& f, float dt, float* ax, float* ay, float* az) {
  const size_t n = set_.size();
  if (n == 0) return true;
  const float r = cp_.radius;
  const SortedFluid sf = sorted(f);
  // Control particles sorted by cell of their own grid, with s and velocity.
  const float cell = r / float(FF_CONTROL_GRID_DIVISIONS);
  if (bounded_)
    cp_grid_.build(n, set_.x.data(), set_.y.data(), set_.z.data(), cell, lo_, hi_, gridCellCap(n));
  else
    cp_grid_.build(n, set_.x.data(), set_.y.data(), set_.z.data(), cell);
  const auto& order = cp_grid_.order();
  for (auto* a : {&sx_, &sy_, &sz_, &ss_, &svx_, &svy_, &svz_}) a->resize(n);
  for (size_t k = 0; k < n; ++k) {
    const uint32_t i = order[k];
    sx_[k] = set_.x[i], sy_[k] = set_.y[i], sz_[k] = set_.z[i], ss_[k] = fields_.s[i];
    svx_[k] = set_.vx[i], svy_[k] = set_.vy[i], svz_[k] = set_.vz[i];
  }
  const float cp_volume = set_.particle_volume;
  // Recapture: the centre of the unfilled control particles and its fade.
  // It aims there where the centre lies among the control particles (within
  // one spacing of one), else (a torus's hole) each fluid particle at its
  // nearest unfilled control particle, by rfield_.
  float ucx = 0.0f, ucy = 0.0f, ucz = 0.0f, cw = 0.0f, uw = 0.0f;
  for (size_t i = 0; i < n; ++i) {
    const float w = ff_recapture_centre_weight(fields_.s[i]);
    ucx += w * set_.x[i], ucy += w * set_.y[i], ucz += w * set_.z[i], cw += w;
    uw += ff_recapture_weight(fields_.s[i]);
  }
  // It acts whenever it is on: the fade scales it on fluid partly within
  // reach, fluid wholly out of reach is drawn back however full the shape
  // reads (ff_recapture_fade).
  FfRecaptureNow now{};
  now.centre[0] = ucx / cw, now.centre[1] = ucy / cw, now.centre[2] = ucz / cw;
  const bool acts = cp_.recapture > 0.0f;
  now.fade = acts ? ff_recapture_fade(uw, float(n)) : 0.0f;
  const int gn[3] = {cp_grid_.nx(), cp_grid_.ny(), cp_grid_.nz()};
  const float go[3] = {cp_grid_.originX(), cp_grid_.originY(), cp_grid_.originZ()};
  now.at_centre = acts && ff_recapture_among(cp_grid_.cellStart().data(), sx_.data(), sy_.data(), sz_.data(),
                                             now.centre[0], now.centre[1], now.centre[2], FF_CBRT(cp_volume),
                                             go, cp_grid_.cellSize(), cp_grid_.invCellSize(), gn);
  if (acts && !now.at_centre)
    rfield_.build(cp_grid_, sx_.data(), sy_.data(), sz_.data(), ss_.data(), ff_recapture_seed_any(uw) != 0);
  const FfControlArgs P = controlArgs(cp_, f.gravity, f.mass, cp_volume, dt, cp_grid_.cellSize(),
                                      rfield_.geom(), f.controlled_by_id != nullptr, 0);
  const uint32_t* seeds = rfield_.seeds().data();
  const std::vector<uint32_t>& groups = *sf.groups;
  const long ngroups = long(groups.size() / 2);
  reached_.assign(f.n, 0);
  // Every control particle reaches the control radius in eq. 4 and 6 (and
  // so in the carried gravity and the recapture, which read their sums):
  // adaptive control's own radii act in eq. 5 only (computeScale).
  const ForceSumsArgs fs{sf.x,        sf.y,       sf.z,       &cp_grid_,   sx_.data(),
                         sy_.data(),  sz_.data(), ss_.data(), svx_.data(), svy_.data(),
                         svz_.data(), r,          P.r2,       P.coef};
  int bad = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(| : bad)
  for (long g = 0; g < ngroups; ++g) {
    const uint32_t b = groups[2 * size_t(g)], e = groups[2 * size_t(g) + 1];
    float sums[56];
    forceSums(fs, b, e, sums);
    for (uint32_t k = b; k < e; ++k) {
      const size_t l = k - b;
      const float wsum = sums[24 + l];
      const size_t i = sf.order ? sf.order[k] : k;
      if (wsum > 0.0f) reached_[i] = 1;
      const bool recaptured = acts && (!f.controlled_by_id || f.controlled_by_id[f.id[i]]);
      const float rho = P.pull_mode == FF_PULL_PER_DENSITY ? (f.rho ? f.rho[i] : f.rest_density) : 1.0f;
      int changed = 0;
      const ff_float3 a = ff_control_fluid_accel(
          P, now, FF_F3(ax[i], ay[i], az[i]), FF_F3(sums[l], sums[8 + l], sums[16 + l]), wsum,
          FF_F3(sums[32 + l], sums[40 + l], sums[48 + l]), FF_F3(f.x[i], f.y[i], f.z[i]),
          FF_F3(f.vx[i], f.vy[i], f.vz[i]), rho, recaptured ? 1 : 0, seeds, sx_.data(), sy_.data(),
          sz_.data(), &changed);
      if (!changed) continue;
      ax[i] = a.x, ay[i] = a.y, az[i] = a.z;
      bad |= std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z) ? 0 : 1;
    }
  }
  return !bad;
}

size_t Controller::memoryBytes() const {
  size_t floats = 0, uints = 0;
  for (const auto* v : {&set_.x,
                        &set_.y,
                        &set_.z,
                        &set_.vx,
                        &set_.vy,
                        &set_.vz,
                        &set_.x0,
                        &set_.y0,
                        &set_.z0,
                        &set_.clusters.rest_cx,
                        &set_.clusters.rest_cy,
                        &set_.clusters.rest_cz,
                        &fields_.s,
                        &fields_.ux,
                        &fields_.uy,
                        &fields_.uz,
                        &sx_,
                        &sy_,
                        &sz_,
                        &ss_,
                        &svx_,
                        &svy_,
                        &svz_,
                        &set_.radius_scale,
                        &cx_,
                        &cy_,
                        &cz_,
                        &gx_,
                        &gy_,
                        &gz_,
                        &cvx_,
                        &cvy_,
                        &cvz_,
                        &fx_,
                        &fy_,
                        &fz_,
                        &fvx_,
                        &fvy_,
                        &fvz_})
    floats += v->capacity();
  for (const auto* v : {&set_.clusters.start, &set_.clusters.members, &set_.clusters.of_start,
                        &set_.clusters.of, &fluid_groups_})
    uints += v->capacity();
  return reached_.capacity() + rfield_.memoryBytes() + floats * sizeof(float) + uints * sizeof(uint32_t) +
         q_.capacity() * sizeof(ff_quat) + cp_grid_.memoryBytes() + fluid_grid_.memoryBytes();
}

int Controller::advance(float dt) {
  if (set_.size() == 0) return 0;
  clock_ += dt;
  int steps = 0;
  const double h = sm_.time_step;
  while (clock_ >= h * (1.0 - 1e-9)) {
    if (!shapeMatchStep()) sm_finite_ = false;
    clock_ -= h;
    ++steps;
  }
  return steps;
}

bool Controller::shapeMatchStep() {
  const long n = long(set_.size());
  if (n == 0) return true;
  clusterFrames(set_, q_, cx_, cy_, cz_, sm_.rotation_iterations);
  clusterGoals(set_, q_, cx_, cy_, cz_, gx_, gy_, gz_);
  clusterVelocities(set_, cvx_, cvy_, cvz_);
  // "Up", against gravity, for the anchor (ff_anchor.h; A.anchor: it acts).
  ff_float3 up = FF_F3(0.0f, 0.0f, 0.0f);
  ff_anchor_up(g_, &up);
  const FfShapeMatchArgs A =
      shapeMatchArgs(sm_, cp_.feedback, uint32_t(n), uint32_t(set_.clusters.count()), set_.blendWeight(), g_,
                     bounded_ ? lo_ : nullptr, bounded_ ? hi_ : nullptr, 0);
  const Clusters& cl = set_.clusters;
  // The velocities after damping, feedback and eq. 7.
#pragma omp parallel for schedule(static) if (n > kParallelLightLoop)
  for (long i = 0; i < n; ++i) {
    const ff_float3 v = ff_sm_velocity(FF_F3(set_.vx[i], set_.vy[i], set_.vz[i]),
                                       FF_F3(set_.x[i], set_.y[i], set_.z[i]), FF_F3(gx_[i], gy_[i], gz_[i]),
                                       FF_F3(fields_.ux[i], fields_.uy[i], fields_.uz[i]), cl.of_start.data(),
                                       cl.of.data(), cvx_.data(), cvy_.data(), cvz_.data(), uint32_t(i), A);
    set_.vx[i] = v.x, set_.vy[i] = v.y, set_.vz[i] = v.z;
  }
  // The anchor: the set's rigid motion along up and its tilt (ff_anchor.h).
  ff_anchor_fix fix{};
  if (A.anchor)
    fix = ff_anchor_correction(set_.x.data(), set_.y.data(), set_.z.data(), set_.vx.data(), set_.vy.data(),
                               set_.vz.data(), set_.x0.data(), set_.y0.data(), set_.z0.data(), uint32_t(n),
                               FF_F3(set_.rest_cx, set_.rest_cy, set_.rest_cz),
                               FF_F3(set_.anchor_x, set_.anchor_y, set_.anchor_z), up, A.anchor, A.g, A.alpha,
                               A.h, q_.empty() ? FF_Q(0.0f, 0.0f, 0.0f, 1.0f) : q_[0], A.iterations);
  int bad = 0;
#pragma omp parallel for schedule(static) reduction(| : bad) if (n > kParallelLightLoop)
  for (long i = 0; i < n; ++i) {
    ff_float3 v = FF_F3(set_.vx[i], set_.vy[i], set_.vz[i]);
    const ff_float3 x = FF_F3(set_.x[i], set_.y[i], set_.z[i]);
    if (A.anchor) v = ff_anchor_velocity(v, x, fix.dv, fix.dw, fix.com);
    int ok = 1;
    const ff_float3 nx = ff_sm_move(x, &v, A, &ok);
    set_.x[i] = nx.x, set_.y[i] = nx.y, set_.z[i] = nx.z;
    set_.vx[i] = v.x, set_.vy[i] = v.y, set_.vz[i] = v.z;
    bad |= ok ? 0 : 1;
  }
  if (set_.blending()) set_.blend_elapsed += double(A.h);
  return !bad;
}

void Controller::step(const FluidView& f, float dt, float* ax, float* ay, float* az) {
  computeScale(f);
  addForces(f, dt, ax, ay, az);
  advance(dt);
}

}  // namespace ff
