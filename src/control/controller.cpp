#include "control/controller.h"

#include <omp.h>
#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstring>

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
  bounded_ = true, pairs_ready_ = false, control_sorted_ = false;
  for (int d = 0; d < 3; ++d) lo_[d] = lo[d], hi_[d] = hi[d];
}

void Controller::reset(ControlSet set) {
  set_ = std::move(set);
  pairs_ready_ = false, control_sorted_ = false;
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

// The control particles (sorted positions in cp_grid, at sx, sy, sz) that
// some fluid particle of the group b .. e-1 (sorted positions of x, y, z; at
// most 8, one row of the fluid grid) reaches within rc, in ascending order,
// into hit[0 ..) (room for them: pairCandidateRoom); returns how many. The
// control grid's ranges within reach of the group's box, each candidate tested
// in the group's 8 lanes, branch-free (Lanes::any, see simd8.h).
size_t pairCandidateRoom(const UniformGrid& cp_grid, const float* x, const float* y, const float* z,
                         uint32_t b, uint32_t e, float rc, std::vector<uint32_t>& spans) {
  const int n = int(e - b);
  const f8 xe = simd::loadN(x + b, n, kFar), ye = simd::loadN(y + b, n, kFar),
           ze = simd::loadN(z + b, n, kFar);
  const float lo[3] = {simd::hmin(xe, n), simd::hmin(ye, n), simd::hmin(ze, n)};
  const float hi[3] = {simd::hmax(xe, n), simd::hmax(ye, n), simd::hmax(ze, n)};
  cp_grid.rangesNear(lo, hi, rc, spans);
  size_t most = 0;
  for (size_t s = 0; s < spans.size(); s += 2) most += spans[s + 1] - spans[s];
  return most;
}
template <class Lanes>
FF_SIMD_BODY size_t pairCandidatesOf(const std::vector<uint32_t>& spans, const float* x, const float* y,
                                     const float* z, uint32_t b, uint32_t e, const float* sx, const float* sy,
                                     const float* sz, float rc2, uint32_t* hit) {
  const int n = int(e - b);
  const f8 xe = simd::loadN(x + b, n, kFar), ye = simd::loadN(y + b, n, kFar),
           ze = simd::loadN(z + b, n, kFar);
  size_t nh = 0;
  for (size_t s = 0; s < spans.size(); s += 2)
    for (uint32_t k = spans[s]; k < spans[s + 1]; ++k) {
      const f8 dx = sx[k] - xe, dy = sy[k] - ye, dz = sz[k] - ze;
      hit[nh] = k;
      nh += Lanes::any(dx * dx + dy * dy + dz * dz < rc2) ? 1 : 0;
    }
  return nh;
}
FF_SIMD_DISPATCH(pairCandidates)

#if FF_SIMD_AVX2
// Each lane of v twice: lanes 2l and 2l + 1 hold v[l].
[[gnu::target("avx512f"), gnu::always_inline]] inline __m512 twice8(f8 v) {
  return (__m512)__builtin_shufflevector(v, v, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7);
}
// p[0] in the even lanes, p[1] in the odd ones.
[[gnu::target("avx512f"), gnu::always_inline]] inline __m512 pairOf(const float* p) {
  double d;
  std::memcpy(&d, p, sizeof d);
  return _mm512_castpd_ps(_mm512_set1_pd(d));
}
// Lanes below r2 at the squared distance from (px, py, pz) to the lanes of (x, y, z).
[[gnu::target("avx512f"), gnu::always_inline]] inline unsigned within16(__m512 px, __m512 py, __m512 pz,
                                                                        __m512 x, __m512 y, __m512 z,
                                                                        __m512 r2) {
  const __m512 dx = _mm512_sub_ps(px, x), dy = _mm512_sub_ps(py, y), dz = _mm512_sub_ps(pz, z);
  const __m512 d2 =
      _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(dx, dx), _mm512_mul_ps(dy, dy)), _mm512_mul_ps(dz, dz));
  return _mm512_cmp_ps_mask(d2, r2, _CMP_LT_OQ);
}

