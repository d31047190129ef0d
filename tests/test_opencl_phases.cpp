// The OpenCL backend phase by phase against the OpenMP backend (the
// independent reference): the same input state goes through each phase on
// both, and the outputs must agree - neighbour grids exactly, values bit for
// bit on PoCL in EachPhaseMatchesTheCpuBackend (the project's rule; ctest runs
// it with each kernel variant forced, opencl.*_kernels_poisoned), within 4 ulp
// of their error scale in the per-variant tests (kPoclPhaseTol), and within the
// GPU tolerance on other devices, in both variants of the neighbour kernels
// (one particle per work-item, 8 as float8 lanes). Each phase's values are
// also checked against the physics itself, worked out here (density, the
// equation of state, eq. 5's scale and u_bar, symplectic Euler, unit
// rotations, kinetic energy and top speed).
//
// Error measure: |a - b| <= tol * max(|a|, scale), with `scale` the size of
// the terms the value is computed from (the GPU rounding policy, docs/GPU.md):
// - by default the RMS of the CPU field over all particles: each value is a
//   float sum of terms of the field's typical size, so a rounding difference
//   is a few ulp of that size, not of the value (a sum that cancels to nearly
//   zero, a particle at rest between its neighbours, keeps that error);
// - pressure p = k (rho - rho0): k times the RMS density (the subtraction
//   cancels most of rho, not its rounding error);
// - control velocities, dv = (goal - x) alpha / dt (eq. 7): alpha / dt times
//   the RMS control position (goal - x cancels most of the positions, whose
//   rounding error is a few ulp of the coordinates).
// The GPU tolerance (gpu_tolerance.h) is checked on PoCL with GPU rounding
// emulated (EmulatedGpuRounding* below).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "control/recapture_field.h"
#include "core/error.h"
#include "cpu/backend_cpu.h"
#include "ff_control.h"
#include "ff_grid.h"
#include "gpu_tolerance.h"
#include "grid/uniform_grid.h"
#include "host/backend_factory.h"
#include "host/backend_opencl.h"
#include "host/cl_context.h"
#include "host/cl_errors.h"
#include "host/cl_program.h"
#include "metrics/fluid_shares.h"
#include "opencl_backend.h"
#include "sim/simulation.h"
#include "test_scenes.h"
#include "thin_target.h"

