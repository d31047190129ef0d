// The dam break of Martin & Moyce (1952) on the `water` preset (issue 9): a
// column of width a and height 2 a (their n^2 = 2) collapses along the floor
// of a long tank; its surge front Z = x / a against T = t sqrt(2 g / a) must
// follow the published measurements within 10 % for T <= 3. The data is
// ../shared/reference/data/dambreak_martin_moyce_1952_surge_front.csv beside
// the source tree; without it the test skips with a message.
//
// To stay short in ctest the column is a slab of a few particles between the
// tank's front and back walls (free-slip, as the analytic walls are), which
// makes the flow two-dimensional as in the experiment's long channel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cpu/backend_cpu.h"
#include "sim/simulation.h"
#include "test_scenes.h"

namespace {

struct SurgePoint {
  double T, Z;
};

// The published points (T, Z), or none when the file is missing.
std::vector<SurgePoint> readSurgeData(const std::string& path) {
  std::vector<SurgePoint> out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 'T') continue;  // comments and the header
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    SurgePoint p{};
    if (fields >> p.T >> p.Z) out.push_back(p);
  }
  return out;
}

// The surge front: the leading edge of the fluid on the floor, i.e. the
// largest particle centre within two spacings of the floor plus half a
// spacing (a particle's own extent; the column's face at the start is then
// exactly at x = a). Particles that run ahead alone (spray) do not count: the
// front is the edge of the 99th percentile of those near the floor.
double surgeFront(const ff::FluidState& s, double spacing) {
  std::vector<float> xs;
  for (size_t i = 0; i < s.x.size(); ++i)
    if (s.y[i] < 2.0 * spacing) xs.push_back(s.x[i]);
  if (xs.empty()) return 0.0;
  std::sort(xs.begin(), xs.end());
  const size_t k = size_t(std::floor(0.99 * double(xs.size() - 1)));
  return double(xs[k]) + 0.5 * spacing;
}

TEST(DamBreak, SurgeFrontFollowsMartinAndMoyce1952) {
  const std::string path =
      std::string(FF_SOURCE_DIR) + "/../shared/reference/data/dambreak_martin_moyce_1952_surge_front.csv";
  const std::vector<SurgePoint> data = readSurgeData(path);
  if (data.empty()) GTEST_SKIP() << "no Martin & Moyce data at " << path;

  ff::Params p = ff::presetParams("water");
  // The experiment's own size: a = 2.25 in = 57.15 mm is 9 spacings of the
  // preset (56.7 mm). The preset's viscosity is fixed in physical units, so
  // the size matters: docs/RESULTS.md has the same column at a = 8 to 20
  // spacings. The slab is 4 spacings deep.
  const int na = 9, nz = 4;
  const double sp = p.fluid.restSpacing(), a = na * sp, g = -p.fluid.gravity[1];
  ASSERT_NEAR(g, 9.81, 1e-6);
  ASSERT_NEAR(a / 0.05715, 1.0, 0.02);  // the experiment's a, within 2 %
  ff::SceneDesc s = fftest::blockScene(ff::Vec3(float(6 * na * sp), float(3 * na * sp), float(nz * sp)),
                                       ff::Vec3(0, 0, 0), na, 2 * na, nz);
  s.preset = "water";
  s.params = p;
  auto backend = std::make_unique<ff::CpuBackend>(2);
  ff::CpuBackend* cpu = backend.get();
  ff::Simulation sim(s, std::move(backend));
  const size_t n = cpu->fluid().size();
  const double T_end = 3.0, time_scale = std::sqrt(2.0 * g / a);  // T = t * time_scale

  // The simulated front at each published T <= 3, linearly interpolated
  // between the frame steps around it.
  double t_prev = 0.0, z_prev = surgeFront(cpu->fluid().s, sp) / a;
  EXPECT_NEAR(z_prev, 1.0, 1e-3);  // the column's face starts at x = a
  int checked = 0;
  size_t next = 0;
  while (next < data.size() && data[next].T <= T_end) {
    sim.step();
    const double t = sim.metrics().time, z = surgeFront(cpu->fluid().s, sp) / a;
    while (next < data.size() && data[next].T <= T_end && data[next].T <= t * time_scale) {
      const double tT = data[next].T / time_scale, w = (tT - t_prev) / (t - t_prev);
      const double zs = z_prev + w * (z - z_prev), ref = data[next].Z;
      std::printf("T = %.2f: Z = %.3f (Martin & Moyce %.2f, %+.1f %%)\n", data[next].T, zs, ref,
                  100.0 * (zs / ref - 1.0));
      EXPECT_NEAR(zs / ref, 1.0, 0.10) << "T = " << data[next].T;
      ++checked, ++next;
    }
    t_prev = t, z_prev = z;
  }
  EXPECT_GE(checked, 12);  // the 13 published points up to T = 3
  // No particle is lost: all finite and inside the tank.
  const ff::FluidState& f = cpu->fluid().s;
  ASSERT_EQ(f.x.size(), n);
  for (size_t i = 0; i < n; ++i) {
    const float pos[3] = {f.x[i], f.y[i], f.z[i]};
    for (int d = 0; d < 3; ++d) {
      ASSERT_TRUE(std::isfinite(pos[d]));
      EXPECT_GE(pos[d], s.container.min[d]);
      EXPECT_LE(pos[d], s.container.max[d]);
    }
  }
  EXPECT_EQ(sim.metrics().solver_capped, 0);
}

}  // namespace
