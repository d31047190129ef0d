#include "cpu/backend_cpu.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "control/shape_matching.h"
#include "cpu/forces/cpu_forces.h"
#include "ff_integrate.h"
#include "metrics/fluid_shares.h"
#include "metrics/pose.h"
#include "parallel/parallel_grain.h"
#include "parallel/simd8.h"

namespace ff {

CpuBackend::CpuBackend(int threads) : threads_(threads), forces_(makeCpuForces()) {
  if (threads_ > 0) omp_set_num_threads(threads_);
  simd::isa();  // a bad $FLOWFORM_SIMD is an error here, not in a parallel loop
}

std::string CpuBackend::device() const {
  return "OpenMP, " + std::to_string(omp_get_max_threads()) + " threads, " + simd::isaName(simd::isa());
}

void CpuBackend::init(const Params& params, const ContainerDesc& box, const FluidState& fluid) {
  box_ = box;
  fluid_ = CpuFluid();
  fluid_.s = fluid;
  const size_t n = fluid.size();
  fluid_.rho.assign(n, params.fluid.rest_density);
  fluid_.p.assign(n, 0.0f);
  for (auto* a : {&fluid_.ax, &fluid_.ay, &fluid_.az}) a->assign(n, 0.0f);
  setParams(params);
  float lo[3] = {box.min.x(), box.min.y(), box.min.z()}, hi[3] = {box.max.x(), box.max.y(), box.max.z()};
  controller_.setBounds(lo, hi);
}

void CpuBackend::setParams(const Params& params) {
  params_ = params;
  if (!solver_ || solver_->name() != solverName(params.fluid.solver))
    solver_ = makeCpuPressureSolver(params.fluid.solver);
  controller_.setParams(params.control, params.shape);
  controller_.setGravity(params.fluid.gravity);
}

void CpuBackend::setControl(ControlSet set) {
  frame_ = RigidFrame();
  frame_.rest_c[0] = set.rest_cx, frame_.rest_c[1] = set.rest_cy, frame_.rest_c[2] = set.rest_cz;
  controller_.reset(std::move(set));
}

FluidView CpuBackend::view() const {
  FluidView v;
  const FluidState& s = fluid_.s;
  v.n = s.size();
  v.x = s.x.data(), v.y = s.y.data(), v.z = s.z.data();
  v.vx = s.vx.data(), v.vy = s.vy.data(), v.vz = s.vz.data();
  if (fluid_.sorted) {  // the grid phase ran since the particles last moved
    v.grid = &fluid_.grid;
    v.groups = &fluid_.groups;
  }
  v.volume = params_.fluid.restVolume();
  v.rho = fluid_.rho.data();
  v.rest_density = params_.fluid.rest_density;
  v.mass = params_.fluid.particle_mass;
  for (int d = 0; d < 3; ++d) v.gravity[d] = params_.fluid.gravity[d];
  v.id = s.id.data();
  v.controlled_by_id = controlled_by_id_.empty() ? nullptr : controlled_by_id_.data();
  return v;
}

void CpuBackend::buildGrid() {
  log_.begin(Phase::Grid);
  buildFluidGrid(fluid_, params_.fluid.smoothing_radius, box_);
  solver_->reorder(fluid_.grid.order());
}

void CpuBackend::computeDensity() {
  log_.begin(Phase::Density);
  if (!solver_->computeDensity(fluid_, params_.fluid, box_)) log_.fail();
}

template <class F>
bool CpuBackend::runForces(Phase of, Phase timed_in, F&& f) {
  const FluidView v = view();
  CpuForceContext c{fluid_, params_, box_, controller_, v, fluid_.sorted ? solver_->neighbours() : nullptr};
  bool ok = true;
  for (const auto& force : forces_) {
    if (force->phase() != of) continue;
    const auto t0 = std::chrono::steady_clock::now();
    ok = f(*force, c) && ok;
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    addStages(stages_, {{phaseName(timed_in), force->name(), ms}});
  }
  return ok;
}

void CpuBackend::computeForces(float dt) {
  log_.begin(Phase::Forces);
  clearAccelerations(fluid_);
  if (!runForces(Phase::Forces, Phase::Forces,
                 [dt](CpuForce& f, CpuForceContext& c) { return f.apply(c, dt); }))
    log_.fail();
}

void CpuBackend::computeControlScale() {
  log_.begin(Phase::ControlScale);
  if (!runForces(Phase::ControlForces, Phase::ControlScale,
                 [](CpuForce& f, CpuForceContext& c) { return f.prepare(c); }))
    log_.fail();
}

void CpuBackend::applyControlForces(float dt) {
  log_.begin(Phase::ControlForces);
  if (!runForces(Phase::ControlForces, Phase::ControlForces,
                 [dt](CpuForce& f, CpuForceContext& c) { return f.apply(c, dt); }))
    log_.fail();
}

void CpuBackend::solvePressure(float dt) {
  log_.begin(Phase::Pressure);
  if (!solver_->solve(fluid_, params_.fluid, box_, dt)) log_.fail();
}

std::vector<StageTime> CpuBackend::takeStageMs() {
  std::vector<StageTime> s;
  s.swap(stages_);
  addStages(s, solver_->takeStages());
  return s;
}

std::vector<std::string> CpuBackend::forceNames() const {
  std::vector<std::string> names;
  for (const auto& f : forces_) names.push_back(f->name());
  return names;
}

void CpuBackend::integrate(float dt) {
  log_.begin(Phase::Integrate);
  if (!integrateFluid(fluid_, params_.fluid, box_, dt)) log_.fail();
}

int CpuBackend::shapeMatching(float dt) {
  log_.begin(Phase::ShapeMatching);
  const int steps = controller_.advance(dt);
  if (!controller_.takeFinite()) log_.fail();
  return steps;
}

Phase CpuBackend::firstNonFinite(int* substep) {
  return log_.take(0, substep);
}

size_t CpuBackend::memoryBytes() const {
  return fluid_.memoryBytes() + controller_.memoryBytes() + solver_->memoryBytes();
}

void CpuBackend::setMetricsTarget(const TargetShape* target) {
  target_ = target;
  target_voxels_ = target ? targetVoxelCount(*target) : 0;
  thin_ = target ? metricsThinVoxels(*target, params_.control.radius) : ThinVoxels();
  thin_radius_ = params_.control.radius;
}

StepMetrics CpuBackend::computeMetrics(bool with_shape) {
  StepMetrics m;
  const FluidState& s = fluid_.s;
  const long n = long(s.size());
  const float rho0 = params_.fluid.rest_density, mass = params_.fluid.particle_mass;
  double derr = 0.0, comp = 0.0, ke = 0.0, vmax2 = 0.0, rho_max = 0.0, p_max = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : derr, comp, ke) reduction(max : vmax2, rho_max, p_max) \
    if (n > kParallelLightLoop)
  for (long i = 0; i < n; ++i) {
    derr += std::fabs(fluid_.rho[i] - rho0) / rho0;
    comp += std::max(fluid_.rho[i] - rho0, 0.0f) / rho0;
    rho_max = std::max(rho_max, double(fluid_.rho[i]));
    p_max = std::max(p_max, double(fluid_.p[i]));
    const double v2 = double(s.vx[i]) * s.vx[i] + double(s.vy[i]) * s.vy[i] + double(s.vz[i]) * s.vz[i];
    ke += 0.5 * mass * v2;
    vmax2 = std::max(vmax2, double(ff_speed2(s.vx[i], s.vy[i], s.vz[i])));  // as the kernel rounds it
  }
  m.density_error = n ? derr / double(n) : 0.0;
  m.compression = n ? comp / double(n) : 0.0;
  m.kinetic_energy = ke;
  m.max_speed = std::sqrt(vmax2);
  m.max_density = rho_max;
  m.max_pressure = p_max;
  const SolverStats st = solver_->take();
  m.solver_iterations = st.iterations;
  m.solver_capped = st.capped;
  m.velocity_clamps = fluid_.velocity_clamps;
  fluid_.velocity_clamps = 0;
  if (controller_.active()) {
    const auto& sv = controller_.fields().s;
    double cov = 0.0;
    for (float si : sv) cov += 1.0 - si;
    m.coverage = cov / double(sv.size());
    m.control_count = long(sv.size());
    if (target_) {
      bestFitFrame(controller_.set(), frame_.q, frame_.c, params_.shape.rotation_iterations * 4);
      if (!with_shape) return m;
      // The thin voxels follow the control radius: a params edit since the
      // target was set (viewer, script, Python) finds them again.
      if (thin_radius_ != params_.control.radius) setMetricsTarget(target_);
      const float h = params_.fluid.smoothing_radius;
      if (!fluid_.grid_current) {  // the next grid phase sorts by this one
        buildFluidIndex(fluid_, h, box_);
        fluid_.grid_current = true;
      }
      const int pad = 2;
      const IouCounts c = voxelIou(*target_, frame_, pad, s.x.data(), s.y.data(), s.z.data(), fluid_.grid,
                                   mass, h, rho0, 0.5f, thin_.thin.empty() ? nullptr : thin_.thin.data());
      const std::vector<uint8_t>& reached = controller_.reached();
      const FluidShares sh =
          fluidShares(*target_, frame_, pad, s.x.data(), s.y.data(), s.z.data(), s.id.data(), size_t(n),
                      controlled_by_id_.empty() ? nullptr : controlled_by_id_.data(),
                      reached.size() == size_t(n) ? reached.data() : nullptr);
      setShapeMetrics(m, c, sh, target_voxels_, particleVoxels(params_.fluid.restVolume(), *target_),
                      thin_.count);
      const ShapePose pose = shapePose(*target_, frame_, params_.fluid.gravity, box_.min, box_.max);
      m.tilt = pose.tilt, m.base_height = pose.base_height;
    }
  }
  return m;
}

}  // namespace ff
