// Microbenchmarks of each phase of the OpenMP backend, at 12k to 1M fluid
// particles. A sphere target with one control particle per four fluid
// particles, after 20 steps so the state is a moving fluid, not a lattice.
//   ./build/flowform_bench --benchmark_filter=Cpu
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>

#include "core/simulation.h"
#include "cpu/backend_cpu.h"

namespace {

struct Fixture {
  std::unique_ptr<ff::Simulation> sim;
  ff::CpuBackend* cpu = nullptr;
};

Fixture& fixture(long n) {
  static std::map<long, Fixture> cache;
  Fixture& f = cache[n];
  if (f.sim) return f;
  ff::SceneDesc s;
  s.source = "bench";
  const int side = int(std::lround(std::cbrt(double(n))));
  const float sp = s.params.fluid.restSpacing();
  const float extent = 2.5f * side * sp;
  s.container.max = ff::Vec3(extent, extent, extent);
  ff::FluidBlockDesc b;
  b.origin = ff::Vec3(0.75f * side * sp, 0.0f, 0.75f * side * sp);
  b.dims[0] = b.dims[1] = b.dims[2] = side;
  s.fluid.push_back(b);
  ff::TargetSpec t;
  t.kind = ff::TargetKind::Sphere;
  t.control_count = int(n / 4);
  s.schedule.push_back({0.0, t});
  auto backend = std::make_unique<ff::CpuBackend>();
  f.cpu = backend.get();
  f.sim = std::make_unique<ff::Simulation>(s, std::move(backend));
  for (int i = 0; i < 20; ++i) f.sim->step();
  return f;
}

template <class F>
void runPhase(benchmark::State& state, F&& phase) {
  Fixture& f = fixture(state.range(0));
  for (auto _ : state) phase(*f.cpu);
  state.counters["particles"] = double(f.cpu->fluid().size());
}

void CpuGrid(benchmark::State& s) {
  runPhase(s, [](ff::CpuBackend& b) { b.buildGrid(); });
}
void CpuDensity(benchmark::State& s) {
  runPhase(s, [](ff::CpuBackend& b) { b.computeDensity(); });
}
void CpuForces(benchmark::State& s) {
  runPhase(s, [](ff::CpuBackend& b) { b.computeForces(); });
}
void CpuControlScale(benchmark::State& s) {
  runPhase(s, [](ff::CpuBackend& b) { b.computeControlScale(); });
}
void CpuControlForces(benchmark::State& s) {
  runPhase(s, [](ff::CpuBackend& b) { b.applyControlForces(0.004f); });
}
void CpuShapeMatching(benchmark::State& s) {
  runPhase(s, [](ff::CpuBackend& b) { b.controller().shapeMatchStep(); });
}
void CpuIntegrate(benchmark::State& s) {
  runPhase(s, [](ff::CpuBackend& b) { b.integrate(0.0f); });
}
void CpuMetrics(benchmark::State& s) {
  runPhase(s, [](ff::CpuBackend& b) { benchmark::DoNotOptimize(b.computeMetrics()); });
}

#define FF_SIZES ->Arg(12000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)
BENCHMARK(CpuGrid) FF_SIZES;
BENCHMARK(CpuDensity) FF_SIZES;
BENCHMARK(CpuForces) FF_SIZES;
BENCHMARK(CpuControlScale) FF_SIZES;
BENCHMARK(CpuControlForces) FF_SIZES;
BENCHMARK(CpuShapeMatching) FF_SIZES;
BENCHMARK(CpuIntegrate) FF_SIZES;
BENCHMARK(CpuMetrics) FF_SIZES;

}  // namespace

BENCHMARK_MAIN();