namespace {

constexpr double kTol = ff::test::kGpuPhaseTol;

using fftest::openClBackend;

struct Err {
  double max_rel = 0.0;   // max_i |a_i - b_i| / max(|a_i|, scale)
  double norm_rel = 0.0;  // ||a - b||_2 / ||a||_2
};

double rms(const std::vector<float>& a) {
  double ss = 0.0;
  for (float v : a) ss += double(v) * v;
  return a.empty() ? 0.0 : std::sqrt(ss / double(a.size()));
}

// scale_floor: the error scale of the quantity where it exceeds its RMS.
Err compare(const std::vector<float>& a, const std::vector<float>& b, double scale_floor) {
  EXPECT_EQ(a.size(), b.size());
  Err e;
  if (a.empty() || a.size() != b.size()) return e;
  double ss = 0.0, dd = 0.0;
  for (float v : a) ss += double(v) * v;
  const double scale = std::max(std::sqrt(ss / double(a.size())), scale_floor);
  for (size_t i = 0; i < a.size(); ++i) {
    const double d = std::fabs(double(a[i]) - double(b[i]));
    dd += d * d;
    e.max_rel = std::max(e.max_rel, d / std::max({std::fabs(double(a[i])), scale, 1e-30}));
  }
  e.norm_rel = ss > 0.0 ? std::sqrt(dd / ss) : std::sqrt(dd);
  return e;
}

// On PoCL the kernels run the OpenMP backend's float operations in its
// order, and the results must agree bit for bit; other devices may fuse
// multiply-adds and round division and sqrt differently, within kTol.
double g_tol = kTol;
double g_worst = 0.0;  // the largest error seen by expectClose

void expectClose(const char* what, const std::vector<float>& cpu, const std::vector<float>& ocl,
                 double scale_floor = 0.0) {
  const Err e = compare(cpu, ocl, scale_floor);
  std::printf("  %-28s max rel %.3g   norm rel %.3g   (%zu values)\n", what, e.max_rel, e.norm_rel,
              cpu.size());
  EXPECT_LE(e.max_rel, g_tol) << what;
  g_worst = std::max(g_worst, e.max_rel);
}

void expectGridEqual(const char* what, const ff::UniformGrid& g, const ff::OpenClBackend::GridSnapshot& s,
                     bool compare_order) {
  EXPECT_EQ(g.nx(), s.geom.nx) << what;
  EXPECT_EQ(g.ny(), s.geom.ny) << what;
  EXPECT_EQ(g.nz(), s.geom.nz) << what;
  EXPECT_EQ(g.originX(), s.geom.ox) << what;
  EXPECT_EQ(g.originY(), s.geom.oy) << what;
  EXPECT_EQ(g.originZ(), s.geom.oz) << what;
  EXPECT_EQ(g.cellSize(), s.geom.cell) << what;
  EXPECT_TRUE(g.cellStart() == s.start) << what << ": cell ranges differ";
  if (compare_order) {
    EXPECT_TRUE(g.order() == s.order) << what << ": sorted order differs";
  }
}

// Absolute checks: besides agreeing with each other, the backends' values
// must be the physical quantities themselves, worked out here independently
// (in double, by brute force over all particles, from the paper's formulas),
// so that a formula bug shared by both backends (they include the same
// kernels/common headers) fails too. Each is held to a few float roundings
// of the quantity's own terms, far below any physical effect.
constexpr double kUlp = 1.0 / 16777216.0;  // 2^-24, a float's unit roundoff

double poly6(double r2, double h) {
  const double q = h * h - r2;
  return q > 0.0 ? 315.0 / (64.0 * M_PI * std::pow(h, 9)) * q * q * q : 0.0;
}

// rho_i = sum_j m W_poly6(|x_i - x_j|, h), for every 5th particle at least h
// from each wall (where no wall share is added).
void expectDensityIsTheSphSum(const ff::FluidState& s, const std::vector<float>& rho, const ff::Params& p,
                              const ff::ContainerDesc& box) {
  const double h = p.fluid.smoothing_radius, m = p.fluid.particle_mass;
  size_t checked = 0;
  double worst = 0.0;
  for (size_t i = 0; i < s.size(); i += 5) {
    const double pos[3] = {s.x[i], s.y[i], s.z[i]};
    bool inner = true;
    for (int d = 0; d < 3; ++d) inner = inner && pos[d] - box.min[d] >= h && box.max[d] - pos[d] >= h;
    if (!inner) continue;
    double sum = 0.0;
    for (size_t j = 0; j < s.size(); ++j) {
      const double dx = pos[0] - s.x[j], dy = pos[1] - s.y[j], dz = pos[2] - s.z[j];
      sum += m * poly6(dx * dx + dy * dy + dz * dz, h);
    }
    worst = std::max(worst, std::fabs(rho[i] - sum) / sum);
    ++checked;
  }
  std::printf("  %-28s max rel %.3g against a brute-force sum (%zu particles)\n", "density (absolute)", worst,
              checked);
  EXPECT_GT(checked, 50u);
  // ~30 neighbour terms of a few roundings each: well under 1e-5.
  EXPECT_LE(worst, 1e-5);
}

// s_i = 1 - min(1, V sum_e W(|c_i - x_e|, r_i)) (eq. 5) and u_bar = V sum_e W v_e / max(V sum_e W, 1),
// brute force over all the fluid, for every control particle, r_i its own
// radius (the control radius times its radius scale: adaptive control).
void expectControlScaleIsTheSum(const ff::ControlSet& c, const ff::ControlFields& f, const ff::FluidState& s,
                                const ff::Params& p) {
  const double v = p.fluid.restVolume();
  double worst_s = 0.0, worst_u = 0.0, vmax = 1e-3;
  for (size_t e = 0; e < s.size(); ++e)
    vmax = std::max(
        vmax, std::sqrt(double(s.vx[e]) * s.vx[e] + double(s.vy[e]) * s.vy[e] + double(s.vz[e]) * s.vz[e]));
  for (size_t i = 0; i < c.size(); ++i) {
    const double r = double(p.control.radius) * c.radius_scale[i];
    double w = 0.0, u[3] = {0, 0, 0};
    for (size_t e = 0; e < s.size(); ++e) {
      const double dx = double(c.x[i]) - s.x[e], dy = double(c.y[i]) - s.y[e], dz = double(c.z[i]) - s.z[e];
      const double k = poly6(dx * dx + dy * dy + dz * dz, r);
      w += k, u[0] += k * s.vx[e], u[1] += k * s.vy[e], u[2] += k * s.vz[e];
    }
    const double rho_hat = v * w, norm = w > 0.0 ? v / std::max(rho_hat, 1.0) : 0.0;
    worst_s = std::max(worst_s, std::fabs(f.s[i] - (1.0 - std::min(1.0, rho_hat))));
    const double got[3] = {f.ux[i], f.uy[i], f.uz[i]};
    for (int d = 0; d < 3; ++d) worst_u = std::max(worst_u, std::fabs(got[d] - u[d] * norm) / vmax);
  }
  std::printf("  %-28s max abs %.3g (s), %.3g of the top fluid speed (u_bar), %zu control particles\n",
              "control scale (absolute)", worst_s, worst_u, c.size());
  // Sums of up to ~2000 terms in 8 float lanes: ~1e-5 at worst.
  EXPECT_LE(worst_s, 2e-5);
  EXPECT_LE(worst_u, 2e-5);
}

// Symplectic Euler (v' = v + dt a, x' = x + dt v') for every particle that
// neither the speed limit nor a wall touched, to a few roundings of its terms.
void expectSymplecticEuler(const ff::FluidState& before, const std::vector<float> a[3],
                           const ff::FluidState& after, const ff::Params& p, const ff::ContainerDesc& box,
                           float dt) {
  const double vmax = double(p.fluid.max_step_fraction) * p.fluid.smoothing_radius / dt;
  size_t checked = 0;
  double worst = 0.0;
  for (size_t i = 0; i < before.size(); ++i) {
    const double x[3] = {before.x[i], before.y[i], before.z[i]},
                 v[3] = {before.vx[i], before.vy[i], before.vz[i]};
    const double x1[3] = {after.x[i], after.y[i], after.z[i]},
                 v1[3] = {after.vx[i], after.vy[i], after.vz[i]};
    double nv[3], nx[3], speed2 = 0.0;
    bool free = true;
    for (int d = 0; d < 3; ++d) {
      nv[d] = v[d] + dt * double(a[d][i]);
      nx[d] = x[d] + dt * nv[d];
      speed2 += nv[d] * nv[d];
      free = free && nx[d] - box.min[d] > 1e-4 && box.max[d] - nx[d] > 1e-4;
    }
    if (!free || std::sqrt(speed2) > 0.999 * vmax) continue;
    for (int d = 0; d < 3; ++d) {
      const double tv = 4 * kUlp * (std::fabs(v[d]) + dt * std::fabs(double(a[d][i]))) + 1e-30;
      const double tx = 4 * kUlp * (std::fabs(x[d]) + dt * std::fabs(nv[d])) + 1e-30;
      worst = std::max({worst, std::fabs(v1[d] - nv[d]) / tv, std::fabs(x1[d] - nx[d]) / tx});
    }
    ++checked;
  }
  std::printf("  %-28s worst %.3g of its 4-rounding bound (%zu free particles)\n", "integration (absolute)",
              worst, checked);
  EXPECT_GT(checked, before.size() / 2);
  EXPECT_LE(worst, 1.0);
}

// A small scene: ~3000 particles falling into a ~600-particle sphere target.
// 3094 particles: not a multiple of 8 (the lanes, the padding) nor of any
// work-group size, so the last work-group and the last 8 lanes are partial.
ff::SceneDesc smallScene() {
  ff::SceneDesc s =
      fftest::blockScene(ff::Vec3(0.2f, 0.2f, 0.2f), ff::Vec3(0.055f, 0.0f, 0.055f), 13, 17, 14);
  s.schedule.push_back({0.0, fftest::target(ff::TargetKind::Sphere, 600)});
  return s;
}

// Both backends start from the state of a CPU run after `steps` steps.
struct Pair {
  ff::SceneDesc scene;
  std::unique_ptr<ff::Simulation> sim;  // owns the target
  ff::CpuBackend cpu{2};
  std::unique_ptr<ff::OpenClBackend> ocl;
};

std::unique_ptr<Pair> makePair(int steps, const ff::SceneDesc& scene = smallScene()) {
  auto p = std::make_unique<Pair>();
  p->ocl = openClBackend();
  if (!p->ocl) return nullptr;
  p->scene = scene;
  p->sim = std::make_unique<ff::Simulation>(p->scene, std::make_unique<ff::CpuBackend>(2));
  for (int i = 0; i < steps; ++i) p->sim->step();
  ff::FluidState fluid;
  ff::ControlSet control;
  ff::ControlFields fields;
  p->sim->backend().readFluid(fluid);
  p->sim->backend().readControl(control, fields);
  const ff::Params& params = p->sim->scene().params;
  for (ff::Backend* b : {static_cast<ff::Backend*>(&p->cpu), static_cast<ff::Backend*>(p->ocl.get())}) {
    b->init(params, p->scene.container, fluid);
    b->setControl(control);
    b->setMetricsTarget(p->sim->target());
  }
  return p;
}

// On PoCL: the variant tests allow a few ulps of each quantity's error scale,
// the Auto test none. The kernels run the OpenMP backend's float operations
// in its order (FP_CONTRACT OFF, dot and cross written out, docs/GPU.md), so
// the expected difference is 0; one or two operations rounded differently
// (a compiler folding a constant, or a division and a reciprocal multiply
// swapped) move a value by one or two roundings of its terms, 2^-24 of the
// error scale each, and 4 of them are allowed. Anything a bug does is far
// larger: a missing term changes a value by ~1e-3 of its scale or more. The
// Auto test keeps the project's rule, bit for bit on PoCL, in one place.
constexpr double kPoclPhaseTol = 4.0 / 16777216.0;

// Every phase on both backends; the OpenCL backend with the given kernel variant.
void checkEachPhase(ff::OpenClBackend::KernelVariant variant, bool bit_for_bit = false,
                    const ff::SceneDesc& scene = smallScene()) {
  auto p = makePair(40, scene);
  ASSERT_TRUE(p);
  ff::CpuBackend& cpu = p->cpu;
  ff::OpenClBackend& ocl = *p->ocl;
  ocl.setKernelVariant(variant);
  const bool pocl = ff::roundsAsTheCpuBackend(ocl.deviceInfo());
  g_tol = !pocl ? kTol : bit_for_bit ? 0.0 : kPoclPhaseTol;
  g_worst = 0.0;
  std::printf("tolerance: %s\n", !pocl         ? "1e-5 of each quantity's error scale (GPU rounding)"
                                 : bit_for_bit ? "0 (PoCL: bit for bit)"
                                               : "4 ulp of each quantity's error scale (PoCL)");
  std::printf("kernel variant: %s\n", ocl.usesLanes() ? "8 particles per work-item" : "1 per work-item");
  const ff::Params& params = p->sim->scene().params;
  const float dt = params.fluid.time_step;
  std::printf("OpenCL device: %s\n", ocl.device().c_str());
  ff::FluidState fc, fo;

  // Grid: same dims, origin, cell ranges and sorted order (so the same neighbours in the same order).
  cpu.buildGrid(), ocl.buildGrid();
  expectGridEqual("fluid grid (cell h)", cpu.fluid().grid, ocl.readGrid(ff::OpenClBackend::GridKind::Fluid),
                  false);
  ocl.readFluid(fo);
  fc = cpu.fluid().s;
  EXPECT_TRUE(fc.id == fo.id) << "particles sorted into a different order";
  EXPECT_TRUE(fc.x == fo.x && fc.y == fo.y && fc.z == fo.z && fc.vx == fo.vx) << "reorder changed values";

  // Density and pressure.
  cpu.computeDensity(), ocl.computeDensity();
  ASSERT_EQ(cpu.firstNonFinite(), ff::Phase::Count);
  ASSERT_EQ(ocl.firstNonFinite(), ff::Phase::Count);
  std::vector<float> rho, pr;
  ocl.readDensity(rho, pr);
  expectClose("density", cpu.fluid().rho, rho);
  expectClose("pressure", cpu.fluid().p, pr, params.fluid.gas_constant * rms(cpu.fluid().rho));
  expectDensityIsTheSphSum(fo, rho, params, p->scene.container);
  {  // the equation of state, p = k (rho - rho0)
    double worst = 0.0;
    const double k = params.fluid.gas_constant, rho0 = params.fluid.rest_density;
    for (size_t i = 0; i < rho.size(); ++i)
      worst = std::max(worst, std::fabs(pr[i] - k * (double(rho[i]) - rho0)) / (k * rho0));
    EXPECT_LE(worst, 4 * kUlp) << "pressure is not k (rho - rho0)";
  }

  // The non-pressure accelerations: viscosity + gravity.
  cpu.computeForces(0.0f), ocl.computeForces(0.0f);
  ASSERT_EQ(ocl.firstNonFinite(), ff::Phase::Count);
  std::vector<float> ax, ay, az;
  ocl.readAccel(ax, ay, az);
  expectClose("forces ax", cpu.fluid().ax, ax);
  expectClose("forces ay", cpu.fluid().ay, ay);
  expectClose("forces az", cpu.fluid().az, az);

  // Control scale s_i and u_bar (over the fluid as the grid phase sorted it).
  cpu.computeControlScale(), ocl.computeControlScale();
  ASSERT_EQ(ocl.firstNonFinite(), ff::Phase::Count);
  ff::ControlSet cs;
  ff::ControlFields cf;
  ocl.readControl(cs, cf);
  const ff::ControlFields& ref = cpu.controller().fields();
  expectClose("control scale s", ref.s, cf.s);
  expectClose("u_bar x", ref.ux, cf.ux);
  expectClose("u_bar y", ref.uy, cf.uy);
  expectClose("u_bar z", ref.uz, cf.uz);
  expectControlScaleIsTheSum(cs, cf, fo, params);

  // Control forces (added to the accelerations); the control particles' grid.
  cpu.applyControlForces(dt), ocl.applyControlForces(dt);
  ASSERT_EQ(ocl.firstNonFinite(), ff::Phase::Count);
  {
    const ff::ControlSet& c = cpu.controller().set();
    ff::UniformGrid g;
    g.build(c.size(), c.x.data(), c.y.data(), c.z.data(), params.control.radius / FF_CONTROL_GRID_DIVISIONS,
            p->scene.container.min.data(), p->scene.container.max.data(), ff::gridCellCap(c.size()));
    const ff::OpenClBackend::GridSnapshot snap = ocl.readGrid(ff::OpenClBackend::GridKind::Control);
    expectGridEqual("control grid", g, snap, true);
    expectGridEqual("control grid (OpenMP backend)", cpu.controller().controlGrid(), snap, true);
  }
  ocl.readAccel(ax, ay, az);
  // The control's accelerations are judged on the scale of gravity at least:
  // every particle feels it, and a net acceleration near zero (gravity
  // carried by the control, or the recapture's relaxation towards its speed
  // cancelling the particle's own) would otherwise make one rounding of its
  // terms look like a large relative error. Under fuse-all emulation with the
  // recapture on, relative to |a| alone, the largest was 1.2e-5.
  const double g = std::fabs(double(params.fluid.gravity[1]));
  expectClose("with control ax", cpu.fluid().ax, ax, g);
  expectClose("with control ay", cpu.fluid().ay, ay, g);
  expectClose("with control az", cpu.fluid().az, az, g);

  // The pressure solve (WCSPH: symmetric pressure force and the walls'), added last.
  cpu.solvePressure(dt), ocl.solvePressure(dt);
  ASSERT_EQ(ocl.firstNonFinite(), ff::Phase::Count);
  ocl.readAccel(ax, ay, az);
  expectClose("with pressure ax", cpu.fluid().ax, ax);
  expectClose("with pressure ay", cpu.fluid().ay, ay);
  expectClose("with pressure az", cpu.fluid().az, az);

  // Integration.
  const ff::FluidState before = fo;  // the fluid has not moved since the grid phase
  const std::vector<float> accel[3] = {ax, ay, az};
  cpu.integrate(dt), ocl.integrate(dt);
  ASSERT_EQ(ocl.firstNonFinite(), ff::Phase::Count);
  ocl.readFluid(fo);
  expectSymplecticEuler(before, accel, fo, params, p->scene.container, dt);
  fc = cpu.fluid().s;
  expectClose("integrated x", fc.x, fo.x);
  expectClose("integrated y", fc.y, fo.y);
  expectClose("integrated z", fc.z, fo.z);
  expectClose("integrated vx", fc.vx, fo.vx);
  expectClose("integrated vy", fc.vy, fo.vy);
  expectClose("integrated vz", fc.vz, fo.vz);

  // One shape-matching step: rotations, goals, control particles.
  const float sm_dt = params.shape.time_step;
  EXPECT_EQ(cpu.shapeMatching(sm_dt), 1);
  EXPECT_EQ(ocl.shapeMatching(sm_dt), 1);
  ASSERT_EQ(ocl.firstNonFinite(), ff::Phase::Count);
  std::vector<ff_quat> q;
  ocl.readClusterRotations(q);
  const std::vector<ff_quat>& qref = cpu.controller().clusterRotations();
  ASSERT_EQ(q.size(), qref.size());
  double qerr = 0.0;
  for (size_t c = 0; c < q.size(); ++c) {
    const ff_quat a = qref[c], b = q[c];
    const double dm =
        std::fabs(a.x - b.x) + std::fabs(a.y - b.y) + std::fabs(a.z - b.z) + std::fabs(a.w - b.w);
    const double dp =
        std::fabs(a.x + b.x) + std::fabs(a.y + b.y) + std::fabs(a.z + b.z) + std::fabs(a.w + b.w);
    qerr = std::max(qerr, std::min(dm, dp));  // q and -q are the same rotation
  }
  std::printf("  %-28s max abs %.3g   (%zu clusters)\n", "cluster rotations", qerr, q.size());
  for (const ff_quat& r : q)  // rotations: unit quaternions
    ASSERT_NEAR(std::sqrt(double(r.x) * r.x + double(r.y) * r.y + double(r.z) * r.z + double(r.w) * r.w), 1.0,
                1e-5);
  EXPECT_LE(qerr, g_tol);
  g_worst = std::max(g_worst, qerr);
  std::vector<float> gx, gy, gz;
  ocl.readGoals(gx, gy, gz);
  expectClose("goal x", cpu.controller().goalX(), gx);
  expectClose("goal y", cpu.controller().goalY(), gy);
  expectClose("goal z", cpu.controller().goalZ(), gz);
  ocl.readControl(cs, cf);
  const ff::ControlSet& cref = cpu.controller().set();
  expectClose("control x", cref.x, cs.x);
  expectClose("control y", cref.y, cs.y);
  expectClose("control z", cref.z, cs.z);
  const double x_rms =
      std::sqrt((rms(cref.x) * rms(cref.x) + rms(cref.y) * rms(cref.y) + rms(cref.z) * rms(cref.z)) / 3.0);
  const double v_scale = params.shape.stiffness / sm_dt * x_rms;
  expectClose("control vx", cref.vx, cs.vx, v_scale);
  expectClose("control vy", cref.vy, cs.vy, v_scale);
  expectClose("control vz", cref.vz, cs.vz, v_scale);
  // The clock: two fluid steps of 0.004 s hold one shape-matching step of 0.005 s.
  EXPECT_EQ(cpu.shapeMatching(dt), ocl.shapeMatching(dt));
  EXPECT_EQ(cpu.shapeMatching(dt), ocl.shapeMatching(dt));
  EXPECT_NEAR(cpu.controller().clock(), ocl.shapeMatchingClock(), 1e-12);

  // Metrics (float partial sums on the device, double on the host).
  const ff::StepMetrics mc = cpu.computeMetrics(), mo = ocl.computeMetrics();
  std::printf(
      "  metrics cpu: iou %.6f coverage %.6f max_speed %.6f density_error %.6f ke %.6g max_rho %.3f\n",
      mc.iou, mc.coverage, mc.max_speed, mc.density_error, mc.kinetic_energy, mc.max_density);
  std::printf(
      "  metrics ocl: iou %.6f coverage %.6f max_speed %.6f density_error %.6f ke %.6g max_rho %.3f\n",
      mo.iou, mo.coverage, mo.max_speed, mo.density_error, mo.kinetic_energy, mo.max_density);
  {  // kinetic energy 1/2 m sum |v|^2 and the top speed, from the fluid itself
    ocl.readFluid(fo);
    double ke = 0.0, top = 0.0;
    for (size_t i = 0; i < fo.size(); ++i) {
      const double v2 =
          double(fo.vx[i]) * fo.vx[i] + double(fo.vy[i]) * fo.vy[i] + double(fo.vz[i]) * fo.vz[i];
      ke += 0.5 * params.fluid.particle_mass * v2, top = std::max(top, std::sqrt(v2));
    }
    EXPECT_GT(ke, 0.0);
    EXPECT_NEAR(mo.kinetic_energy, ke, 1e-5 * ke);
    EXPECT_NEAR(mo.max_speed, top, 1e-6 * top);
  }
  EXPECT_GT(mc.iou, 0.0);
  EXPECT_NEAR(mo.iou, mc.iou, 1e-3);  // a voxel whose density sits exactly on the threshold may flip
  EXPECT_NEAR(mo.coverage, mc.coverage, kTol * std::max(1.0, mc.coverage));
  EXPECT_NEAR(mo.max_speed, mc.max_speed, kTol * mc.max_speed);
  EXPECT_NEAR(mo.density_error, mc.density_error, kTol * mc.density_error);
  EXPECT_NEAR(mo.compression, mc.compression, kTol * std::max(mc.compression, 1e-3));
  EXPECT_NEAR(mo.kinetic_energy, mc.kinetic_energy, kTol * mc.kinetic_energy);
  EXPECT_NEAR(mo.max_density, mc.max_density, kTol * mc.max_density);
  EXPECT_EQ(mo.control_count, mc.control_count);
  // filled shares the iou's voxel counts; captured and stray count particles
  // by the same shared formulas (ff_metrics.h) and the reach of the control
  // forces, so they agree exactly.
  std::printf("  filled cpu %.6f ocl %.6f   captured cpu %.6f ocl %.6f   stray cpu %.6f ocl %.6f\n",
              mc.filled, mo.filled, mc.captured, mo.captured, mc.stray, mo.stray);
  EXPECT_GT(mc.filled, 0.0);
  EXPECT_GT(mc.captured, 0.0);
  EXPECT_NEAR(mo.filled, mc.filled, 1e-3);
  EXPECT_EQ(mo.captured, mc.captured);
  EXPECT_EQ(mo.stray, mc.stray);
  // filled_thin: the thin voxels' share of the same voxel counts (the OpenCL
  // backend marks them in its target buffer, the CPU's passes a mask).
  const long thin = ff::metricsThinVoxels(*p->sim->target(), params.control.radius).count;
  std::printf("  filled_thin cpu %.6f ocl %.6f over %ld thin voxels\n", mc.filled_thin, mo.filled_thin, thin);
  if (thin == 0) {
    EXPECT_EQ(mc.filled_thin, 1.0);
  }
  EXPECT_NEAR(mo.filled_thin, mc.filled_thin, thin > 0 ? 1.0 / double(thin) + 1e-12 : 0.0);

  // The next grid build reuses the metrics' index grid: still the CPU's order.
  cpu.buildGrid(), ocl.buildGrid();
  ocl.readFluid(fo);
  EXPECT_TRUE(cpu.fluid().s.id == fo.id) << "sorted order differs after the metrics' grid";
  expectGridEqual("fluid grid after metrics", cpu.fluid().grid,
                  ocl.readGrid(ff::OpenClBackend::GridKind::Fluid), false);
}

// filled_thin follows the control radius edited after the target (bit 2 of
// the target buffer and the third counter), as on the CPU backend
// (test_fluid_shares.cpp).
TEST(OpenClPhases, FilledThinFollowsAControlRadiusEditedAfterTheTarget) {
  const auto ocl = openClBackend();
  ASSERT_TRUE(ocl);
  fftest::expectFilledThinFollowsTheRadius(*ocl);
}

TEST(OpenClPhases, EachPhaseMatchesTheCpuBackend) {
  checkEachPhase(ff::OpenClBackend::KernelVariant::Auto, true);
}

// Adaptive control (thin features): a thin plate (a box 1 x 0.12 x 1) gives
// its control particles their own radii, most below the control radius; each
// phase still agrees bit for bit on PoCL (and within the variant tests'
// 4 ulp in the one-particle-per-work-item kernels), and eq. 5's
// scale is the brute-force sum within each particle's own radius.
ff::SceneDesc thinPlateScene() {
  ff::SceneDesc s = fftest::blockScene(ff::Vec3(0.3f, 0.2f, 0.3f), ff::Vec3(0.08f, 0.0f, 0.08f), 20, 8, 20);
  ff::TargetSpec plate = fftest::target(ff::TargetKind::Box, 700);
  plate.box_size = ff::Vec3(1.0f, 0.12f, 1.0f);
  s.schedule.push_back({0.0, plate});
  s.params.control.adaptive = 1;
  return s;
}

TEST(OpenClPhases, ThinPlateOwnRadiiMatchTheCpuBackend) {
  {
    ff::Simulation sim(thinPlateScene(), std::make_unique<ff::CpuBackend>(2));
    ff::ControlSet c;
    ff::ControlFields f;
    sim.backend().readControl(c, f);
    ASSERT_EQ(c.radius_scale.size(), c.size());
    const size_t smaller = size_t(
        std::count_if(c.radius_scale.begin(), c.radius_scale.end(), [](float s) { return s < 0.99f; }));
    std::printf("  %zu of %zu control particles with a radius below the control radius\n", smaller, c.size());
    EXPECT_GT(smaller, c.size() / 2) << "the thin plate did not get smaller radii";
  }
  checkEachPhase(ff::OpenClBackend::KernelVariant::Auto, true, thinPlateScene());
  checkEachPhase(ff::OpenClBackend::KernelVariant::Scalar, false, thinPlateScene());
}

// Both variants of the neighbour kernels, whatever the device: the one for
// GPUs (one particle per work-item) and the one for CPUs (8 as float8 lanes).
TEST(OpenClPhases, OneParticlePerWorkItemMatchesTheCpuBackend) {
  checkEachPhase(ff::OpenClBackend::KernelVariant::Scalar);
}
TEST(OpenClPhases, EightLanesPerWorkItemMatchTheCpuBackend) {
  checkEachPhase(ff::OpenClBackend::KernelVariant::Lanes);
}

// The recapture's field of targets (ff_recapture_field.h) and the forces it
// aims, on a torus formed over a wide block: fluid in the torus's hole and
// around the ring is out of reach, so the field is read. Both backends build
// the same field (exactly: indices) and the same accelerations (bit for bit
// on PoCL, in both kernel variants); and the field is what it claims to be,
// checked by brute force over all control particles: every cell names an
// unfilled control particle near the nearest unfilled one to its centre. It is
// not always that one: a field cell keeps one control particle of those in it
// (the nearest its own centre), so a farther cell may only see a neighbour of
// its nearest, up to a field cell's diagonal away. Measured: 0.08 of a field
// cell farther on average, 0.43 at worst; bounds here: 0.15 and the diagonal.
ff::SceneDesc torusScene() {
  ff::SceneDesc s =
      fftest::blockScene(ff::Vec3(0.36f, 0.25f, 0.36f), ff::Vec3(0.085f, 0.0f, 0.085f), 30, 7, 30);
  ff::TargetSpec torus = fftest::target(ff::TargetKind::Torus, 700);
  torus.torus_major = 1.0f, torus.torus_minor = 0.3f;
  s.schedule.push_back({0.0, torus});
  return s;
}

// full: the torus lies in a block of fluid (fftest::immersedTorusScene): no
// control particle is unfilled, and the field names any control particle.
void checkRecaptureField(ff::OpenClBackend::KernelVariant variant, bool full = false) {
  auto p = makePair(3, full ? fftest::immersedTorusScene() : torusScene());
  ASSERT_TRUE(p);
  ff::CpuBackend& cpu = p->cpu;
  ff::OpenClBackend& ocl = *p->ocl;
  ocl.setKernelVariant(variant);
  const bool pocl = ff::roundsAsTheCpuBackend(ocl.deviceInfo());
  g_tol = pocl ? 0.0 : kTol;
  const ff::Params& params = p->sim->scene().params;
  const float dt = params.fluid.time_step;
  for (ff::Backend* b : {static_cast<ff::Backend*>(&cpu), static_cast<ff::Backend*>(&ocl)}) {
    b->buildGrid(), b->computeDensity(), b->computeForces(0.0f), b->computeControlScale(),
        b->applyControlForces(dt);
  }
  ASSERT_EQ(ocl.firstNonFinite(), ff::Phase::Count);
  const ff::RecaptureField& field = cpu.controller().recaptureField();
  const std::vector<uint32_t> seeds = ocl.readRecaptureField();
  ASSERT_FALSE(field.seeds().empty());
  EXPECT_TRUE(seeds == field.seeds()) << "the recapture's fields differ";
  // Brute force: the unfilled control particles (all of them where none
  // is), in the control grid's order.
  const ff::ControlSet& c = cpu.controller().set();
  const std::vector<float>& s = cpu.controller().fields().s;
  const std::vector<uint32_t>& order = cpu.controller().controlGrid().order();
  const ff::RecaptureFieldGeom& g = field.geom();
  size_t unfilled = 0, exact = 0;
  double excess = 0.0;
  for (uint32_t k = 0; k < order.size(); ++k) unfilled += s[order[k]] > 0.5f;
  if (full)
    ASSERT_EQ(unfilled, 0u) << "the immersed torus has an unfilled control particle";
  else
    ASSERT_GT(unfilled, 0u);
  auto candidate = [&](uint32_t i) { return full || s[i] > 0.5f; };
  double worst = 0.0;
  for (int z = 0; z < g.m[2]; ++z)
    for (int y = 0; y < g.m[1]; ++y)
      for (int x = 0; x < g.m[0]; ++x) {
        const double q[3] = {g.o[0] + (x + 0.5) * g.fcell, g.o[1] + (y + 0.5) * g.fcell,
                             g.o[2] + (z + 0.5) * g.fcell};
        auto dist = [&](uint32_t i) {
          return std::sqrt(std::pow(c.x[i] - q[0], 2) + std::pow(c.y[i] - q[1], 2) +
                           std::pow(c.z[i] - q[2], 2));
        };
        double nearest = 1e30;
        for (uint32_t k = 0; k < order.size(); ++k)
          if (candidate(order[k])) nearest = std::min(nearest, dist(order[k]));
        const uint32_t k = field.seeds()[(size_t(z) * g.m[1] + y) * g.m[0] + x];
        ASSERT_LT(k, order.size());
        EXPECT_TRUE(candidate(order[k])) << "a field cell names a filled control particle";
        const double d = dist(order[k]);
        worst = std::max(worst, d - nearest);
        excess += d - nearest;
        exact += d == nearest;
      }
  std::printf(
      "  recapture field: %zu cells, %zu unfilled control particles of %zu; %zu cells exact, worst "
      "%.3g m and on average %.3g m farther than the nearest (field cell %.3g m)\n",
      g.cells(), unfilled, order.size(), exact, worst, excess / double(g.cells()), g.fcell);
  EXPECT_LE(worst, std::sqrt(3.0) * g.fcell);
  EXPECT_LE(excess / double(g.cells()), 0.15 * g.fcell);
  // The forces: the recapture acts on fluid out of reach here.
  const std::vector<uint8_t>& reached = cpu.controller().reached();
  EXPECT_GT(std::count(reached.begin(), reached.end(), uint8_t(0)), 10) << "no fluid out of reach";
  std::vector<float> ax, ay, az;
  ocl.readAccel(ax, ay, az);
  const double grav = std::fabs(double(params.fluid.gravity[1]));
  expectClose("recaptured ax", cpu.fluid().ax, ax, grav);
  expectClose("recaptured ay", cpu.fluid().ay, ay, grav);
  expectClose("recaptured az", cpu.fluid().az, az, grav);
}

TEST(OpenClPhases, RecaptureFieldAndForcesMatchTheCpuBackendOneParticlePerWorkItem) {
  checkRecaptureField(ff::OpenClBackend::KernelVariant::Scalar);
}
TEST(OpenClPhases, RecaptureFieldAndForcesMatchTheCpuBackendEightLanes) {
  checkRecaptureField(ff::OpenClBackend::KernelVariant::Lanes);
}
// A shape that reads full: the recapture still acts on the fluid out of
// reach, aimed through a field of all the control particles.
TEST(OpenClPhases, RecaptureOfAFullShapeMatchesTheCpuBackendOneParticlePerWorkItem) {
  checkRecaptureField(ff::OpenClBackend::KernelVariant::Scalar, true);
}
TEST(OpenClPhases, RecaptureOfAFullShapeMatchesTheCpuBackendEightLanes) {
  checkRecaptureField(ff::OpenClBackend::KernelVariant::Lanes, true);
}

// GPU rounding emulated on PoCL (ff::GpuRounding): the kernels built as a GPU
// compiler may build them, with multiply-adds fused. Each phase must stay
// within the GPU tolerance, and the emulation must change the results (else
// it emulates nothing).
class GpuRoundingEmulation {
 public:
  explicit GpuRoundingEmulation(const char* mode) { setenv("FLOWFORM_CL_GPU_ROUNDING", mode, 1); }
  ~GpuRoundingEmulation() { unsetenv("FLOWFORM_CL_GPU_ROUNDING"); }
};

void checkEachPhaseUnderGpuRounding(const char* mode, ff::OpenClBackend::KernelVariant variant) {
  GpuRoundingEmulation emulate(mode);
  std::printf("GPU rounding emulated: %s\n", mode);
  checkEachPhase(variant);
  EXPECT_EQ(g_tol, kTol);
  EXPECT_GT(g_worst, 0.0) << "FLOWFORM_CL_GPU_ROUNDING=" << mode << " did not change any result";
  std::printf("largest error under %s: %.3g (tolerance %.3g)\n", mode, g_worst, g_tol);
}

TEST(OpenClPhases, EmulatedGpuRoundingContractedStaysWithinTheGpuTolerance) {
  checkEachPhaseUnderGpuRounding("contract", ff::OpenClBackend::KernelVariant::Scalar);
  checkEachPhaseUnderGpuRounding("contract", ff::OpenClBackend::KernelVariant::Lanes);
}
TEST(OpenClPhases, EmulatedGpuRoundingFusedEverywhereStaysWithinTheGpuTolerance) {
  checkEachPhaseUnderGpuRounding("fuse-all", ff::OpenClBackend::KernelVariant::Scalar);
  checkEachPhaseUnderGpuRounding("fuse-all", ff::OpenClBackend::KernelVariant::Lanes);
}

TEST(OpenClPhases, StableSortKeepsInputOrderWithinCells) {
  // Dense: many points per cell, given in scrambled order. The order within a
  // cell must be the input order (what UniformGrid's sequential scatter gives),
  // whatever order the device's atomics run in. Sparse: points spread over a
  // metre, so the grid has ~50k cells (gridCellCap) and the prefix scan two levels.
  auto ocl = openClBackend();
  ASSERT_TRUE(ocl);
  ff::Params params;
  ff::ContainerDesc box;
  box.max = ff::Vec3(1.0f, 1.0f, 1.0f);
  // Both variants: the scan in serial chunks (CPU devices) and by work-groups (GPUs).
  for (const auto variant :
       {ff::OpenClBackend::KernelVariant::Scalar, ff::OpenClBackend::KernelVariant::Lanes})
    for (const float extent : {0.04f, 1.0f}) {
      ocl->setKernelVariant(variant);
      ff::FluidState f;
      std::mt19937 rng(7);
      std::uniform_real_distribution<float> u(0.01f, 0.01f + extent);
      for (int i = 0; i < 5000; ++i) f.push(u(rng), u(rng), u(rng), 0.0f, 0.0f, 0.0f);
      ff::UniformGrid g;
      g.build(f.size(), f.x.data(), f.y.data(), f.z.data(), params.fluid.smoothing_radius, box.min.data(),
              box.max.data(), ff::gridCellCap(f.size()));
      std::vector<uint32_t> ids(g.order().size());
      for (size_t k = 0; k < ids.size(); ++k) ids[k] = f.id[g.order()[k]];
      for (int rep = 0; rep < 2; ++rep) {
        ocl->init(params, box, f);
        ocl->buildGrid();
        ff::FluidState sorted;
        ocl->readFluid(sorted);
        EXPECT_TRUE(ids == sorted.id)
            << "extent " << extent << ", repeat " << rep << ", lanes " << ocl->usesLanes();
        expectGridEqual("grid", g, ocl->readGrid(ff::OpenClBackend::GridKind::Fluid), false);
      }
    }
}

TEST(OpenClPhases, GridHeaderMatchesUniformGrid) {
  // kernels/common/ff_grid.h compiles as C++ too: its cell arithmetic is UniformGrid's.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.1f, 0.5f);
  std::vector<float> x(500), y(500), z(500);
  for (size_t i = 0; i < x.size(); ++i) x[i] = u(rng), y[i] = u(rng), z[i] = u(rng);
  ff::UniformGrid g;
  g.build(x.size(), x.data(), y.data(), z.data(), 0.03f);
  const float inv = 1.0f / g.cellSize();
  for (size_t i = 0; i < x.size(); ++i) {
    const float px = x[i] * 1.3f - 0.05f;  // also points outside the grid
    ASSERT_EQ(ff_cell_coord(px, g.originX(), inv, g.nx()), g.cellCoord(px, g.originX(), g.nx()));
    const int cx = g.cellCoord(x[i], g.originX(), g.nx()), cy = g.cellCoord(y[i], g.originY(), g.ny()),
              cz = g.cellCoord(z[i], g.originZ(), g.nz());
    uint b[9], e[9];
    ff_grid_ranges(g.cellStart().data(), cx, cy, cz, g.nx(), g.ny(), g.nz(), b, e);
    std::vector<std::pair<uint32_t, uint32_t>> mine, ref;
    for (int r = 0; r < 9; ++r)
      if (b[r] < e[r]) mine.emplace_back(b[r], e[r]);
    g.forEachRange(x[i], y[i], z[i], [&](uint32_t bb, uint32_t ee) { ref.emplace_back(bb, ee); });
    ASSERT_EQ(mine, ref);
  }
}

TEST(OpenClHost, KernelSourcesResolveFromTheEmbeddedFiles) {
  const std::vector<std::string> files = ff::embeddedKernelFiles();
  for (const char* phase : {"kernels/grid.cl", "kernels/density.cl", "kernels/forces.cl",
                            "kernels/control_scale.cl", "kernels/control_forces.cl",
                            "kernels/shape_matching.cl", "kernels/integrate.cl", "kernels/metrics.cl"})
    EXPECT_NE(std::find(files.begin(), files.end(), phase), files.end()) << phase;
  std::set<std::string> included;
  const std::string src = ff::resolveKernelSource("kernels/control_forces.cl", included);
  EXPECT_EQ(src.find("#include \""), std::string::npos);  // only ff_compat.h's C++ branch keeps <cmath>
  EXPECT_NE(src.find("ff_velocity_force_implicit"), std::string::npos);
  EXPECT_TRUE(included.count("kernels/common/ff_sph.h") && included.count("kernels/common/ff_compat.h"));
  // A header already included is not repeated.
  const std::string again = ff::resolveKernelSource("kernels/density.cl", included);
  EXPECT_EQ(again.find("FF_SPH_H"), std::string::npos);
}

// The code of OpenCL C source: no comments, no preprocessor lines other than
// #define (a macro's body is the code where it is used), and not the C++
// side's math macros of ff_compat.h (the lines with std::).
std::string codeOnly(const std::string& src) {
  std::string text;
  for (size_t i = 0; i < src.size(); ++i) {
    if (src.compare(i, 2, "//") == 0) {
      i = src.find('\n', i);
      if (i == std::string::npos) break;
    } else if (src.compare(i, 2, "/*") == 0) {
      i = src.find("*/", i + 2);
      if (i == std::string::npos) break;
      ++i;
      continue;
    }
    text += src[i];
  }
  std::istringstream in(text);
  std::string line, out;
  bool continued = false;
  while (std::getline(in, line)) {
    const size_t first = line.find_first_not_of(" \t");
    const bool directive =
        continued ||
        (first != std::string::npos && line[first] == '#' && line.compare(first, 7, "#define") != 0) ||
        line.find("std::") != std::string::npos;
    continued = directive && !line.empty() && line.back() == '\\';
    if (!directive) out += line + '\n';
  }
  return out;
}

// The rounding policy in the sources (docs/GPU.md, "Rounding"): every kernel
// file switches contraction off before its first kernel, and no kernel calls
// a builtin that a device may round differently from the C++ side (dot, cross
// and sin/cos are written out in kernels/common/; cbrt appears only in
// ff_control_full_coverage, which the host evaluates).
TEST(OpenClHost, KernelsFollowTheRoundingPolicy) {
  const char* builtins[] = {"dot",   "cross",    "sin",    "cos",       "tan",   "exp",
                            "log",   "pow",      "mad",    "fma",       "rsqrt", "native_",
                            "half_", "distance", "length", "normalize", "fast_"};
  for (const std::string& file : ff::embeddedKernelFiles()) {
    std::set<std::string> included;
    const std::string raw = ff::resolveKernelSource(file, included);
    const size_t pragma = raw.find("#pragma OPENCL FP_CONTRACT OFF"), kernel = raw.find("__kernel");
    EXPECT_NE(pragma, std::string::npos) << file;
    EXPECT_LT(pragma, kernel) << file;
    const std::string src = codeOnly(raw);
    // Every identifier followed by "(": a call (or a declaration) of that name.
    auto ident = [](char c) { return std::isalnum((unsigned char)c) || c == '_'; };
    for (size_t i = 0; i < src.size(); ++i) {
      if (!ident(src[i]) || (i > 0 && ident(src[i - 1]))) continue;
      size_t end = i;
      while (end < src.size() && ident(src[end])) ++end;
      const std::string name = src.substr(i, end - i);
      size_t k = end;
      while (k < src.size() && src[k] == ' ') ++k;
      if (k >= src.size() || src[k] != '(') continue;
      for (const char* b : builtins) {
        const std::string bn = b;
        const bool hit = bn.back() == '_' ? name.compare(0, bn.size(), bn) == 0 : name == bn;
        EXPECT_FALSE(hit) << file << " calls the builtin " << name << ": "
                          << src.substr(i, src.find('\n', i) - i);
      }
      i = end;
    }
  }
  // The emulation switches the pragmas on, and only when asked.
  const std::string off = "#pragma OPENCL FP_CONTRACT OFF\nx = a * b + c;\n";
  EXPECT_EQ(ff::withGpuRoundingEmulation(off), off);
  {
    GpuRoundingEmulation emulate("contract");
    EXPECT_EQ(ff::withGpuRoundingEmulation(off).find("FP_CONTRACT OFF"), std::string::npos);
    EXPECT_NE(ff::withGpuRoundingEmulation(off).find("FP_CONTRACT ON"), std::string::npos);
  }
  {
    GpuRoundingEmulation emulate("sometimes");
    EXPECT_THROW(ff::gpuRoundingEmulation(), ff::Error);
  }
}

TEST(OpenClHost, BuildFailureCarriesTheBuildLog) {
  auto ocl = openClBackend();
  ASSERT_TRUE(ocl);
  ff::ClContext ctx(ocl->deviceInfo().index);
  try {
    ff::buildProgramSource(
        ctx, "#line 1 \"kernels/broken.cl\"\n__kernel void k(__global float* a) { a[0] = nope; }\n");
    FAIL() << "expected a build error";
  } catch (const ff::Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("CL_BUILD_PROGRAM_FAILURE"), std::string::npos) << m;
    EXPECT_NE(m.find("build log"), std::string::npos) << m;
    EXPECT_NE(m.find("nope"), std::string::npos) << m;  // the compiler's own message
    EXPECT_NE(m.find(ctx.info().name), std::string::npos) << m;
  }
}

