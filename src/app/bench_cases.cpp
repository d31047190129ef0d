// bench_cases.cpp - the Table 1 scenes and the scaling sweeps.
#include "app/bench_cases.h"

#include <algorithm>
#include <cmath>

#include "core/embedded.h"

namespace ff::app {

std::vector<BenchCase> table1Cases() {
  std::vector<BenchCase> cases;
  for (const char* name : {"bunny", "teapot", "runner", "dragon"}) {
    const std::string file = std::string("scenes/") + name + ".json";
    BenchCase c;
    c.name = name;
    // Relative mesh names resolve along FLOWFORM_MESH_PATH only.
    c.scene = parseScene(embeddedFile(file), "<built-in " + file + ">", "");
    c.fluid = c.scene.fluidCount();
    c.control = c.scene.schedule.empty() ? 0 : c.scene.schedule.front().target.control_count;
    cases.push_back(std::move(c));
  }
  return cases;
}

BenchCase sweepCase(const std::string& name, long fluid, long control) {
  BenchCase c;
  c.name = name;
  SceneDesc& s = c.scene;
  s.name = name;
  s.source = "<flowform bench " + name + ">";
  s.preset = "paper";
  s.params = presetParams("paper");
  const int side = std::max(2, int(std::lround(std::cbrt(double(fluid)))));
  const float sp = s.params.fluid.restSpacing();
  // The block fills the middle third of the floor, so that the shape forms
  // away from the walls, as in the Table 1 scenes.
  const float block = float(side) * sp;
  const float extent = std::max(0.3f, 2.2f * block);
  s.container.min = Vec3(0.0f, 0.0f, 0.0f);
  s.container.max = Vec3(extent, extent, extent);
  FluidBlockDesc b;
  b.origin = Vec3(0.5f * (extent - block), 0.0f, 0.5f * (extent - block));
  b.dims[0] = b.dims[1] = b.dims[2] = side;
  s.fluid.push_back(b);
  TargetSpec t;
  t.kind = TargetKind::Sphere;
  t.control_count = int(control);
  s.schedule.push_back({0.0, t});
  s.duration = 1.0;
  c.fluid = s.fluidCount();
  c.control = control;
  return c;
}

std::vector<BenchCase> fluidSweepCases(long max_fluid) {
  std::vector<BenchCase> cases;
  for (long side : {23L, 30L, 40L, 50L, 64L, 80L, 100L}) {  // 12.2k .. 1M
    const long n = side * side * side;
    if (n > max_fluid && !cases.empty()) break;
    cases.push_back(sweepCase("fluid-sweep", n, std::lround(0.266 * double(n))));
  }
  return cases;
}

std::vector<BenchCase> controlSweepCases(long max_control) {
  std::vector<BenchCase> cases;
  for (long c : {500L, 1000L, 2000L, 5000L, 10000L, 20000L, 50000L}) {
    if (c > max_control && !cases.empty()) break;
    cases.push_back(sweepCase("control-sweep", 23L * 23 * 23, c));
  }
  return cases;
}

}  // namespace ff::app