// pairCandidates in the 16 lanes of AVX-512: two candidates at once, the
// group's particle l in lanes 2l (against candidate k) and 2l + 1 (against
// k + 1), with the same operations per lane (so the same candidates).
[[gnu::target("avx512f")]] size_t pairCandidatesWide(const std::vector<uint32_t>& spans, const float* x,
                                                     const float* y, const float* z, uint32_t b, uint32_t e,
                                                     const float* sx, const float* sy, const float* sz,
                                                     float rc2, uint32_t* hit) {
  const int n = int(e - b);
  const __m512 xe = twice8(simd::loadN(x + b, n, kFar)), ye = twice8(simd::loadN(y + b, n, kFar)),
               ze = twice8(simd::loadN(z + b, n, kFar));
  const __m512 r2 = _mm512_set1_ps(rc2);
  size_t nh = 0;
  for (size_t s = 0; s < spans.size(); s += 2) {
    uint32_t k = spans[s];
    const uint32_t end = spans[s + 1];
    for (; k + 1 < end; k += 2) {
      const unsigned m = within16(pairOf(sx + k), pairOf(sy + k), pairOf(sz + k), xe, ye, ze, r2);
      hit[nh] = k;
      nh += (m & 0x5555u) ? 1 : 0;
      hit[nh] = k + 1;
      nh += (m & 0xaaaau) ? 1 : 0;
    }
    if (k < end) {
      const unsigned m =
          within16(_mm512_set1_ps(sx[k]), _mm512_set1_ps(sy[k]), _mm512_set1_ps(sz[k]), xe, ye, ze, r2);
      hit[nh] = k;
      nh += m ? 1 : 0;
    }
  }
  return nh;
}
#endif

// Control scale sums (eq. 5 and the feedback's mean velocity) of the control
// particles hit[0 .. nh-1] (sorted positions in the control grid, ascending)
// over the fluid group b .. e-1, added to acc (per sorted position 4 x 8
// lanes: sum W, sum W v x, y, z). A control particle's sum runs in 8 lanes:
// the fluid particle at sorted position k adds to lane k mod 8, so the group
// is loaded into those lanes (the others far, still). Groups visited in
// ascending order add to each lane in ascending k: the sums of
// kernels/control_scale.cl (and of a walk per control particle) bit for bit,
// since a fluid particle out of a control particle's own radius (sr2, scoef:
// its squared radius and poly6 coefficient) adds exactly 0.
template <class>
FF_SIMD_BODY void scaleScatterOf(size_t n, const float* x, const float* y, const float* z, const float* vx,
                                 const float* vy, const float* vz, uint32_t b, uint32_t e,
                                 const uint32_t* hit, size_t nh, const float* sx, const float* sy,
                                 const float* sz, const float* sr2, const float* scoef, float* acc) {
  // Lane l holds position base + l or base + 8 + l, whichever lies in b .. e-1.
  const uint32_t base = b & ~7u;
  const int m0 = int(std::min<size_t>(8, n - base)),
            m1 = int(std::min<size_t>(8, n - std::min<size_t>(n, base + 8)));
  const i8 iota = {0, 1, 2, 3, 4, 5, 6, 7};
  const i8 low = iota + int(base) >= int(b), k = low ? iota + int(base) : iota + int(base + 8);
  const i8 in = k < int(e);
  auto lanes = [&](const float* a, float fill) {
    const f8 v = low ? simd::loadN(a + base, m0, fill) : simd::loadN(a + base + 8, m1, fill);
    return in ? v : simd::splat(fill);
  };
  const f8 xr = lanes(x, kFar), yr = lanes(y, kFar), zr = lanes(z, kFar);
  const f8 vxr = lanes(vx, 0.0f), vyr = lanes(vy, 0.0f), vzr = lanes(vz, 0.0f);
  for (size_t q = 0; q < nh; ++q) {
    const uint32_t k = hit[q];
    const f8 dx = sx[k] - xr, dy = sy[k] - yr, dz = sz[k] - zr;
    const f8 w = ff_poly6(dx * dx + dy * dy + dz * dz, sr2[k], scoef[k]);
    float* a = acc + 32 * size_t(k);
    const f8 add[4] = {w, w * vxr, w * vyr, w * vzr};
    for (int j = 0; j < 4; ++j) {
      f8 v;
      std::memcpy(&v, a + 8 * j, sizeof v);
      v += add[j];
      std::memcpy(a + 8 * j, &v, sizeof v);
    }
  }
}
FF_SIMD_DISPATCH(scaleScatter)

