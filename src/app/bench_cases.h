// bench_cases.h - the scenes `flowform bench` times: the paper's Table 1 (12k
// fluid particles, the four meshes at their control-particle counts) and the
// scaling sweeps (fluid count at the Table 1 control ratio, control count at
// 12k fluid particles).
#pragma once
#include <string>
#include <vector>

#include "scene/scene.h"

namespace ff::app {

struct BenchCase {
  std::string name;  // "bunny", "fluid-sweep", "control-sweep"
  SceneDesc scene;
  long fluid = 0;    // fluid particles
  long control = 0;  // requested control particles (the placed count may differ by < 3%)
};

// The four Table 1 scenes (embedded copies of scenes/{bunny,teapot,runner,dragon}.json);
// meshes come from FLOWFORM_MESH_PATH. Throws ff::Error naming the mesh that
// cannot be found.
std::vector<BenchCase> table1Cases();

// A cube of `fluid` particles (rounded to a cube number) dropping into a
// sphere target of `control` control particles, in a container sized for it.
BenchCase sweepCase(const std::string& name, long fluid, long control);

// Fluid counts from 12k to `max_fluid` (12k, 27k, 64k, 125k, 256k, 512k, 1M),
// each with control = 0.266 x fluid (the bunny's ratio, 3197 / 12000).
std::vector<BenchCase> fluidSweepCases(long max_fluid);
// Control counts 500 .. `max_control` (500, 1k, 2k, 5k, 10k, 20k, 50k) at 12k fluid.
std::vector<BenchCase> controlSweepCases(long max_control);

}  // namespace ff::app
