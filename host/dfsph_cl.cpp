#include "host/dfsph_cl.h"

#include <algorithm>
#include <chrono>

#include "core/error.h"
#include "host/backend_opencl_impl.h"

namespace ff {

namespace {

// As src/cpu/dfsph_solver.cpp (the equivalence tests fail if they part).
constexpr float kWarmStart = 0.5f;
constexpr float kBulkShare = 0.6f;

// Work-groups of the sources' reduction (at most 64 partial sums for dfsph_check).
size_t sourceGroups(size_t n, size_t local) {
  const size_t g = (n + local - 1) / local;
  return g < 1 ? 1 : (g > 64 ? 64 : g);
}

double nowMs() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

ClDfsphSolver::ClDfsphSolver(const cl::Program& program, const ClContext& ctx) {
  factor_ = makeKernel(program, "dfsph_factor", ctx);
  factor_lanes_ = makeKernel(program, "dfsph_factor_lanes", ctx, kLaneGroupCap);
  rate_ = makeKernel(program, "dfsph_rate", ctx);
  rate_lanes_ = makeKernel(program, "dfsph_rate_lanes", ctx, kLaneGroupCap);
  kappa_ = makeKernel(program, "dfsph_kappa", ctx);
  kappa_lanes_ = makeKernel(program, "dfsph_kappa_lanes", ctx, kLaneGroupCap);
  source_ = makeKernel(program, "dfsph_source", ctx, 256, sizeof(double));
  check_ = makeKernel(program, "dfsph_check", ctx);
  warm_ = makeKernel(program, "dfsph_warm", ctx);
  increment_ = makeKernel(program, "dfsph_increment", ctx);
  apply_ = makeKernel(program, "dfsph_apply", ctx);
  predict_ = makeKernel(program, "dfsph_predict", ctx);
  finish_ = makeKernel(program, "dfsph_finish", ctx);
  reorder_ = makeKernel(program, "dfsph_reorder", ctx);
  state_.ensure(ctx.context(), 4 * sizeof(cl_int));
  partial_.ensure(ctx.context(), 64 * sizeof(double));
}

void ClDfsphSolver::ensure(const ClFluidRefs& f) {
  if (sized_ && n_ == f.n) return;
  const cl::Context& c = *f.context;
  cl::CommandQueue& q = *f.queue;
  n_ = f.n;
  const size_t bytes = padded8(n_) * sizeof(float);
  for (DeviceBuffer* b :
       {&alpha_, &wgx_, &wgy_, &wgz_,     &vax_,     &vay_,     &vaz_,      &q_,      &wall_,
        &wpx_,   &wpy_, &wpz_, &alpha_p_, &inc_,     &b_,       &rate_buf_, &dux_,    &duy_,
        &duz_,   &ux_,  &uy_,  &uz_,      &k_[0][0], &k_[0][1], &k_[1][0],  &k_[1][1]})
    b->ensure(c, bytes);
  bulk_.ensure(c, padded8(n_));
  // k starts at 0 (as the OpenMP solver's); the 8-wide loads read the
  // padding of k and u (masked, but it must hold numbers).
  for (DeviceBuffer* b : {&inc_, &ux_, &uy_, &uz_, &k_[0][0], &k_[0][1], &k_[1][0], &k_[1][1]})
    fillBuffer(q, *b, 0.0f, padded8(n_));
  kcur_ = 0;
  sized_ = true;
}

void ClDfsphSolver::record(const ClFluidRefs& f, const char* phase, const char* name, double* t0) {
  if (!profiling_) return;
  finishQueue(*f.queue);
  const double t = nowMs();
  addStages(stages_, {{phase, name, t - *t0}});
  *t0 = t;
}

void ClDfsphSolver::computeDensity(const ClFluidRefs& f, const FluidParams& p, const ContainerDesc& box,
                                   int tag) {
  ensure(f);
  if (f.n == 0) return;
  double t0 = nowMs();
  FfDfsphArgs& a = args_;
  a.h = p.smoothing_radius;
  a.inv_h = 1.0f / a.h;
  a.k = ff_cubic_coef(a.h);
  a.kg = a.k * a.inv_h * a.inv_h;
  if (vol_spacing_ != p.restSpacing() || vol_h_ != a.h) {
    vol_spacing_ = p.restSpacing(), vol_h_ = a.h;
    vol_ = ff_dfsph_lattice_volume(vol_spacing_, a.h);
  }
  a.vol = vol_, a.spacing = vol_spacing_;
  a.full = 4.18879f * a.h * a.h * a.h / vol_;
  a.eps = ff_dfsph_eps(a.inv_h);
  a.bulk_share = kBulkShare;
  a.rho0 = p.rest_density;
  a.cell = f.grid->geom.cell;
  for (int d = 0; d < 3; ++d) a.lo[d] = box.min[d], a.hi[d] = box.max[d];
  a.lo[3] = a.hi[3] = 0.0f;
  const DeviceGrid& g = *f.grid;
  if (f.lanes)
    launch(*f.queue, factor_lanes_, padded8(f.n) / 8, *f.x, *f.y, *f.z, cl_uint(f.n), g.start.get(),
           g.geom.geo(), g.geom.dims(), a, *f.rho, alpha_.get(), wgx_.get(), wgy_.get(), wgz_.get(),
           vax_.get(), vay_.get(), vaz_.get(), q_.get(), wall_.get(), bulk_.get(), *f.bad, cl_int(tag));
  else
    launch(*f.queue, factor_, f.n, *f.x, *f.y, *f.z, cl_uint(f.n), g.start.get(), g.geom.geo(), g.geom.dims(),
           a, *f.rho, alpha_.get(), wgx_.get(), wgy_.get(), wgz_.get(), vax_.get(), vay_.get(), vaz_.get(),
           q_.get(), wall_.get(), bulk_.get(), *f.bad, cl_int(tag));
  record(f, "density", "dfsph factor", &t0);
}

void ClDfsphSolver::sources(const ClFluidRefs& f, bool density, float dt, bool gated) {
  const DeviceGrid& g = *f.grid;
  launch(*f.queue, f.lanes ? rate_lanes_ : rate_, f.lanes ? padded8(f.n) / 8 : f.n, *f.x, *f.y, *f.z,
         cl_uint(f.n), g.start.get(), g.geom.geo(), g.geom.dims(), args_, ux_.get(), uy_.get(), uz_.get(),
         wgx_.get(), wgy_.get(), wgz_.get(), rate_buf_.get(), state_.get(), cl_int(gated));
  const size_t local = source_.pow2_local, groups = sourceGroups(f.n, local);
  launchGroups(*f.queue, source_, groups, local, rate_buf_.get(), *f.rho, bulk_.get(), *f.x, *f.y, *f.z,
               ux_.get(), uy_.get(), uz_.get(), args_, cl_uint(f.n), cl_int(density), 1.0f / rho0_, dt,
               b_.get(), partial_.get(), cl::Local(local * sizeof(double)), state_.get(), cl_int(gated),
               alpha_.get(), wgx_.get(), wgy_.get(), wgz_.get(), vax_.get(), vay_.get(), vaz_.get(), q_.get(),
               wall_.get(), wpx_.get(), wpy_.get(), wpz_.get(), alpha_p_.get());
}

void ClDfsphSolver::applyVelocityChange(const ClFluidRefs& f, bool density, const DeviceBuffer& k,
                                        float scale, bool gated) {
  const DeviceGrid& g = *f.grid;
  const DeviceBuffer &gx = density ? wpx_ : wgx_, &gy = density ? wpy_ : wgy_, &gz = density ? wpz_ : wgz_;
  launch(*f.queue, f.lanes ? kappa_lanes_ : kappa_, f.lanes ? padded8(f.n) / 8 : f.n, *f.x, *f.y, *f.z,
         cl_uint(f.n), g.start.get(), g.geom.geo(), g.geom.dims(), args_, k.get(), gx.get(), gy.get(),
         gz.get(), dux_.get(), duy_.get(), duz_.get(), state_.get(), cl_int(gated));
  launch(*f.queue, apply_, f.n, ux_.get(), uy_.get(), uz_.get(), dux_.get(), duy_.get(), duz_.get(),
         cl_uint(f.n), 1.0f / scale, state_.get(), cl_int(gated));
}

int ClDfsphSolver::iterate(const ClFluidRefs& f, const FluidParams& p, bool density, float dt, double tol,
                           int min_iterations, float warm, int which) {
  cl::CommandQueue& q = *f.queue;
  const float scale = density ? dt : 1.0f;
  const DeviceBuffer& k = k_[kcur_][which];
  const size_t groups = sourceGroups(f.n, source_.pow2_local);
  const float tol_hi = float(tol), tol_lo = float(tol - double(tol_hi));
  fillBuffer(q, state_, cl_int(0), 4);
  // Warm start where the particle compresses now, then the first test.
  sources(f, density, dt, false);
  launch(q, warm_, f.n, k.get(), b_.get(), cl_uint(f.n), warm);
  applyVelocityChange(f, density, k, scale, false);
  sources(f, density, dt, false);
  auto check = [&](int first) {
    launchGroups(q, check_, 1, 1, partial_.get(), cl_uint(groups), cl_uint(f.n), tol_hi, tol_lo,
                 cl_int(min_iterations), cl_int(p.max_iterations), cl_int(first), state_.get());
  };
  check(1);
  cl_int st[4] = {0, 0, 0, 0};
  // The first batch is the iterations every solve runs (min_iterations; a
  // solve stops there most often), the later ones kIterationBatch. With no
  // iterations allowed the solve stops at the first test.
  int batch = p.max_iterations > 0 ? std::max(min_iterations, 1) : 0;
  for (;;) {
    for (int b = 0; b < batch; ++b) {
      launch(q, increment_, f.n, k.get(), inc_.get(), b_.get(), density ? alpha_p_.get() : alpha_.get(),
             cl_uint(f.n), state_.get(), cl_int(1));
      applyVelocityChange(f, density, inc_, scale, true);
      sources(f, density, dt, true);
      check(0);
    }
    blockingRead(q, state_.get(), sizeof st, st);
    if (st[0]) break;
    batch = kIterationBatch;
  }
  iterations_ += st[1];
  capped_ += st[2];
  return st[1];
}

void ClDfsphSolver::solve(const ClFluidRefs& f, const FluidParams& p, float dt, int tag) {
  if (!sized_ || n_ != f.n) throw Error("dfsph: the pressure phase ran before the density phase");
  if (f.n == 0) return;
  cl::CommandQueue& q = *f.queue;
  const size_t bytes = f.n * sizeof(float);
  double t0 = nowMs();
  rho0_ = p.rest_density;
  q.enqueueCopyBuffer(*f.vx, ux_.get(), 0, 0, bytes);
  q.enqueueCopyBuffer(*f.vy, uy_.get(), 0, 0, bytes);
  q.enqueueCopyBuffer(*f.vz, uz_.get(), 0, 0, bytes);
  // k scales as the pressure times dt^2 (density) or dt (divergence).
  const float ratio = last_dt_ > 0.0f ? dt / last_dt_ : 1.0f;
  last_dt_ = dt;
  // Divergence-free solve on the velocities of the last substep.
  last_div_ = iterate(f, p, false, dt, double(p.divergence_tolerance) / double(dt),
                      p.divergence_min_iterations, kWarmStart * ratio, 1);
  record(f, "pressure", "divergence solve", &t0);
  // Every other acceleration of the substep and the walls' support, then the
  // constant-density solve.
  launch(q, predict_, f.n, *f.x, *f.y, *f.z, ux_.get(), uy_.get(), uz_.get(), *f.ax, *f.ay, *f.az,
         cl_uint(f.n), args_, dt);
  last_dens_ = iterate(f, p, true, dt, double(p.density_tolerance), 2, kWarmStart * ratio * ratio, 0);
  launch(q, finish_, f.n, ux_.get(), uy_.get(), uz_.get(), *f.vx, *f.vy, *f.vz, k_[kcur_][0].get(),
         k_[kcur_][1].get(), cl_uint(f.n), 1.0f / dt, rho0_, *f.ax, *f.ay, *f.az, *f.p, *f.bad, cl_int(tag));
  record(f, "pressure", "density solve", &t0);
}

void ClDfsphSolver::reorder(const ClFluidRefs& f) {
  if (!sized_ || n_ != f.n || f.n == 0) return;  // sized at the next density phase
  const int o = 1 - kcur_;
  launch(*f.queue, reorder_, f.n, f.grid->order.get(), cl_uint(f.n), k_[kcur_][0].get(), k_[kcur_][1].get(),
         k_[o][0].get(), k_[o][1].get());
  kcur_ = o;
}

void ClDfsphSolver::take(long& iterations, long& capped) {
  iterations = iterations_, capped = capped_;
  iterations_ = capped_ = 0;
}

size_t ClDfsphSolver::memoryBytes() const {
  size_t bytes = 0;
  for (const DeviceBuffer* b :
       {&alpha_, &wgx_, &wgy_,     &wgz_,     &vax_,   &vay_,     &vaz_,      &q_,       &wall_,   &wpx_,
        &wpy_,   &wpz_, &alpha_p_, &bulk_,    &inc_,   &b_,       &rate_buf_, &dux_,     &duy_,    &duz_,
        &ux_,    &uy_,  &uz_,      &partial_, &state_, &k_[0][0], &k_[0][1],  &k_[1][0], &k_[1][1]})
    bytes += b->capacity();
  return bytes;
}

}  // namespace ff
