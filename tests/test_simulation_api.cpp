// The engine API: target changes at any step, the schedule, the cache, the
// region, and NaN detection naming step and phase.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "control/control_set.h"
#include "core/error.h"
#include "core/param_table.h"
#include "cpu/backend_cpu.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"
#include "test_scenes.h"

namespace {

ff::SceneDesc smallScene() {
  return fftest::blockScene(ff::Vec3(0.2f, 0.2f, 0.2f), ff::Vec3(0.06f, 0.0f, 0.06f), 12, 12, 12);
}

// A scene on the water preset (shape_matching.time_step_fall 0.0904, which
// sets the shape-matching step at every target) that gives
// shape_matching.time_step in seconds runs on that step, at its first target
// and the next (a step given in seconds turns off its fall-time multiple);
// given with time_step_fall, the fall time sets it: time_step_fall
// sqrt(r / |g|), computed here.
TEST(SimulationApi, AShapeMatchingStepInSecondsInASceneIsTheStepTaken) {
  const std::string schedule =
      R"("preset": "water", "schedule": [{"time": 0, "target": "sphere"}, {"time": 0.008, "target": "box"}])";
  auto sceneWith = [&](const std::string& sm) {
    return ff::parseScene(fftest::blockSceneJson("sm", 0.2, 0.06, 0.06, 8,
                                                 schedule + R"(, "params": {"shape_matching": )" + sm + "}"),
                          "sm.json", ".");
  };
  ASSERT_GT(ff::presetParams("water").shape.time_step_fall, 0.0f);
  ff::Simulation sim(sceneWith(R"({"time_step": 0.003})"), std::make_unique<ff::CpuBackend>(1));
  ASSERT_NE(sim.target(), nullptr);
  EXPECT_EQ(sim.scene().params.shape.time_step, 0.003f);
  EXPECT_EQ(sim.scene().params.shape.time_step_fall, 0.0f);
  for (int i = 0; i < 3; ++i) sim.step();
  EXPECT_EQ(sim.target()->label, "box");
  EXPECT_EQ(sim.scene().params.shape.time_step, 0.003f);

  ff::Simulation fall(sceneWith(R"({"time_step": 0.003, "time_step_fall": 0.05})"),
                      std::make_unique<ff::CpuBackend>(1));
  ASSERT_NE(fall.target(), nullptr);
  const ff::Params& p = fall.scene().params;
  const double g = std::sqrt(double(p.fluid.gravity[0]) * p.fluid.gravity[0] +
                             double(p.fluid.gravity[1]) * p.fluid.gravity[1] +
                             double(p.fluid.gravity[2]) * p.fluid.gravity[2]);
  const double want = 0.05 * std::sqrt(double(p.control.radius) / g);
  EXPECT_NEAR(p.shape.time_step, want, 1e-6 * want);
  EXPECT_NE(p.shape.time_step, 0.003f);
}

// paramActs (what the viewer's panel shows and bench --stability sweeps)
// against runs: each number parameter that a rule of overrideRules names,
// doubled, changes the metrics of a few steps where it says the parameter
// acts, and leaves them the same bit for bit where it says another
// parameter overrides it, on both presets (paper: the paper's pull, the
// radius in metres, steps in seconds; water: normalised, the radius in
// control spacings, steps in fall times).
TEST(SimulationApi, AParameterActsWhereParamActsSaysSo) {
  std::vector<std::pair<std::string, std::string>> keys;
  for (const ff::OverrideRule& r : ff::overrideRules())
    if (std::string(r.key) != "units") keys.emplace_back(r.group, r.key);  // units: not a number
  ASSERT_GE(keys.size(), 7u);
  for (const char* preset : {"paper", "water"}) {
    ff::SceneDesc s = smallScene();
    s.preset = preset;
    s.params = ff::presetParams(preset);
    s.schedule.push_back({0.0, fftest::target(ff::TargetKind::Sphere, 200)});
    auto run = [&](const ff::Params& p) {
      ff::SceneDesc t = s;
      t.params = p;
      ff::Simulation sim(t, std::make_unique<ff::CpuBackend>(1));
      for (int i = 0; i < 4; ++i) sim.step();
      return std::vector<double>{sim.metrics().iou, sim.metrics().max_speed, sim.metrics().kinetic_energy,
                                 sim.metrics().coverage};
    };
    const std::vector<double> base = run(s.params);
    for (const auto& [group, key] : keys) {
      const auto it = std::find_if(ff::paramTable().begin(), ff::paramTable().end(),
                                   [&](const ff::ParamInfo& i) { return i.group == group && i.key == key; });
      ASSERT_NE(it, ff::paramTable().end()) << key;
      ASSERT_EQ(it->type, ff::ParamInfo::Type::Real) << key;
      ff::Params p = s.params;
      float& v = *static_cast<float*>(it->field(p));
      v *= 2.0f;
      const bool changed = run(p) != base;
      EXPECT_EQ(changed, ff::paramActs(*it, s.params)) << preset << " " << group << "." << key;
    }
  }
}

// Clusters are built when the control particles are placed. A change of the
// fields that build them (ShapeMatchParams::sameClusters: the stride, the
// half-width, the coarse level) through Simulation::setParams, as Python's
// set_params and a script's params action make it, takes effect at once:
// the run then has the clusters a run that started with those params has
// (the clusters are centred on the target's voxels, whatever the fluid).
// Other shape-matching fields keep the clusters as they are. Before, only
// the viewer re-placed them; elsewhere they waited for the next target.
// The control set of `sim`, read back from its backend.
ff::ControlSet controlOf(ff::Simulation& sim) {
  ff::ControlSet set;
  ff::ControlFields fields;
  sim.backend().readControl(set, fields);
  return set;
}

// The control set that a run of `s` started with `params` places first.
ff::ControlSet firstControl(ff::SceneDesc s, const ff::Params& params) {
  s.params = params;
  ff::Simulation sim(s, std::make_unique<ff::CpuBackend>(1));
  return controlOf(sim);
}

TEST(SimulationApi, AClusterChangeTakesEffectAtOnce) {
  ff::SceneDesc s = smallScene();
  s.schedule.push_back({0.0, fftest::target(ff::TargetKind::Sphere, 400)});
  auto count = [](const ff::ControlSet& set) {
    return set.clusters.start.empty() ? size_t(0) : set.clusters.start.size() - 1;
  };
  auto clusters = [&](ff::Simulation& sim) { return count(controlOf(sim)); };
  auto fresh = [&](const ff::Params& p) { return count(firstControl(s, p)); };
  ff::Simulation sim(s, std::make_unique<ff::CpuBackend>(1));
  sim.step();
  const size_t before = clusters(sim);
  ASSERT_EQ(before, fresh(s.params));
  ff::Params p = sim.scene().params;
  p.shape.stiffness = 0.4f;  // not a cluster field: the clusters stay
  sim.setParams(p);
  EXPECT_EQ(clusters(sim), before);
  p.shape.cluster_stride = 1;
  sim.setParams(p);
  const size_t finer = clusters(sim);
  EXPECT_GT(finer, before);
  EXPECT_EQ(finer, fresh(p));
  p.shape.coarse_clusters = 3;
  sim.setParams(p);
  EXPECT_GT(clusters(sim), finer);
  EXPECT_EQ(clusters(sim), fresh(p));
  sim.step();
  EXPECT_EQ(clusters(sim), fresh(p));
}

// control.adaptive, and with it on the control radius, are read as the
// control particles are placed (each one's radius_scale, a share of the
// radius; its clusters). A change through Simulation::setParams re-places
// them at once: the run then has the radius scales a run that started with
// those params has. Before, they waited for the next target.
TEST(SimulationApi, AnAdaptiveControlChangeTakesEffectAtOnce) {
  ff::SceneDesc s = smallScene();
  s.params.control.radius = 0.08f;  // wider than the torus's tube: its radius scales are below 1
  s.schedule.push_back({0.0, fftest::target(ff::TargetKind::Torus, 400)});
  auto scales = [](ff::Simulation& sim) { return controlOf(sim).radius_scale; };
  auto fresh = [&](const ff::Params& p) { return firstControl(s, p).radius_scale; };
  ff::Simulation sim(s, std::make_unique<ff::CpuBackend>(1));
  sim.step();
  const std::vector<float> one = scales(sim);
  ASSERT_FALSE(one.empty());
  EXPECT_EQ(*std::min_element(one.begin(), one.end()), 1.0f);
  ff::Params p = sim.scene().params;
  p.control.adaptive = 1;
  sim.setParams(p);
  const std::vector<float> own = scales(sim);
  EXPECT_LT(*std::min_element(own.begin(), own.end()), 1.0f);
  EXPECT_EQ(own, fresh(p));
  p.control.radius = 0.1f;
  sim.setParams(p);
  EXPECT_NE(scales(sim), own);
  EXPECT_EQ(scales(sim), fresh(p));
  p.control.adaptive = 0;
  sim.setParams(p);
  EXPECT_EQ(scales(sim), one);
}

TEST(SimulationApi, ScheduleChangesTargetsAtTheirTimes) {
  ff::SceneDesc s = smallScene();
  s.schedule.push_back({0.0, fftest::target(ff::TargetKind::Sphere, 400)});
  s.schedule.push_back({0.02, fftest::target(ff::TargetKind::Box, 400)});
  ff::Simulation sim(s, std::make_unique<ff::CpuBackend>());
  ASSERT_NE(sim.target(), nullptr);
  EXPECT_EQ(sim.target()->label, "sphere");
  for (int i = 0; i < 5; ++i) sim.step();  // t = 0.02
  sim.step();
  EXPECT_EQ(sim.target()->label, "box");
  EXPECT_EQ(sim.targetCacheSize(), 2u);
}

// setShapeMetricsOnRequest: the target's metrics only in the steps after
// requestMetrics(), the same bits there as a run that computes them every
// step (the best fit still advances every step), the last values carried
// between them, and the same fluid throughout (the physics never reads them).
TEST(SimulationApi, ShapeMetricsOnRequestAreTheEveryStepValues) {
  ff::SceneDesc s = smallScene();
  s.schedule.push_back({0.0, fftest::target(ff::TargetKind::Sphere, 400)});
  s.schedule.push_back({0.02, fftest::target(ff::TargetKind::Box, 400)});
  ff::Simulation every(s, std::make_unique<ff::CpuBackend>(1)), asked(s, std::make_unique<ff::CpuBackend>(1));
  asked.setShapeMetricsOnRequest(true);
  double carried = -1.0;
  for (int k = 1; k <= 12; ++k) {
    const bool request = k == 3 || k == 9 || k == 12;
    if (request) asked.requestMetrics();
    every.step(), asked.step();
    const ff::StepMetrics &a = every.metrics(), &b = asked.metrics();
    EXPECT_EQ(a.max_speed, b.max_speed) << "step " << k;
    EXPECT_EQ(a.density_error, b.density_error) << "step " << k;
    EXPECT_EQ(a.max_pressure, b.max_pressure) << "step " << k;
    EXPECT_EQ(a.coverage, b.coverage) << "step " << k;
    if (request) {
      EXPECT_GT(a.iou, 0.0) << "step " << k;
      EXPECT_EQ(a.iou, b.iou) << "step " << k;
      EXPECT_EQ(a.filled, b.filled) << "step " << k;
      EXPECT_EQ(a.captured, b.captured) << "step " << k;
      EXPECT_EQ(a.stray, b.stray) << "step " << k;
      EXPECT_EQ(a.filled_thin, b.filled_thin) << "step " << k;
      EXPECT_EQ(a.tilt, b.tilt) << "step " << k;
      EXPECT_EQ(a.base_height, b.base_height) << "step " << k;
      carried = b.iou;
    } else if (carried >= 0.0) {
      EXPECT_EQ(b.iou, carried) << "step " << k << ": the last computed value";
      EXPECT_NE(a.iou, carried) << "step " << k << ": the shape is still forming";
    }
  }
  ff::FluidState fa, fb;
  every.backend().readFluid(fa), asked.backend().readFluid(fb);
  EXPECT_EQ(fa.x, fb.x);
  EXPECT_EQ(fa.vy, fb.vy);
}

// StepMetrics::copyShapeMetrics (what a step without the target's metrics
// carries over) copies exactly the columns that measure the fluid against the
// target, named here, and leaves every other column as it was.
TEST(SimulationApi, CopyShapeMetricsCopiesTheTargetsColumnsAlone) {
  const std::set<std::string> target = {"iou",         "filled", "captured",   "stray",
                                        "filled_thin", "tilt",   "base_height"};
  ff::StepMetrics from;
  from.step = 1, from.time = 2, from.iou = 0.3, from.coverage = 0.4, from.max_speed = 5,
  from.density_error = 0.6;
  from.kinetic_energy = 7, from.control_count = 8, from.max_density = 9, from.substeps = 10;
  from.solver_iterations = 11, from.max_density_error = 12, from.solver_capped = 13, from.filled = 0.14;
  from.captured = 0.15, from.stray = 0.16, from.velocity_clamps = 17, from.compression = 0.18, from.tilt = 19;
  from.base_height = 0.2, from.filled_thin = 0.21;
  ff::StepMetrics to;
  to.copyShapeMetrics(from);
  const auto f = ff::metricValues(from), t = ff::metricValues(to), d = ff::metricValues(ff::StepMetrics());
  size_t copied = 0;
  for (size_t k = 0; k < f.size(); ++k) {
    const std::string name = ff::kMetricColumns[k].name;
    ASSERT_NE(f[k], d[k]) << name << ": the test gives every column a value of its own";
    const bool shape = target.count(name) != 0;
    EXPECT_EQ(t[k], shape ? f[k] : d[k]) << name;
    copied += shape;
  }
  EXPECT_EQ(copied, target.size());
}

TEST(SimulationApi, SetTargetAtAnyStepAndCacheReuse) {
  ff::SceneDesc s = smallScene();
  ff::Simulation sim(s, std::make_unique<ff::CpuBackend>());
  EXPECT_EQ(sim.target(), nullptr);
  for (int i = 0; i < 3; ++i) sim.step();
  sim.setTarget(fftest::target(ff::TargetKind::Torus, 500));
  const ff::TargetShape* torus = sim.target();
  ASSERT_NE(torus, nullptr);
  ff::ControlSet c;
  ff::ControlFields f;
  sim.backend().readControl(c, f);
  EXPECT_EQ(c.size(), torus->reference.size());
  EXPECT_NEAR(double(c.size()), 500.0, 15.0);
  for (int i = 0; i < 3; ++i) sim.step();
  sim.setTarget(fftest::target(ff::TargetKind::Capsule, 500));
  sim.setTarget(fftest::target(ff::TargetKind::Torus, 500));
  // Back to the torus: made from the fluid of the current shape, whose volume
  // differs, so the cached voxelisation is rescaled, not voxelised again.
  EXPECT_EQ(sim.targetVoxelisations(), 2u);
  EXPECT_EQ(sim.target()->reference.size(), torus->reference.size());
  EXPECT_EQ(sim.target()->label, "torus");
  sim.step();
  EXPECT_TRUE(std::isfinite(sim.metrics().iou));
}

TEST(SimulationApi, ControlParticlesFillTheRegionBoundingBox) {
  ff::SceneDesc s = smallScene();
  s.region.kind = ff::RegionDesc::Kind::Box;
  s.region.min = ff::Vec3(0.0f, 0.025f, 0.0f);
  s.region.max = ff::Vec3(0.2f, 0.06f, 0.2f);  // a middle layer of the block only
  s.schedule.push_back({0.0, fftest::target(ff::TargetKind::Box, 300)});
  ff::Simulation sim(s, std::make_unique<ff::CpuBackend>());
  ff::ControlSet c;
  ff::ControlFields f;
  sim.backend().readControl(c, f);
  ff::FluidState fl;
  sim.backend().readFluid(fl);
  long in_region = 0;
  ff::Vec3 lo(1, 1, 1), hi(-1, -1, -1);
  for (size_t i = 0; i < fl.size(); ++i) {
    ff::Vec3 p(fl.x[i], fl.y[i], fl.z[i]);
    if (p.y() < 0.025f || p.y() > 0.06f) continue;
    ++in_region, lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  EXPECT_EQ(sim.controlledCount(), in_region);
  // The reference particles' bounding box maps onto the region's: the control
  // particles span exactly the region's fluid bounding box.
  ff::Vec3 clo(1, 1, 1), chi(-1, -1, -1);
  for (size_t i = 0; i < c.size(); ++i) {
    ff::Vec3 p(c.x[i], c.y[i], c.z[i]);
    clo = clo.cwiseMin(p), chi = chi.cwiseMax(p);
  }
  EXPECT_LT((clo - lo).norm(), 1e-5f);
  EXPECT_LT((chi - hi).norm(), 1e-5f);
}

// Lowest point of the rigid goal shape around the placed particles' centre of mass.
double lowestGoal(const ff::ControlSet& c) {
  double cy = 0, rest_lo = 1e9;
  for (size_t i = 0; i < c.size(); ++i) cy += c.y[i], rest_lo = std::min(rest_lo, double(c.y0[i]));
  return cy / double(c.size()) + (rest_lo - c.rest_cy);
}

TEST(SimulationApi, PlacementFitsTheFormingShapeIntoTheContainer) {
  // A region on the floor: the box target of the same volume is taller than
  // the region, so around the region's centre it would reach below the floor.
  // Placement lifts it so that the rigid shape fits.
  ff::SceneDesc s = smallScene();
  s.region.kind = ff::RegionDesc::Kind::Box;
  s.region.min = ff::Vec3(0.0f, 0.0f, 0.0f);
  s.region.max = ff::Vec3(0.2f, 0.04f, 0.2f);
  s.schedule.push_back({0.0, fftest::target(ff::TargetKind::Box, 300)});
  ff::Simulation sim(s, std::make_unique<ff::CpuBackend>());
  ff::ControlSet c;
  ff::ControlFields f;
  sim.backend().readControl(c, f);
  const double g = lowestGoal(c);
  EXPECT_GE(g, 0.0);
  EXPECT_LT(g, 0.01);  // lifted by what is needed (half a voxel of margin), not more
}

TEST(SimulationApi, PlacementNeverLiftsTheParticlesOffTheirFluid) {
  // A thin layer: fitting the shape would need a lift larger than half the
  // layer; the lift stops there, so the particles still overlap the fluid.
  ff::SceneDesc s = smallScene();
  s.region.kind = ff::RegionDesc::Kind::Box;
  s.region.min = ff::Vec3(0.0f, 0.0f, 0.0f);
  s.region.max = ff::Vec3(0.2f, 0.012f, 0.2f);
  s.schedule.push_back({0.0, fftest::target(ff::TargetKind::Box, 300)});
  ff::Simulation sim(s, std::make_unique<ff::CpuBackend>());
  ff::ControlSet c;
  ff::ControlFields f;
  sim.backend().readControl(c, f);
  float lowest = 1e9f;
  for (float y : c.y) lowest = std::min(lowest, y);
  EXPECT_LT(lowest, 0.012f);
  EXPECT_LT(lowestGoal(c), 0.0);  // the floor lifts the rest while the shape forms
}

TEST(SimulationApi, ANewTargetIsMadeFromTheFluidOfTheCurrentShape) {
  // A block and a small blob far from it. The first target is made from all
  // the fluid; the next one only from the fluid that forms the current shape,
  // so the blob no longer counts.
  ff::SceneDesc s = smallScene();
  ff::FluidBlockDesc blob;
  blob.origin = ff::Vec3(0.005f, 0.0f, 0.005f);
  blob.dims[0] = blob.dims[1] = blob.dims[2] = 2;  // 8 particles in a corner
  s.fluid.push_back(blob);
  s.schedule.push_back({0.0, fftest::target(ff::TargetKind::Box, 400)});
  // Without the recapture, which brings the blob back into the shape on
  // purpose (tests/test_recapture.cpp): here the blob must stay away.
  s.params.control.recapture = 0.0f;
  ff::Simulation sim(s, std::make_unique<ff::CpuBackend>());
  EXPECT_EQ(sim.controlledCount(), 12 * 12 * 12 + 8);
  for (int i = 0; i < 50; ++i) sim.step();
  sim.setTarget(fftest::target(ff::TargetKind::Sphere, 400));
  EXPECT_LE(sim.controlledCount(), 12 * 12 * 12);
  EXPECT_GT(sim.controlledCount(), 12 * 12 * 12 / 2);
}

TEST(SimulationApi, EmptyRegionIsAClearError) {
  ff::SceneDesc s = smallScene();
  s.region.kind = ff::RegionDesc::Kind::Sphere;
  s.region.center = ff::Vec3(0.19f, 0.19f, 0.19f);
  s.region.radius = 0.005f;
  s.schedule.push_back({0.0, fftest::target(ff::TargetKind::Sphere, 300)});
  try {
    ff::Simulation sim(s, std::make_unique<ff::CpuBackend>());
    FAIL() << "expected an error";
  } catch (const ff::Error& e) {
    EXPECT_NE(std::string(e.what()).find("region"), std::string::npos) << e.what();
  }
}

TEST(SimulationApi, NanStopsTheRunNamingStepAndPhase) {
  ff::SceneDesc s = smallScene();
  auto backend = std::make_unique<ff::CpuBackend>();
  ff::CpuBackend* cpu = backend.get();
  ff::Simulation sim(s, std::move(backend));
  sim.step();
  sim.step();
  cpu->fluid().s.vx[7] = std::nanf("");  // the viscosity force is the first to read it
  try {
    sim.step();
    FAIL() << "expected an error";
  } catch (const ff::Error& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("step 2"), std::string::npos) << m;
    EXPECT_NE(m.find("'forces'"), std::string::npos) << m;
  }
}

TEST(SimulationApi, NanParametersAreRejected) {
  ff::SceneDesc s = smallScene();
  s.params.fluid.gas_constant = std::nanf("");
  EXPECT_THROW(ff::Simulation(s, std::make_unique<ff::CpuBackend>()), ff::Error);
}

}  // namespace
