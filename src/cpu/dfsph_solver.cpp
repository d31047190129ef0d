#include "cpu/dfsph_solver.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "cpu/lane_group.h"
#include "cpu/neighbour_cache.h"
#include "ff_dfsph.h"

namespace ff {

using simd::f8;

namespace {

// Share of the last substep's k that starts a solve, where the particle
// compresses again (SPlisHSPlasH's DFSPH: 1/2). Measured on a 10 x 30 x 10
// column (docs/PRESETS.md): a full warm start overshoots after a transient
// (the increments never take k back) and the column blows apart.
constexpr float kWarmStart = 0.5f;
// The divergence solve runs where a particle has at least this many
// neighbours, counting the wall's share as the neighbours of a full support
// it stands for (SPlisHSPlasH: 20 of about 33 at H = 2 spacings).
constexpr float kBulkShare = 0.6f;

struct Kernel {
  float h, inv_h, k, kg;
  explicit Kernel(float support)
      : h(support), inv_h(1.0f / support), k(ff_cubic_coef(support)), kg(k * inv_h * inv_h) {}
};

// w = sum_j W_ij, a = sum_j g r_ij, ssq = sum_j g^2 |r_ij|^2, the count of
// neighbours within H and rs = sum_j g (v_i - v_j).r_ij (the divergence
// solve's first sources, groupSources' walk on the velocities v) of the
// particles b .. e-1 (7 x 8 lanes), group gi. First keeps in `cache` the
// candidates that a lane reaches (a cheap test on r^2), then sums over those
// alone and stores their g: the candidates left out add exactly 0 to every
// sum (NeighbourCache). rs adds the same terms in the same order as
// groupSources' walk, so it is that walk's value bit for bit.
template <class Lanes>
FF_SIMD_BODY void factorSumsOf(const CpuFluid& f, size_t gi, uint32_t b, uint32_t e, const Kernel& kr,
                               float* out, NeighbourCache& cache) {
  const FluidState& s = f.s;
  std::vector<uint32_t>& spans = threadSpans();
  Group g;
  loadGroup(s, b, e, kr.h, f.grid, g, spans);
  const float *x = s.x.data(), *y = s.y.data(), *z = s.z.data();
  const float *vx = s.vx.data(), *vy = s.vy.data(), *vz = s.vz.data();
  const f8 uxi = simd::loadN(&vx[b], g.n, 0.0f), uyi = simd::loadN(&vy[b], g.n, 0.0f),
           uzi = simd::loadN(&vz[b], g.n, 0.0f);
  const float h2 = kr.h * kr.h;
  const f8 reach2 = simd::splat(cache.reach2());
  size_t most = 0;
  for (size_t r = 0; r < spans.size(); r += 2) most += spans[r + 1] - spans[r];
  NeighbourCache::Writer list = cache.open(most);
  for (size_t r = 0; r < spans.size(); r += 2) {
    // The range's ends as locals: list.put's stores could alias spans.
    const uint32_t jb = spans[r], je = spans[r + 1];
#pragma GCC unroll 4
    for (uint32_t j = jb; j < je; ++j) {
      const f8 dx = g.x - x[j], dy = g.y - y[j], dz = g.z - z[j];
      list.put(j, Lanes::any(dx * dx + dy * dy + dz * dz < reach2));
    }
  }
  const f8 zero = simd::splat(0.0f), one = simd::splat(1.0f);
  f8 w = zero, ax = zero, ay = zero, az = zero, ssq = zero, cnt = zero, rs = zero;
  // The kernel's constants as locals: list.value's stores could alias kr,
  // which kept the compiler from hoisting its loads and products out of the
  // loop (the same values and operations either way).
  const float inv_h = kr.inv_h, kk = kr.k, kg = kr.kg;
  const size_t m = list.size();
  // Two passes over the list, each sum's terms in the same order as one pass
  // (the build contracts no products into fmas, so a recomputed r_ij and r^2
  // are the same bits): with the seven sums, the kernel and the velocities in
  // one loop GCC spilled five of the seven to the stack each candidate. The
  // first pass takes the square root, the kernel and the gradient's factor g,
  // which it stores in the list; the second reads g back.
  for (size_t q = 0; q < m; ++q) {
    const uint32_t j = list.index(q);
    const f8 dx = g.x - x[j], dy = g.y - y[j], dz = g.z - z[j];
    const f8 r2 = dx * dx + dy * dy + dz * dz;
    const f8 dist = simd::sqrt8(r2);
    w += ff_cubic(dist, inv_h, kk);
    cnt += r2 < h2 ? one : zero;
    list.value(q, ff_cubic_grad_factor(dist, inv_h, kg));
  }
  for (size_t q = 0; q < m; ++q) {
    const uint32_t j = list.index(q);
    const f8 dx = g.x - x[j], dy = g.y - y[j], dz = g.z - z[j];
    const f8 r2 = dx * dx + dy * dy + dz * dz;
    const f8 gf = list.valueAt(q);
    ax += gf * dx, ay += gf * dy, az += gf * dz;
    ssq += gf * gf * r2;
    rs += gf * ((uxi - vx[j]) * dx + (uyi - vy[j]) * dy + (uzi - vz[j]) * dz);
  }
  cache.close(gi, list);
  const f8 sums[7] = {w, ax, ay, az, ssq, cnt, rs};
  for (int q = 0; q < 7; ++q) simd::storeN(out + 8 * q, sums[q], g.n);
}
FF_SIMD_DISPATCH(factorSums)

// Where the density phase writes each particle's factor and its parts.
struct FactorOut {
  float *alpha, *wgx, *wgy, *wgz, *wall, *vax, *vay, *vaz, *q;
};

// The density phase at the particles b .. e-1 from their sums (factorSums'
// 6 x 8 lanes) on 8 lanes: the walls' share S(x) and gradient
// (ff_dfsph_wall_of, skipped where no lane is in a wall's reach: S and
// grad S are +0 there, the bits it gives) and ff_dfsph_factor_of, as
// ff_dfsph_factor_parts does for one particle. Writes rho / rho0 to rho_hat.
template <class Lanes>
FF_SIMD_BODY void factorPartsOf(const CpuFluid& f, uint32_t b, uint32_t e, const float* sums, const float* lo,
                                const float* hi, float spacing, const Kernel& kr, float vol, float eps,
                                float* rho_hat, const FactorOut& o) {
  const Group g = lanesOf(f.s, b, e);
  const int n = g.n;
  const f8 zero = simd::splat(0.0f);
  f8 share = zero, wg[3] = {zero, zero, zero};
  const f8 reach = ff_dfsph_wall_reach(g.x, g.y, g.z, lo, hi, spacing, kr.h);
  if (Lanes::any((reach != 0.0f) & simd::liveLanes(n)))
    share = ff_dfsph_wall_of(g.x, g.y, g.z, lo, hi, spacing, vol, kr.h, kr.inv_h, wg);
  f8 sum[6];
  for (int q = 0; q < 6; ++q) std::memcpy(&sum[q], sums + 8 * q, sizeof sum[q]);
  const f8 a[3] = {sum[1], sum[2], sum[3]};
  f8 rh, va[3], q;
  const f8 alpha = ff_dfsph_factor_of(share, wg, vol, sum[0], a, sum[4], eps, &rh, va, &q);
  simd::storeN(rho_hat, rh, n);
  simd::storeN(o.alpha + b, alpha, n), simd::storeN(o.wall + b, share, n), simd::storeN(o.q + b, q, n);
  simd::storeN(o.wgx + b, wg[0], n), simd::storeN(o.wgy + b, wg[1], n), simd::storeN(o.wgz + b, wg[2], n);
  simd::storeN(o.vax + b, va[0], n), simd::storeN(o.vay + b, va[1], n), simd::storeN(o.vaz + b, va[2], n);
}
FF_SIMD_DISPATCH(factorParts)

// What the sources of a solve read and write (DfsphSolver::sources).
struct SourceArgs {
  const float *ux, *uy, *uz;                // the velocities the sources measure
  const float *wgx, *wgy, *wgz, *alpha;     // the density phase's grad S(x) and factor
  const float *x, *y, *z, *rho;             // positions and densities
  const float *wall, *vax, *vay, *vaz, *q;  // the density phase's S(x) and factor parts
  const uint8_t* bulk;                      // support filled (the divergence solve)
  const float* rs;                          // the walk's sums if known (else walks)
  float *b, *inc, *wpx, *wpy, *wpz;         // the sources, increments, walls' gradient at x + dt u
  float lo[3], hi[3];
  float vol, spacing, H, inv_h, eps, inv_rho0, dt;
  bool density;
};

// The sources b and next increments of the particles b .. e-1 (group gi):
// rs = sum_j g (u_i - u_j).r_ij over the cached candidates (the grid walk's
// terms in its order; a.rs's where given: factorSums' on the same
// velocities), then the rate and source per lane (ff_dfsph_rate_of,
// ff_dfsph_density_source or ff_dfsph_divergence_source,
// ff_dfsph_increment). Where a lane is near a wall
// (ff_dfsph_wall_near_axis) its density source is
// ff_dfsph_density_source_wall, as in ff_dfsph_density_source_at, on the
// group's 8 lanes.
template <class Lanes>
FF_SIMD_BODY void groupSourcesOf(const CpuFluid& f, const NeighbourCache& nc, size_t gi, uint32_t b,
                                 uint32_t e, const SourceArgs& a) {
  const FluidState& s = f.s;
  const Group g = lanesOf(s, b, e);
  const float *x = s.x.data(), *y = s.y.data(), *z = s.z.data();
  const float *ux = a.ux, *uy = a.uy, *uz = a.uz;
  const f8 uxi = simd::loadN(&ux[b], g.n, 0.0f), uyi = simd::loadN(&uy[b], g.n, 0.0f),
           uzi = simd::loadN(&uz[b], g.n, 0.0f);
  const int n = g.n;
  f8 rs = simd::splat(0.0f);
  if (a.rs) {
    rs = simd::loadN(&a.rs[b], n, 0.0f);
  } else {
    const uint32_t* js = nc.neighbours(gi);
    const float* gs = nc.values(gi);
    const uint32_t m = nc.count(gi);
#pragma GCC unroll 4
    for (uint32_t q = 0; q < m; ++q) {
      const uint32_t j = js[q];
      const f8 dx = g.x - x[j], dy = g.y - y[j], dz = g.z - z[j];
      f8 gf;
      std::memcpy(&gf, gs + 8 * size_t(q), sizeof gf);
      rs += gf * ((uxi - ux[j]) * dx + (uyi - uy[j]) * dy + (uzi - uz[j]) * dz);
    }
  }
  const f8 gx = simd::loadN(&a.wgx[b], n, 0.0f), gy = simd::loadN(&a.wgy[b], n, 0.0f),
           gz = simd::loadN(&a.wgz[b], n, 0.0f), alpha = simd::loadN(&a.alpha[b], n, 0.0f);
  const f8 rate = ff_dfsph_rate_of(rs, a.vol, uxi, uyi, uzi, gx, gy, gz);
  if (!a.density) {
    f8 bulk;
    for (int l = 0; l < 8; ++l) bulk[l] = l < n ? float(a.bulk[b + uint32_t(l)]) : 0.0f;
    const f8 bs = ff_dfsph_divergence_source(rate, bulk);
    simd::storeN(&a.b[b], bs, n);
    simd::storeN(&a.inc[b], ff_dfsph_increment(bs, alpha), n);
    return;
  }
  const f8 rho_hat = simd::loadN(&a.rho[b], n, 0.0f) * a.inv_rho0;
  f8 bs = ff_dfsph_density_source(rho_hat, rate, a.dt), al = alpha;
  f8 wp[3] = {gx, gy, gz};
  const f8 near_sum = ff_dfsph_wall_near_axis(g.x, uxi, a.dt, a.lo[0], a.hi[0], a.H) +
                      ff_dfsph_wall_near_axis(g.y, uyi, a.dt, a.lo[1], a.hi[1], a.H) +
                      ff_dfsph_wall_near_axis(g.z, uzi, a.dt, a.lo[2], a.hi[2], a.H);
  const simd::i8 near = (near_sum != 0.0f) & simd::liveLanes(n);
  if (Lanes::any(near)) {
    // The density after dt, with the walls' share at x + dt u, and the
    // walls' gradient and the factor there for this iteration's push.
    const f8 va[3] = {simd::loadN(&a.vax[b], n, 0.0f), simd::loadN(&a.vay[b], n, 0.0f),
                      simd::loadN(&a.vaz[b], n, 0.0f)};
    f8 g1[3], a1;
    const f8 b1 = ff_dfsph_density_source_wall(
        g.x, g.y, g.z, uxi, uyi, uzi, rho_hat, rate, a.dt, wp, simd::loadN(&a.wall[b], n, 0.0f), va,
        simd::loadN(&a.q[b], n, 0.0f), a.eps, a.lo, a.hi, a.spacing, a.vol, a.H, a.inv_h, g1, &a1);
    bs = near ? b1 : bs, al = near ? a1 : al;
    for (int c = 0; c < 3; ++c) wp[c] = near ? g1[c] : wp[c];
  }
  simd::storeN(&a.b[b], bs, n);
  simd::storeN(&a.inc[b], ff_dfsph_increment(bs, al), n);  // the next iteration's, if there is one
  simd::storeN(&a.wpx[b], wp[0], n), simd::storeN(&a.wpy[b], wp[1], n), simd::storeN(&a.wpz[b], wp[2], n);
}
FF_SIMD_DISPATCH(groupSources)

// ks = sum_j g (k_i + k_j) r_ij of the particles b .. e-1 (group gi; 3 x 8
// lanes), over the cached candidates.
template <class>
FF_SIMD_BODY void kappaSumsOf(const CpuFluid& f, const NeighbourCache& nc, size_t gi, const float* k,
                              uint32_t b, uint32_t e, float* out) {
  const FluidState& s = f.s;
  const Group g = lanesOf(s, b, e);
  const float *x = s.x.data(), *y = s.y.data(), *z = s.z.data();
  const f8 ki = simd::loadN(&k[b], g.n, 0.0f);
  const uint32_t* js = nc.neighbours(gi);
  const float* gs = nc.values(gi);
  const uint32_t m = nc.count(gi);
  const f8 zero = simd::splat(0.0f);
  f8 kx = zero, ky = zero, kz = zero;
#pragma GCC unroll 4
  for (uint32_t q = 0; q < m; ++q) {
    const uint32_t j = js[q];
    const f8 dx = g.x - x[j], dy = g.y - y[j], dz = g.z - z[j];
    f8 gf;
    std::memcpy(&gf, gs + 8 * size_t(q), sizeof gf);
    const f8 c = gf * (ki + k[j]);
    kx += c * dx, ky += c * dy, kz += c * dz;
  }
  const f8 sums[3] = {kx, ky, kz};
  for (int q = 0; q < 3; ++q) simd::storeN(out + 8 * q, sums[q], g.n);
}
FF_SIMD_DISPATCH(kappaSums)

using Clock = std::chrono::steady_clock;

// Adds the time since t0 to the stage `name` of `phase`.
void record(std::vector<StageTime>& stages, const char* phase, const char* name, Clock::time_point t0) {
  addStages(stages, {{phase, name, std::chrono::duration<double, std::milli>(Clock::now() - t0).count()}});
}

void box(const ContainerDesc& c, float* lo, float* hi) {
  for (int d = 0; d < 3; ++d) lo[d] = c.min[d], hi[d] = c.max[d];
}

}  // namespace

bool DfsphSolver::computeDensity(CpuFluid& f, const FluidParams& p, const ContainerDesc& c) {
  const size_t n = f.size();
  f.rho.resize(n), f.p.resize(n);
  for (auto* a : {&alpha_, &wgx_, &wgy_, &wgz_, &wall_, &vax_, &vay_, &vaz_, &q_}) a->resize(n);
  bulk_.resize(n), rs_.resize(n);
  if (kd_.size() != n) kd_.assign(n, 0.0f), kv_.assign(n, 0.0f);
  const Kernel kr(p.smoothing_radius);
  if (vol_spacing_ != p.restSpacing() || vol_h_ != kr.h) {
    vol_spacing_ = p.restSpacing(), vol_h_ = kr.h;
    vol_ = ff_dfsph_lattice_volume(vol_spacing_, kr.h);
  }
  // The neighbours of a full support in the rest lattice.
  const float full = 4.18879f * kr.h * kr.h * kr.h / vol_;
  const float eps = ff_dfsph_eps(kr.inv_h);
  const float rho0 = p.rest_density, vol = vol_;
  float lo[3], hi[3];
  box(c, lo, hi);
  const long groups = long(f.groups.size() / 2);
  const Clock::time_point t0 = Clock::now();
  const int threads = cache_.reset(size_t(groups), kr.h);
  const FactorOut out{alpha_.data(), wgx_.data(), wgy_.data(), wgz_.data(), wall_.data(),
                      vax_.data(),   vay_.data(), vaz_.data(), q_.data()};
  // Each thread fills the lists of the groups it will walk: the last
  // substep's parts, where their first particles stood (the particles moved
  // little), with forEachGroupInParts' help where that misses.
  fillParts(f.groups, threads);
  const bool finite = forEachGroupInParts(fill_parts_, f.groups, [&](size_t gi, uint32_t b, uint32_t e) {
    float sums[56];
    factorSums(f, gi, b, e, kr, sums, cache_);
    float rho_hat[8];
    factorParts(f, b, e, sums, lo, hi, vol_spacing_, kr, vol, eps, rho_hat, out);
    bool ok = true;
    for (uint32_t i = b; i < e; ++i) {
      const size_t l = i - b;
      f.rho[i] = rho0 * rho_hat[l];
      rs_[i] = sums[48 + l];
      const float share = rho_hat[l] - vol * sums[l];  // the walls' share
      bulk_[i] = uint8_t(ff_dfsph_bulk(sums[40 + l], share, full, kBulkShare));
      ok = ok && std::isfinite(f.rho[i]) && std::isfinite(alpha_[i]);
    }
    return ok;
  });
  cache_.split(threads);
  split_at_.resize(cache_.parts().size());
  for (size_t k = 0; k < split_at_.size(); ++k) {
    const size_t g = cache_.parts()[k];
    split_at_[k] = g < size_t(groups) ? f.groups[2 * g] : uint32_t(n);
  }
  cache_current_ = true, rs_current_ = true;
  record(stages_, "density", "dfsph factor + neighbour cache", t0);
  return finite;
}

void DfsphSolver::fillParts(const std::vector<uint32_t>& groups, int threads) {
  const size_t count = groups.size() / 2;
  fill_parts_.assign(size_t(threads) + 1, count);
  fill_parts_[0] = 0;
  const bool known = split_at_.size() == fill_parts_.size();
  for (size_t k = 1; k < size_t(threads); ++k) {
    if (!known) {
      fill_parts_[k] = count * k / size_t(threads);
      continue;
    }
    // The first group that starts at or after the part's first particle.
    size_t lo = fill_parts_[k - 1], hi = count;
    while (lo < hi) {
      const size_t mid = (lo + hi) / 2;
      if (groups[2 * mid] < split_at_[k])
        lo = mid + 1;
      else
        hi = mid;
    }
    fill_parts_[k] = lo;
  }
}

double DfsphSolver::sources(const CpuFluid& f, bool density, float dt, const float* rs, float* warm_k,
                            float warm, bool* warmed) {
  const long n = long(f.size());
  const FluidState& s = f.s;
  SourceArgs a;
  a.ux = ux_.data(), a.uy = uy_.data(), a.uz = uz_.data();
  a.wgx = wgx_.data(), a.wgy = wgy_.data(), a.wgz = wgz_.data(), a.alpha = alpha_.data();
  a.x = s.x.data(), a.y = s.y.data(), a.z = s.z.data(), a.rho = f.rho.data();
  a.wall = wall_.data(), a.vax = vax_.data(), a.vay = vay_.data(), a.vaz = vaz_.data(), a.q = q_.data();
  a.bulk = bulk_.data(), a.rs = rs;
  a.b = b_.data(), a.inc = inc_.data(), a.wpx = wpx_.data(), a.wpy = wpy_.data(), a.wpz = wpz_.data();
  for (int d = 0; d < 3; ++d) a.lo[d] = lo_[d], a.hi[d] = hi_[d];
  a.vol = vol_, a.spacing = vol_spacing_, a.H = vol_h_, a.inv_h = 1.0f / vol_h_,
  a.eps = ff_dfsph_eps(a.inv_h);
  a.inv_rho0 = 1.0f / rho0_, a.dt = dt, a.density = density;
  // The sum of b by group and the warm start in the same pass (b still in
  // cache), then the sum over the groups in their order: the same sum
  // whatever the threads.
  group_b_.resize(f.groups.size() / 2);
  double* const gb = group_b_.data();
  std::atomic<bool> any{false};
  forEachGroupInParts(cache_.parts(), f.groups, [&](size_t gi, uint32_t b, uint32_t e) {
    groupSources(f, cache_, gi, b, e, a);
    double sum = 0.0;
    for (uint32_t i = b; i < e; ++i) sum += double(a.b[i]);
    gb[gi] = sum;
    if (!warm_k) return true;
    bool nonzero = false;
    for (uint32_t i = b; i < e; ++i) {
      warm_k[i] = ff_dfsph_warm_start(warm_k[i], a.b[i], warm);
      nonzero |= warm_k[i] != 0.0f;
    }
    if (nonzero) any.store(true, std::memory_order_relaxed);
    return true;
  });
  if (warmed) *warmed = any.load(std::memory_order_relaxed);
  double err = 0.0;
  for (const double g : group_b_) err += g;
  return n ? err / double(n) : 0.0;
}

void DfsphSolver::applyVelocityChange(const CpuFluid& f, bool density, const std::vector<float>& k,
                                      float scale, std::vector<float>* total) {
  const float inv = 1.0f / scale;
  const float *gx = density ? wpx_.data() : wgx_.data(), *gy = density ? wpy_.data() : wgy_.data(),
              *gz = density ? wpz_.data() : wgz_.data();
  // As locals: the epilogue's stores could alias inv and vol_, which were
  // reloaded per particle (the same values and operations).
  float* const tot = total ? total->data() : nullptr;
  const float* const kp = k.data();
  float *const ux = ux_.data(), *const uy = uy_.data(), *const uz = uz_.data();
  const float vol = vol_;
  forEachGroupInParts(cache_.parts(), f.groups, [&](size_t gi, uint32_t b, uint32_t e) {
    float ks[24];
    kappaSums(f, cache_, gi, kp, b, e, ks);
    const float iv = inv, v = vol;
    for (uint32_t i = b; i < e; ++i) {
      const size_t l = i - b;
      const float sum[3] = {ks[l], ks[8 + l], ks[16 + l]}, wg[3] = {gx[i], gy[i], gz[i]};
      float du[3];
      ff_dfsph_velocity_change(sum, kp[i], v, wg, du);
      ux[i] += du[0] * iv, uy[i] += du[1] * iv, uz[i] += du[2] * iv;
      if (tot) tot[i] += kp[i];
    }
    return true;
  });
}

int DfsphSolver::iterate(const CpuFluid& f, const FluidParams& p, bool density, float dt, double tol,
                         int min_iterations, float warm, std::vector<float>& k) {
  const float scale = density ? dt : 1.0f;
  // The divergence solve's first sources: on the velocities of the density
  // phase, whose walk summed them already (factorSums), unless the particles
  // were reordered since.
  const bool known = !density && rs_current_;
  rs_current_ = false;
  // Warm start (in the sources' pass): the last substep's k where this one
  // compresses too. Where that is 0 for every particle (a divergence solve
  // that has not iterated since k last came to 0, say), its velocity change
  // is 0 and the sources after it are the first ones: both walks are
  // skipped, for the same bits.
  bool warmed = false;
  double err = sources(f, density, dt, known ? rs_.data() : nullptr, k.data(), warm, &warmed);
  if (warmed) {
    applyVelocityChange(f, density, k, scale, nullptr);
    err = sources(f, density, dt);
  } else {
    ++(density ? cold_starts_[0] : cold_starts_[1]);
  }
  int it = 0;
  for (;;) {
    if (it >= min_iterations && err <= tol) break;
    if (it >= p.max_iterations) {
      ++stats_.capped;
      break;
    }
    // One Jacobi iteration: the increment that removes each particle's
    // remaining compression on its own (sources() set it), added to k and
    // applied to the velocities.
    applyVelocityChange(f, density, inc_, scale, &k);
    err = sources(f, density, dt);
    ++it;
  }
  stats_.iterations += it;
  return it;
}

bool DfsphSolver::solve(CpuFluid& f, const FluidParams& p, const ContainerDesc& c, float dt) {
  const long n = long(f.size());
  if (alpha_.size() != size_t(n) || cache_.groups() != f.groups.size() / 2)
    throw Error("dfsph: the pressure phase ran before the density phase");
  if (n == 0) return true;
  FluidState& s = f.s;
  for (auto* a : {&b_, &inc_, &wpx_, &wpy_, &wpz_}) a->resize(size_t(n));
  rho0_ = p.rest_density;
  box(c, lo_, hi_);
  ux_ = s.vx, uy_ = s.vy, uz_ = s.vz;
  // k scales as the pressure times dt^2 (density) or dt (divergence).
  const float ratio = last_dt_ > 0.0f ? dt / last_dt_ : 1.0f;
  last_dt_ = dt;
  // Divergence-free solve on the velocities of the last substep.
  Clock::time_point t0 = Clock::now();
  last_div_ = iterate(f, p, false, dt, double(p.divergence_tolerance) / double(dt),
                      p.divergence_min_iterations, kWarmStart * ratio, kv_);
  record(stages_, "pressure", "divergence solve", t0);
  t0 = Clock::now();
  // Every other acceleration of the substep and the walls' support in the
  // pressure gradient it causes, then the constant-density solve.
  float lo[3], hi[3];
  box(c, lo, hi);
  const float spacing = vol_spacing_, H = vol_h_, inv_h = 1.0f / H, vol = vol_;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const size_t q = size_t(i);
    const float pos[3] = {s.x[q], s.y[q], s.z[q]}, acc[3] = {f.ax[q], f.ay[q], f.az[q]};
    float u[3] = {ux_[q], uy_[q], uz_[q]};
    ff_dfsph_predict(pos, lo, hi, spacing, vol, H, inv_h, acc, dt, u);
    ux_[q] = u[0], uy_[q] = u[1], uz_[q] = u[2];
  }
  last_dens_ = iterate(f, p, true, dt, double(p.density_tolerance), 2, kWarmStart * ratio * ratio, kd_);
  record(stages_, "pressure", "density solve", t0);
  // The accelerations that take v to the solved velocities, and the pressure
  // p = rho0 (kd / dt^2 + kv / dt) of both solves.
  const float inv_dt = 1.0f / dt, rho0 = rho0_;
  int bad = 0;
#pragma omp parallel for schedule(static) reduction(| : bad)
  for (long i = 0; i < n; ++i) {
    const size_t q = size_t(i);
    f.ax[q] = (ux_[q] - s.vx[q]) * inv_dt, f.ay[q] = (uy_[q] - s.vy[q]) * inv_dt,
    f.az[q] = (uz_[q] - s.vz[q]) * inv_dt;
    f.p[q] = ff_dfsph_pressure(kd_[q], kv_[q], inv_dt, rho0);
    bad |= std::isfinite(f.ax[q]) && std::isfinite(f.ay[q]) && std::isfinite(f.az[q]) && std::isfinite(f.p[q])
               ? 0
               : 1;
  }
  return !bad;
}