// Control force sums of the fluid particles b .. e-1 (sorted positions, at
// most 8, one row of the fluid grid) as lanes, over the control particles
// hit[0 .. nh-1] (sorted positions in the control grid, ascending: those that
// some lane reaches, or more) broadcast one at a time: each lane sums as
// kernels/control_forces.cl does for its particle (a control particle that no
// lane reaches adds exactly 0 to every lane, as the kernel's any() skips it).
// out: 7 x 8 floats (attraction x, y, z, sum of W, sum of W v x, y, z).
struct ForceSumsArgs {
  const float *x, *y, *z;                            // the sorted fluid
  const float *sx, *sy, *sz, *ss, *svx, *svy, *svz;  // control particles in cp_grid order
  float r2, coef;                                    // eq. 4 and 6's kernel: P.r2 and P.coef
};
template <class>
FF_SIMD_BODY void forceSumsOf(const ForceSumsArgs& A, uint32_t b, uint32_t e, const uint32_t* hit, size_t nh,
                              float* out) {
  const int n = int(e - b);
  const f8 xe = simd::loadN(A.x + b, n, kFar), ye = simd::loadN(A.y + b, n, kFar),
           ze = simd::loadN(A.z + b, n, kFar);
  const float *sx = A.sx, *sy = A.sy, *sz = A.sz, r2 = A.r2;
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

void Controller::sortControl() {
  if (control_sorted_) return;  // nothing moved since the last sort
  control_sorted_ = true;
  const size_t n = set_.size();
  // Cells of radius / FF_CONTROL_GRID_DIVISIONS, over the container if bounded.
  const float cell = cp_.radius / float(FF_CONTROL_GRID_DIVISIONS);
  if (bounded_)
    cp_grid_.build(n, set_.x.data(), set_.y.data(), set_.z.data(), cell, lo_, hi_, gridCellCap(n));
  else
    cp_grid_.build(n, set_.x.data(), set_.y.data(), set_.z.data(), cell);
  const auto& order = cp_grid_.order();
  for (auto* a : {&sx_, &sy_, &sz_, &svx_, &svy_, &svz_, &sr2_, &scoef_}) a->resize(n);
  for (size_t k = 0; k < n; ++k) {
    const uint32_t i = order[k];
    sx_[k] = set_.x[i], sy_[k] = set_.y[i], sz_[k] = set_.z[i];
    svx_[k] = set_.vx[i], svy_[k] = set_.vy[i], svz_[k] = set_.vz[i];
    const float ri = ff_control_radius(cp_.radius, set_.radius_scale[i]);
    sr2_[k] = ri * ri, scoef_[k] = ff_poly6_coef(ri);
  }
}

void Controller::findPairs(const SortedFluid& sf) {
  // Every control particle reaches the control radius in eq. 4 and 6, its
  // own (adaptive control, at most that) in eq. 5.
  float most_scale = 1.0f;
  for (float v : set_.radius_scale) most_scale = std::max(most_scale, v);
  const float rc = ff_control_radius(cp_.radius, most_scale), rc2 = rc * rc;
  const std::vector<uint32_t>& groups = *sf.groups;
  const long ngroups = long(groups.size() / 2);
  hit_at_.resize(3 * size_t(ngroups));
  const int threads = omp_get_max_threads();
  if (hit_bufs_.size() < size_t(threads)) hit_bufs_.resize(size_t(threads));
  // The control particles in chunks of their sorted positions (computeScale):
  // each group's pairs are cut where a chunk begins.
  const size_t n = set_.size(), nch = std::min({n, 2 * size_t(threads), size_t(64)});
  chunks_ = nch;
  hit_cut_.resize((nch + 1) * size_t(ngroups));
  [[maybe_unused]] const bool wide = simd::hasAvx512();
  uint32_t firsts[64];  // chunk c's first sorted position
  for (size_t c = 0; c < nch; ++c) firsts[c] = uint32_t(c * n / nch);
#pragma omp parallel
  {
    const size_t t = size_t(omp_get_thread_num());
    std::vector<uint32_t>& buf = hit_bufs_[t];
    std::vector<uint32_t>& spans = threadSpans();
    size_t used = 0;
#pragma omp for schedule(dynamic, 16)
    for (long g = 0; g < ngroups; ++g) {
      const uint32_t b = groups[2 * size_t(g)], e = groups[2 * size_t(g) + 1];
      const size_t room = pairCandidateRoom(cp_grid_, sf.x, sf.y, sf.z, b, e, rc, spans);
      if (buf.size() < used + room) buf.resize(std::max(used + room, 2 * buf.size()));
      size_t nh;
#if FF_SIMD_AVX2
      if (wide)
        nh = pairCandidatesWide(spans, sf.x, sf.y, sf.z, b, e, sx_.data(), sy_.data(), sz_.data(), rc2,
                                buf.data() + used);
      else
#endif
        nh = pairCandidates(spans, sf.x, sf.y, sf.z, b, e, sx_.data(), sy_.data(), sz_.data(), rc2,
                            buf.data() + used);
      uint32_t* at = hit_at_.data() + 3 * size_t(g);
      at[0] = uint32_t(t), at[1] = uint32_t(used), at[2] = uint32_t(nh);
      uint32_t* cut = hit_cut_.data() + (nch + 1) * size_t(g);
      const uint32_t* h = buf.data() + used;
      // Cut c: the first pair with a control particle at or after chunk c's
      // first (the pairs ascend), the last cut after them all.
      for (size_t c = 0; c < nch; ++c) cut[c] = uint32_t(std::lower_bound(h, h + nh, firsts[c]) - h);
      cut[nch] = uint32_t(nh);
      used += nh;
    }
  }
  // Group g's pairs: hit_ptr_[g] .. hit_ptr_[g] + count.
  hit_ptr_.resize(size_t(ngroups));
  for (size_t g = 0; g < size_t(ngroups); ++g)
    hit_ptr_[g] = hit_bufs_[hit_at_[3 * g]].data() + hit_at_[3 * g + 1];
}

bool Controller::computeScale(const FluidView& f) {
  const size_t n = set_.size();
  pairs_ready_ = false;
  if (n == 0) return true;
  const SortedFluid sf = sorted(f);
  // The pairs of fluid and control particles within reach, found once from
  // the fluid's side; addForces reuses them.
  sortControl();
  findPairs(sf);
  pairs_ready_ = true, pairs_x_ = f.x, pairs_n_ = f.n;
  // Each control particle's sums, from the fluid groups in ascending order
  // (scaleScatter): the control particles in chunks of their sorted
  // positions, each chunk's sums added by one thread.
  const std::vector<uint32_t>& groups = *sf.groups;
  const long ngroups = long(groups.size() / 2);
  acc_.resize(32 * n);
  const long chunks = long(chunks_);
  const float* sv[5] = {sx_.data(), sy_.data(), sz_.data(), sr2_.data(), scoef_.data()};
#pragma omp parallel for schedule(dynamic, 1)
  for (long c = 0; c < chunks; ++c) {
    const uint32_t ca = uint32_t(size_t(c) * n / size_t(chunks)),
                   cb = uint32_t(size_t(c + 1) * n / size_t(chunks));
    std::fill(acc_.begin() + 32 * ptrdiff_t(ca), acc_.begin() + 32 * ptrdiff_t(cb), 0.0f);
    for (long g = 0; g < ngroups; ++g) {
      const uint32_t* cut = hit_cut_.data() + (size_t(chunks) + 1) * size_t(g) + c;  // chunk c's pairs
      if (cut[0] == cut[1]) continue;
      scaleScatter(f.n, sf.x, sf.y, sf.z, sf.vx, sf.vy, sf.vz, groups[2 * size_t(g)],
                   groups[2 * size_t(g) + 1], hit_ptr_[size_t(g)] + cut[0], size_t(cut[1] - cut[0]), sv[0],
                   sv[1], sv[2], sv[3], sv[4], acc_.data());
    }
  }
  const auto& order = cp_grid_.order();
  int bad = 0;
#pragma omp parallel for schedule(static) reduction(| : bad) if (long(n) > kParallelLightLoop)
  for (long k = 0; k < long(n); ++k) {
    const float* a = acc_.data() + 32 * k;
    auto total = [a](int j) {
      const float* v = a + 8 * j;
      return ff_lane_sum8(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]);
    };
    ff_float3 u;
    const float s = ff_control_scale_of(total(0), FF_F3(total(1), total(2), total(3)), f.volume, &u);
    const uint32_t i = order[size_t(k)];
    fields_.s[i] = s;
    fields_.ux[i] = u.x, fields_.uy[i] = u.y, fields_.uz[i] = u.z;
    bad |= std::isfinite(s) && std::isfinite(u.x) && std::isfinite(u.y) && std::isfinite(u.z) ? 0 : 1;
  }
  return !bad;
}

