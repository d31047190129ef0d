#include "host/backend_opencl.h"

#include <chrono>

#include "host/backend_factory.h"
#include "host/backend_opencl_impl.h"
#include "host/cl_errors.h"
#include "host/dfsph_cl.h"
#include "host/forces/cl_forces.h"
#include "host/sph_args.h"

namespace ff {

OpenClBackend::Impl::Impl(int device_index)
    : ctx(device_index), program(buildKernelProgram(ctx, embeddedKernelFiles())), grids(ctx, program) {
  reorder = makeKernel(program, "grid_reorder_fluid", ctx);
  density = makeKernel(program, "density", ctx);
  pressure_wcsph = makeKernel(program, "pressure_wcsph", ctx);
  integrate = makeKernel(program, "integrate", ctx);
  density_lanes = makeKernel(program, "density_lanes", ctx, kLaneGroupCap);
  pressure_wcsph_lanes = makeKernel(program, "pressure_wcsph_lanes", ctx, kLaneGroupCap);
  sm_frames = makeKernel(program, "sm_cluster_frames", ctx);
  sm_frames_by_lane = makeKernel(program, "sm_cluster_frames_by_lane", ctx, 256, 15 * sizeof(float));
  sm_velocities = makeKernel(program, "sm_velocities", ctx);
  sm_anchor = makeKernel(program, "sm_anchor", ctx);
  sm_integrate = makeKernel(program, "sm_integrate", ctx);
  m_fluid = makeKernel(program, "metrics_fluid", ctx, 256, 6 * sizeof(float));
  m_coverage = makeKernel(program, "metrics_coverage", ctx, 256, sizeof(float));
  m_com = makeKernel(program, "metrics_com", ctx, 256, 3 * sizeof(float));
  m_apq = makeKernel(program, "metrics_apq", ctx, 256, 9 * sizeof(float));
  m_iou = makeKernel(program, "metrics_iou", ctx, 256, 2 * sizeof(cl_uint));
  m_iou_lanes = makeKernel(program, "metrics_iou_lanes", ctx, 256, 2 * sizeof(cl_uint));
  m_shares = makeKernel(program, "metrics_shares", ctx, 256, 4 * sizeof(cl_uint));
  bad.ensure(ctx.context(), sizeof(cl_int));
  fillBuffer(ctx.queue(), bad, cl_int(0), 1);
  clamps.ensure(ctx.context(), sizeof(cl_uint));
}

OpenClBackend::OpenClBackend(int device_index)
    : d_(clGuard("starting the backend", [&] { return std::make_unique<Impl>(device_index); })),
      forces_(clGuard("making the non-pressure forces", [&] { return makeClForces(d_->program, d_->ctx); })) {
  const std::string k = kernelChoice();
  setKernelVariant(k == "scalar"  ? KernelVariant::Scalar
                   : k == "lanes" ? KernelVariant::Lanes
                                  : KernelVariant::Auto);
}

void OpenClBackend::setKernelVariant(KernelVariant v) {
  lanes_ = v == KernelVariant::Lanes ||
           (v == KernelVariant::Auto && (d_->ctx.info().type & CL_DEVICE_TYPE_CPU) != 0);
  d_->grids.setChunkedScan(lanes_);
}

OpenClBackend::~OpenClBackend() = default;

std::string OpenClBackend::device() const {
  return "OpenCL: " + d_->ctx.info().summary() + (lanes_ ? ", lanes kernels" : ", scalar kernels");
}

const ClDeviceInfo& OpenClBackend::deviceInfo() const {
  return d_->ctx.info();
}

int OpenClBackend::beginPhase(Phase p) {
  return int(log_.begin(p));
}

void OpenClBackend::endPhase() {
  if (profiling_) finishQueue(d_->queue());
}

void OpenClBackend::init(const Params& params, const ContainerDesc& box, const FluidState& fluid) {
  clGuard("init", [&] {
    Impl& d = *d_;
    const cl::Context& c = d.ctx.context();
    cl::CommandQueue& q = d.queue();
    box_ = box;
    n_ = fluid.size();
    d.cur = 0;
    for (DeviceBuffer* b : {&d.x[0], &d.y[0], &d.z[0], &d.vx[0], &d.vy[0], &d.vz[0], &d.x[1], &d.y[1],
                            &d.z[1], &d.vx[1], &d.vy[1], &d.vz[1]})
      b->ensure(c, padded8(n_) * sizeof(float));
    upload(q, c, d.x[0], fluid.x), upload(q, c, d.y[0], fluid.y), upload(q, c, d.z[0], fluid.z);
    upload(q, c, d.vx[0], fluid.vx), upload(q, c, d.vy[0], fluid.vy), upload(q, c, d.vz[0], fluid.vz);
    upload(q, c, d.id[0], fluid.id);
    d.id[1].ensure(c, n_ * sizeof(float));
    for (DeviceBuffer* b : {&d.rho, &d.p, &d.ax, &d.ay, &d.az}) b->ensure(c, padded8(n_) * sizeof(float));
    fillBuffer(q, d.rho, params.fluid.rest_density, n_);
    for (DeviceBuffer* b : {&d.p, &d.ax, &d.ay, &d.az}) fillBuffer(q, *b, 0.0f, n_);
    // The padding past n: no kernel writes it, the 8-wide loads read it
    // (masked, but 0 x NaN is NaN), so it is zeroed here, after every resize.
    for (int k = 0; k < 2; ++k)
      for (DeviceBuffer* b : {&d.x[k], &d.y[k], &d.z[k], &d.vx[k], &d.vy[k], &d.vz[k]})
        fillBuffer(q, *b, 0.0f, padded8(n_) - n_, n_);
    for (DeviceBuffer* b : {&d.rho, &d.p, &d.ax, &d.ay, &d.az}) fillBuffer(q, *b, 0.0f, padded8(n_) - n_, n_);
    d.reach.ensure(c, padded8(n_));
    fillBuffer(q, d.reach, cl_uchar(0), padded8(n_));
    fillBuffer(q, d.clamps, cl_uint(0), 1);
    setParams(params);
    grid_state_ = GridState::Stale;
    finishQueue(q);
  });
}

ClFluidRefs OpenClBackend::fluidRefs() {
  Impl& d = *d_;
  ClFluidRefs f;
  f.queue = &d.queue(), f.context = &d.ctx.context();
  f.x = &d.X(), f.y = &d.Y(), f.z = &d.Z(), f.vx = &d.VX(), f.vy = &d.VY(), f.vz = &d.VZ();
  f.rho = &d.rho.get(), f.p = &d.p.get(), f.ax = &d.ax.get(), f.ay = &d.ay.get(), f.az = &d.az.get();
  f.grid = &d.fluid_h, f.bad = &d.bad.get(), f.n = n_, f.lanes = lanes_;
  return f;
}

void OpenClBackend::setParams(const Params& params) {
  if (params.fluid.solver == PressureSolverKind::Dfsph && !dfsph_) {
    dfsph_ = clGuard("starting the DFSPH solver",
                     [&] { return std::make_unique<ClDfsphSolver>(d_->program, d_->ctx); });
    dfsph_->setProfiling(profiling_);
  } else if (params.fluid.solver != PressureSolverKind::Dfsph) {
    dfsph_.reset();
  }
  if (params.fluid.smoothing_radius != params_.fluid.smoothing_radius) grid_state_ = GridState::Stale;
  params_ = params;
}

void OpenClBackend::setControl(ControlSet set) {
  control_ = std::move(set);
  anchorAtCentre(control_);  // as Controller::reset
  nc_ = control_.size();
  if (control_.radius_scale.size() != nc_) control_.radius_scale.assign(nc_, 1.0f);  // as Controller::reset
  nclusters_ = control_.clusters.count();
  clock_ = 0.0;
  frame_ = RigidFrame();
  frame_.rest_c[0] = control_.rest_cx, frame_.rest_c[1] = control_.rest_cy,
  frame_.rest_c[2] = control_.rest_cz;
  if (nc_ > 0) clGuard("uploading the control particles", [&] { uploadControl(); });
}

void OpenClBackend::uploadControl() {
  Impl& d = *d_;
  const cl::Context& c = d.ctx.context();
  cl::CommandQueue& q = d.queue();
  const ControlSet& s = control_;
  upload(q, c, d.cx, s.x), upload(q, c, d.cy, s.y), upload(q, c, d.cz, s.z);
  upload(q, c, d.cvx, s.vx), upload(q, c, d.cvy, s.vy), upload(q, c, d.cvz, s.vz);
  upload(q, c, d.x0, s.x0), upload(q, c, d.y0, s.y0), upload(q, c, d.z0, s.z0);
  upload(q, c, d.crs, s.radius_scale);
  upload(q, c, d.gx, s.x), upload(q, c, d.gy, s.y), upload(q, c, d.gz, s.z);  // as Controller::reset
  for (DeviceBuffer* b : {&d.s, &d.ux, &d.uy, &d.uz, &d.sx, &d.sy, &d.sz, &d.ss, &d.svx, &d.svy, &d.svz})
    b->ensure(c, nc_ * sizeof(float));
  fillBuffer(q, d.s, 1.0f, nc_);
  for (DeviceBuffer* b : {&d.ux, &d.uy, &d.uz}) fillBuffer(q, *b, 0.0f, nc_);
  const Clusters& cl = s.clusters;
  upload(q, c, d.cl_start, cl.start), upload(q, c, d.cl_members, cl.members);
  upload(q, c, d.rest_cx, cl.rest_cx), upload(q, c, d.rest_cy, cl.rest_cy),
      upload(q, c, d.rest_cz, cl.rest_cz);
  upload(q, c, d.of_start, cl.of_start), upload(q, c, d.of, cl.of);
  if (s.blending()) {
    upload(q, c, d.bx0, s.bx0), upload(q, c, d.by0, s.by0), upload(q, c, d.bz0, s.bz0);
    upload(q, c, d.from_cx, cl.from_cx), upload(q, c, d.from_cy, cl.from_cy),
        upload(q, c, d.from_cz, cl.from_cz);
  }
  const std::vector<ff_quat> identity(nclusters_, FF_Q(0.0f, 0.0f, 0.0f, 1.0f));
  upload(q, c, d.q, identity);
  for (DeviceBuffer* b : {&d.com_x, &d.com_y, &d.com_z, &d.ccv_x, &d.ccv_y, &d.ccv_z})
    b->ensure(c, nclusters_ * sizeof(float));
  finishQueue(q);  // `identity` must outlive the non-blocking writes
}

void OpenClBackend::setControlledFluid(std::vector<uint8_t> by_id) {
  masked_ = !by_id.empty();
  if (!masked_) return;
  clGuard("uploading the controlled fluid", [&] {
    upload(d_->queue(), d_->ctx.context(), d_->controlled, by_id);
    finishQueue(d_->queue());
  });
}

void OpenClBackend::setMetricsTarget(const TargetShape* target) {
  target_ = target;
  target_voxels_ = target ? targetVoxelCount(*target) : 0;
  thin_voxels_ = 0;
  if (!target) return;
  // Inside voxels 1, thin inside voxels 3 (bit 2: metrics_iou's filled_thin).
  const ThinVoxels thin = metricsThinVoxels(*target, params_.control.radius);
  thin_voxels_ = thin.count;
  thin_radius_ = params_.control.radius;
  std::vector<uint8_t> classes(target->grid.inside.size());
  for (size_t i = 0; i < classes.size(); ++i)
    classes[i] = uint8_t((target->grid.inside[i] ? 1 : 0) | (thin.thin[i] ? 2 : 0));
  clGuard("uploading the metrics target", [&] {
    upload(d_->queue(), d_->ctx.context(), d_->inside, classes);
    finishQueue(d_->queue());
  });
}

void OpenClBackend::buildGrid() {
  clGuard("phase 'grid'", [&] {
    Impl& d = *d_;
    beginPhase(Phase::Grid);
    if (n_ == 0) return;
    if (grid_state_ != GridState::Index)
      d.grids.build(d.fluid_h, d.X(), d.Y(), d.Z(), n_, params_.fluid.smoothing_radius, boxMin(box_),
                    boxMax(box_));
    const int o = 1 - d.cur;
    launch(d.queue(), d.reorder, n_, d.fluid_h.order.get(), cl_uint(n_), d.X(), d.Y(), d.Z(), d.VX(), d.VY(),
           d.VZ(), d.id[d.cur].get(), d.x[o].get(), d.y[o].get(), d.z[o].get(), d.vx[o].get(), d.vy[o].get(),
           d.vz[o].get(), d.id[o].get());
    d.cur = o;
    if (dfsph_) dfsph_->reorder(fluidRefs());
    grid_state_ = GridState::Sorted;
    endPhase();
  });
}

void OpenClBackend::computeDensity() {
  clGuard("phase 'density'", [&] {
    Impl& d = *d_;
    const int tag = beginPhase(Phase::Density);
    const FluidParams& f = params_.fluid;
    const DeviceGrid& g = d.fluid_h;
    if (dfsph_)
      dfsph_->computeDensity(fluidRefs(), f, box_, tag);
    else
      launch(d.queue(), lanes_ ? d.density_lanes : d.density, lanes_ ? padded8(n_) / 8 : n_, d.X(), d.Y(),
             d.Z(), cl_uint(n_), g.start.get(), g.geom.geo(), g.geom.dims(), sphArgs(f, box_, g.geom.cell),
             d.rho.get(), d.p.get(), d.bad.get(), cl_int(tag));
    endPhase();
  });
}

template <class F>
void OpenClBackend::runForces(Phase of, Phase timed_in, int tag, F&& f) {
  const ClFluidRefs refs = fluidRefs();
  ClForceContext c{refs, *d_, params_, box_, control_, nc_, masked_, tag};
  for (const auto& force : forces_) {
    if (force->phase() != of) continue;
    const auto t0 = std::chrono::steady_clock::now();
    f(*force, c);
    if (!profiling_) continue;
    finishQueue(d_->queue());
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    addStages(stages_, {{phaseName(timed_in), force->name(), ms}});
  }
}

void OpenClBackend::computeForces(float dt) {
  clGuard("phase 'forces'", [&] {
    Impl& d = *d_;
    const int tag = beginPhase(Phase::Forces);
    for (DeviceBuffer* b : {&d.ax, &d.ay, &d.az}) fillBuffer(d.queue(), *b, 0.0f, n_);
    runForces(Phase::Forces, Phase::Forces, tag, [dt](ClForce& f, ClForceContext& c) { f.apply(c, dt); });
    endPhase();
  });
}

void OpenClBackend::computeControlScale() {
  clGuard("phase 'control_scale'", [&] {
    const int tag = beginPhase(Phase::ControlScale);
    runForces(Phase::ControlForces, Phase::ControlScale, tag,
              [](ClForce& f, ClForceContext& c) { f.prepare(c); });
    endPhase();
  });
}

void OpenClBackend::applyControlForces(float dt) {
  clGuard("phase 'control_forces'", [&] {
    const int tag = beginPhase(Phase::ControlForces);
    runForces(Phase::ControlForces, Phase::ControlForces, tag,
              [dt](ClForce& f, ClForceContext& c) { f.apply(c, dt); });
    endPhase();
  });
}

void OpenClBackend::addForce(std::unique_ptr<ClForce> force) {
  forces_.push_back(std::move(force));
}

const ClContext& OpenClBackend::context() const {
  return d_->ctx;
}

void OpenClBackend::setProfiling(bool on) {
  profiling_ = on;
  if (dfsph_) dfsph_->setProfiling(on);
}

std::vector<std::string> OpenClBackend::forceNames() const {
  std::vector<std::string> names;
  for (const auto& f : forces_) names.push_back(f->name());
  return names;
}

std::vector<StageTime> OpenClBackend::takeStageMs() {
  std::vector<StageTime> s;
  s.swap(stages_);
  if (dfsph_) addStages(s, dfsph_->takeStages());
  return s;
}

void OpenClBackend::solvePressure(float dt) {
  clGuard("phase 'pressure'", [&] {
    Impl& d = *d_;
    const int tag = beginPhase(Phase::Pressure);
    const FluidParams& f = params_.fluid;
    const DeviceGrid& g = d.fluid_h;
    if (dfsph_)
      dfsph_->solve(fluidRefs(), f, dt, tag);
    else
      launch(d.queue(), lanes_ ? d.pressure_wcsph_lanes : d.pressure_wcsph, lanes_ ? padded8(n_) / 8 : n_,
             d.X(), d.Y(), d.Z(), d.rho.get(), d.p.get(), cl_uint(n_), g.start.get(), g.geom.geo(),
             g.geom.dims(), sphArgs(f, box_, g.geom.cell), d.ax.get(), d.ay.get(), d.az.get(), d.bad.get(),
             cl_int(tag));
    endPhase();
  });
}

void OpenClBackend::integrate(float dt) {
  clGuard("phase 'integrate'", [&] {
    Impl& d = *d_;
    const int tag = beginPhase(Phase::Integrate);
    const FluidParams& f = params_.fluid;
    const float vmax = f.max_step_fraction * f.smoothing_radius / dt;
    const float eps = 1e-6f * f.smoothing_radius;
    launch(d.queue(), d.integrate, n_, d.X(), d.Y(), d.Z(), d.VX(), d.VY(), d.VZ(), d.ax.get(), d.ay.get(),
           d.az.get(), cl_uint(n_), dt, vmax, eps, boxLo(box_), boxHi(box_), d.clamps.get(), d.bad.get(),
           cl_int(tag));
    grid_state_ = GridState::Stale;
    endPhase();
  });
}

Phase OpenClBackend::firstNonFinite(int* substep) {
  return clGuard("reading the non-finite record", [&] {
    cl_int tag = 0;
    blockingRead(d_->queue(), d_->bad.get(), sizeof(cl_int), &tag);
    if (tag != 0) fillBuffer(d_->queue(), d_->bad, cl_int(0), 1);
    return log_.take(uint32_t(tag), substep);
  });
}

size_t OpenClBackend::memoryBytes() const {
  const Impl& d = *d_;
  size_t bytes = 0;
  for (int k = 0; k < 2; ++k)
    for (const DeviceBuffer* b : {&d.x[k], &d.y[k], &d.z[k], &d.vx[k], &d.vy[k], &d.vz[k], &d.id[k]})
      bytes += b->capacity();
  for (const DeviceBuffer* b :
       {&d.rho,      &d.p,          &d.ax,         &d.ay,        &d.az,      &d.cx,         &d.cy,
        &d.cz,       &d.cvx,        &d.cvy,        &d.cvz,       &d.x0,      &d.y0,         &d.z0,
        &d.s,        &d.ux,         &d.uy,         &d.uz,        &d.gx,      &d.gy,         &d.gz,
        &d.sx,       &d.sy,         &d.sz,         &d.ss,        &d.svx,     &d.svy,        &d.svz,
        &d.cl_start, &d.cl_members, &d.rest_cx,    &d.rest_cy,   &d.rest_cz, &d.of_start,   &d.of,
        &d.q,        &d.com_x,      &d.com_y,      &d.com_z,     &d.ccv_x,   &d.ccv_y,      &d.ccv_z,
        &d.inside,   &d.rcentre,    &d.rseeds[0],  &d.rseeds[1], &d.reach,   &d.controlled, &d.partial,
        &d.clamps,   &d.bad,        &d.anchor_fix, &d.bx0,       &d.by0,     &d.bz0,        &d.from_cx,
        &d.from_cy,  &d.from_cz})
    bytes += b->capacity();
  return bytes + d.fluid_h.memoryBytes() + d.control_r.memoryBytes() + d.grids.memoryBytes() +
         (dfsph_ ? dfsph_->memoryBytes() : 0);
}

void OpenClBackend::readFluid(FluidState& out) {
  clGuard("reading the fluid", [&] {
    Impl& d = *d_;
    cl::CommandQueue& q = d.queue();
    download(q, d.x[d.cur], n_, out.x), download(q, d.y[d.cur], n_, out.y),
        download(q, d.z[d.cur], n_, out.z);
    download(q, d.vx[d.cur], n_, out.vx), download(q, d.vy[d.cur], n_, out.vy);
    download(q, d.vz[d.cur], n_, out.vz), download(q, d.id[d.cur], n_, out.id);
  });
}

void OpenClBackend::readDensity(std::vector<float>& rho, std::vector<float>& pressure) {
  clGuard("reading the density", [&] {
    download(d_->queue(), d_->rho, n_, rho);
    download(d_->queue(), d_->p, n_, pressure);
  });
}

void OpenClBackend::readAccel(std::vector<float>& ax, std::vector<float>& ay, std::vector<float>& az) {
  clGuard("reading the accelerations", [&] {
    download(d_->queue(), d_->ax, n_, ax), download(d_->queue(), d_->ay, n_, ay);
    download(d_->queue(), d_->az, n_, az);
  });
}

void OpenClBackend::readControl(ControlSet& set, ControlFields& fields) {
  clGuard("reading the control particles", [&] {
    Impl& d = *d_;
    cl::CommandQueue& q = d.queue();
    if (nc_ > 0) {
      download(q, d.cx, nc_, control_.x), download(q, d.cy, nc_, control_.y),
          download(q, d.cz, nc_, control_.z);
      download(q, d.cvx, nc_, control_.vx), download(q, d.cvy, nc_, control_.vy);
      download(q, d.cvz, nc_, control_.vz);
    }
    set = control_;
    download(q, d.s, nc_, fields.s), download(q, d.ux, nc_, fields.ux), download(q, d.uy, nc_, fields.uy);
    download(q, d.uz, nc_, fields.uz);
  });
}

void OpenClBackend::readGoals(std::vector<float>& gx, std::vector<float>& gy, std::vector<float>& gz) {
  clGuard("reading the goals", [&] {
    download(d_->queue(), d_->gx, nc_, gx), download(d_->queue(), d_->gy, nc_, gy);
    download(d_->queue(), d_->gz, nc_, gz);
  });
}

void OpenClBackend::readClusterRotations(std::vector<ff_quat>& q) {
  clGuard("reading the cluster rotations", [&] { download(d_->queue(), d_->q, nclusters_, q); });
}

OpenClBackend::GridSnapshot OpenClBackend::readGrid(GridKind kind) {
  return clGuard("reading a grid", [&] {
    const DeviceGrid& g = kind == GridKind::Fluid ? d_->fluid_h : d_->control_r;
    GridSnapshot s;
    s.geom = g.geom;
    if (g.start.capacity() == 0) return s;  // never built
    download(d_->queue(), g.start, g.geom.cells() + 1, s.start);
    download(d_->queue(), g.order, g.n, s.order);
    return s;
  });
}

std::vector<uint32_t> OpenClBackend::readRecaptureField() {
  return clGuard("reading the recapture's field", [&] {
    std::vector<uint32_t> seeds;
    if (d_->rfield_cells > 0) download(d_->queue(), d_->rseeds[0], d_->rfield_cells, seeds);
    return seeds;
  });
}

}  // namespace ff