TEST(OpenClHost, ErrorsNameTheCallAndTheCode) {
  EXPECT_STREQ(ff::clErrorName(CL_OUT_OF_RESOURCES), "CL_OUT_OF_RESOURCES");
  EXPECT_STREQ(ff::clErrorName(CL_INVALID_WORK_GROUP_SIZE), "CL_INVALID_WORK_GROUP_SIZE");
  EXPECT_STREQ(ff::clErrorName(-1001), "CL_PLATFORM_NOT_FOUND_KHR");
  EXPECT_STREQ(ff::clErrorName(12345), "CL_UNKNOWN_ERROR");
  auto ocl = openClBackend();
  ASSERT_TRUE(ocl);
  ff::ClContext ctx(ocl->deviceInfo().index);
  try {
    ff::clGuard("a zero-sized buffer", [&] { return cl::Buffer(ctx.context(), CL_MEM_READ_WRITE, 0); });
    FAIL() << "expected an error";
  } catch (const ff::Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("clCreateBuffer"), std::string::npos) << m;
    EXPECT_NE(m.find("CL_INVALID_BUFFER_SIZE"), std::string::npos) << m;
    EXPECT_NE(m.find("a zero-sized buffer"), std::string::npos) << m;
  }
  try {
    ff::OpenClBackend bad(1000);
    FAIL() << "expected an error";
  } catch (const ff::Error& e) {
    EXPECT_NE(std::string(e.what()).find("--device 1000"), std::string::npos) << e.what();
  }
}