bool Controller::addForces(const FluidView& f, float dt, float* ax, float* ay, float* az) {
  const size_t n = set_.size();
  if (n == 0) return true;
  const SortedFluid sf = sorted(f);
  // The control particles in their grid's order, and the pairs within reach:
  // computeScale's, on this view with nothing moved since, else found anew.
  const bool reuse =
      pairs_ready_ && pairs_x_ == f.x && pairs_n_ == f.n && hit_at_.size() == 3 * (sf.groups->size() / 2);
  pairs_ready_ = false;
  if (!reuse) sortControl(), findPairs(sf);
  const auto& order = cp_grid_.order();
  ss_.resize(n);
  for (size_t k = 0; k < n; ++k) ss_[k] = fields_.s[order[k]];
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
  const ForceSumsArgs fs{sf.x,       sf.y,        sf.z,        sx_.data(),  sy_.data(), sz_.data(),
                         ss_.data(), svx_.data(), svy_.data(), svz_.data(), P.r2,       P.coef};
  int bad = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(| : bad)
  for (long g = 0; g < ngroups; ++g) {
    const uint32_t b = groups[2 * size_t(g)], e = groups[2 * size_t(g) + 1];
    float sums[56];
    forceSums(fs, b, e, hit_ptr_[size_t(g)], size_t(hit_at_[3 * size_t(g) + 2]), sums);
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
                        &set_.clusters.of, &fluid_groups_, &hit_at_, &hit_cut_})
    uints += v->capacity();
  for (const auto& v : hit_bufs_) uints += v.capacity();
  uints += hit_ptr_.capacity() * sizeof(const uint32_t*) / sizeof(uint32_t);
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
  pairs_ready_ = false, control_sorted_ = false;  // the control particles move
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