void DfsphSolver::reorder(const std::vector<uint32_t>& order) {
  cache_current_ = false, rs_current_ = false;
  if (kd_.size() != order.size()) return;  // sized at the next density phase
  permute(kd_, order, scratch_);
  permute(kv_, order, scratch_);
}

void DfsphSolver::saveState(StateWriter& w) const {
  w.vec(kd_);
  w.vec(kv_);
  w.pod(last_dt_);  // the warm start scales k by the change of dt
}

void DfsphSolver::loadState(StateReader& r, size_t n) {
  std::vector<float> kd, kv;
  r.vec(kd);
  r.vec(kv);
  const float last_dt = r.pod<float>();
  r.check(std::isfinite(last_dt) && last_dt >= 0.0f, "its DFSPH substep is not a finite time >= 0");
  r.check((kd.empty() || kd.size() == n) && kd.size() == kv.size(),
          "its DFSPH state does not match its " + std::to_string(n) + " fluid particles");
  kd_ = std::move(kd), kv_ = std::move(kv);
  last_dt_ = last_dt;
}

size_t DfsphSolver::memoryBytes() const {
  size_t floats = 0;
  for (const auto* v : {&alpha_, &wgx_, &wgy_, &wgz_, &wall_, &vax_, &vay_, &vaz_, &q_,       &wpx_, &wpy_,
                        &wpz_,   &kd_,  &kv_,  &b_,   &inc_,  &ux_,  &uy_,  &uz_,  &scratch_, &rs_})
    floats += v->capacity();
  return floats * sizeof(float) + group_b_.capacity() * sizeof(double) + bulk_.capacity() +
         cache_.memoryBytes();
}

}  // namespace ff
