// Microbenchmarks of each phase, on each backend present: the OpenMP backend
// and every OpenCL device, at 12k, 100k and 1M fluid particles. A sphere
// target with one control particle per four fluid particles, after 20 steps so
// that the state is a moving fluid, not a lattice. Phases run in profiling
// mode, so each call returns when its work is done (on OpenCL too).
//   ./build/flowform_bench --benchmark_filter='cpu/'
//   ./build/flowform_bench --benchmark_filter='opencl0/control'
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "host/backend_factory.h"
#include "sim/simulation.h"
#ifndef FF_NO_OPENCL
#include "host/cl_context.h"
#endif

namespace {

struct BackendChoice {
  std::string label;  // "cpu", "opencl0", ...
  std::string kind;
  int device = -1;
};

// One simulation per backend and size, made on first use and kept.
ff::Simulation& fixture(const BackendChoice& b, long n) {
  static std::map<std::string, std::unique_ptr<ff::Simulation>> cache;
  std::unique_ptr<ff::Simulation>& sim = cache[b.label + "/" + std::to_string(n)];
  if (sim) return *sim;
  ff::SceneDesc s;
  s.source = "bench";
  const int side = int(std::lround(std::cbrt(double(n))));
  const float sp = s.params.fluid.restSpacing();
  const float extent = 2.5f * side * sp;
  s.container.max = ff::Vec3(extent, extent, extent);
  ff::FluidBlockDesc block;
  block.origin = ff::Vec3(0.75f * side * sp, 0.0f, 0.75f * side * sp);
  block.dims[0] = block.dims[1] = block.dims[2] = side;
  s.fluid.push_back(block);
  ff::TargetSpec t;
  t.kind = ff::TargetKind::Sphere;
  t.control_count = int(n / 4);
  s.schedule.push_back({0.0, t});
  std::string note;
  sim = std::make_unique<ff::Simulation>(s, ff::makeBackend(b.kind, b.device, 0, &note));
  sim->setProfiling(true);
  for (int i = 0; i < 20; ++i) sim->step();
  return *sim;
}

using PhaseCall = std::function<void(ff::Backend&, const ff::Params&)>;

void runPhase(benchmark::State& state, BackendChoice b, PhaseCall call) {
  ff::Simulation& sim = fixture(b, state.range(0));
  for (auto _ : state) call(sim.backend(), sim.scene().params);
  state.counters["fluid"] = double(sim.scene().fluidCount());
  state.counters["control"] = double(sim.metrics().control_count);
  state.SetLabel(sim.backend().device());
}

std::vector<BackendChoice> backends() {
  std::vector<BackendChoice> list = {{"cpu", "cpu", -1}};
#ifndef FF_NO_OPENCL
  try {
    for (const ff::ClDeviceInfo& d : ff::listClDevices())
      list.push_back({"opencl" + std::to_string(d.index), "opencl", d.index});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "no OpenCL backend to time: %s\n", e.what());
  }
#endif
  return list;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::pair<std::string, PhaseCall>> phases = {
      {"grid", [](ff::Backend& b, const ff::Params&) { b.buildGrid(); }},
      {"density", [](ff::Backend& b, const ff::Params&) { b.computeDensity(); }},
      {"forces", [](ff::Backend& b, const ff::Params&) { b.computeForces(0.0f); }},
      {"control_scale", [](ff::Backend& b, const ff::Params&) { b.computeControlScale(); }},
      {"control_forces",
       [](ff::Backend& b, const ff::Params& p) { b.applyControlForces(p.fluid.time_step); }},
      {"pressure", [](ff::Backend& b, const ff::Params& p) { b.solvePressure(p.fluid.time_step); }},
      // dt = 0: the fluid does not move, so every iteration times the same state.
      {"integrate", [](ff::Backend& b, const ff::Params&) { b.integrate(0.0f); }},
      // One shape-matching step per call (its clock's step).
      {"shape_matching", [](ff::Backend& b, const ff::Params& p) { b.shapeMatching(p.shape.time_step); }},
      {"metrics", [](ff::Backend& b, const ff::Params&) { benchmark::DoNotOptimize(b.computeMetrics()); }},
  };
  for (const BackendChoice& b : backends())
    for (const auto& [name, call] : phases)
      benchmark::RegisterBenchmark((b.label + "/" + name).c_str(),
                                   [b, call = call](benchmark::State& s) { runPhase(s, b, call); })
          ->Arg(12000)
          ->Arg(100000)
          ->Arg(1000000)
          ->Unit(benchmark::kMillisecond);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