TEST(OpenClHost, BackendSelection) {
  std::string note;
  auto cpu = ff::makeBackend("cpu", -1, 2, &note);
  EXPECT_EQ(cpu->name(), "cpu");
  EXPECT_TRUE(note.empty());
  EXPECT_THROW(ff::makeBackend("cuda", -1, 2, &note), ff::Error);
  EXPECT_THROW(ff::makeBackend("cpu", 0, 2, &note), ff::Error);

  std::vector<ff::ClDeviceInfo> devices;
  try {
    devices = ff::listClDevices();
  } catch (const ff::Error& e) {
    FAIL() << "no OpenCL platform: " << e.what() << " (PoCL is a declared dependency)";
  }
  ASSERT_FALSE(devices.empty());
  auto explicit_cl = ff::makeBackend("opencl", int(devices.size()) - 1, 2, &note);
  EXPECT_EQ(explicit_cl->name(), "opencl");
  EXPECT_THROW(ff::makeBackend("opencl", int(devices.size()), 2, &note), ff::Error);

  const bool has_gpu =
      std::any_of(devices.begin(), devices.end(), [](const ff::ClDeviceInfo& d) { return d.isGpu(); });
  auto automatic = ff::makeBackend("auto", -1, 2, &note);
  if (has_gpu) {
    EXPECT_EQ(automatic->name(), "opencl");
  } else {
    EXPECT_EQ(automatic->name(), "cpu");
    EXPECT_NE(note.find("no OpenCL GPU found (platforms: " + devices[0].platform), std::string::npos) << note;
    EXPECT_NE(note.find("using the OpenMP CPU backend"), std::string::npos) << note;
    EXPECT_EQ(note.find('\n'), std::string::npos);
  }
}

}  // namespace
