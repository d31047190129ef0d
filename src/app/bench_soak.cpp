// bench_soak.cpp - the target-change soak of `flowform bench --soak`.
#include "app/bench_soak.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <string>

#include "app/fluid_census.h"
#include "core/error.h"
#include "core/fluid_state.h"
#include "host/backend_factory.h"
#include "sim/simulation.h"

namespace ff::app {

namespace {

double statusMb(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::string prefix = std::string(key) + ":";
  while (std::getline(in, line))
    if (line.compare(0, prefix.size(), prefix) == 0) return std::stod(line.substr(prefix.size())) / 1024.0;
  return 0.0;  // the value is in kB
}

// A 0.25 m box with a fluid_side^3 block resting on its floor.
SceneDesc soakScene(int side) {
  SceneDesc s;
  s.name = "soak";
  s.source = "<bench soak>";
  s.params = presetParams("paper");
  s.container.min = Vec3(0.0f, 0.0f, 0.0f);
  s.container.max = Vec3(0.25f, 0.25f, 0.25f);
  FluidBlockDesc b;
  const float extent = float(side) * s.params.fluid.restSpacing();
  b.origin = Vec3(0.5f * (0.25f - extent), 0.0f, 0.5f * (0.25f - extent));
  b.dims[0] = b.dims[1] = b.dims[2] = side;
  s.fluid = {b};
  return s;
}

// The k-th target: the four analytic shapes in turn, each with proportions
// and a rotation that change from one change to the next (so most changes
// voxelise a new shape), and every 7th sized by a control count.
TargetSpec soakTarget(int k) {
  TargetSpec t;
  const float f = float(k % 13) / 12.0f;  // 0 .. 1
  switch (k % 4) {
    case 0:
      t.kind = TargetKind::Sphere;
      break;
    case 1:
      t.kind = TargetKind::Box;
      t.box_size = Vec3(1.0f + f, 1.0f, 0.6f + 0.5f * f);
      break;
    case 2:
      t.kind = TargetKind::Torus;
      t.torus_major = 1.0f;
      t.torus_minor = 0.3f + 0.2f * f;
      break;
    default:
      t.kind = TargetKind::Capsule;
      t.capsule_radius = 0.4f + 0.2f * f;
      t.capsule_length = 0.5f + f;
      break;
  }
  t.rotation_deg = Vec3(float((k * 37) % 90), float((k * 53) % 180), 0.0f);
  if (k % 7 == 3) t.control_count = 300 + 40 * (k % 11);
  return t;
}

// The k-th region, around the fluid as it is now: all of it, the lower or
// the upper part of its bounding box in turn, or a sphere at its centroid.
RegionDesc soakRegion(int k, const FluidState& fluid) {
  RegionDesc r;
  Vec3 lo(1e30f, 1e30f, 1e30f), hi(-1e30f, -1e30f, -1e30f), mean(0.0f, 0.0f, 0.0f);
  for (size_t i = 0; i < fluid.size(); ++i) {
    const Vec3 p(fluid.x[i], fluid.y[i], fluid.z[i]);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    mean += p;
  }
  mean /= float(std::max<size_t>(fluid.size(), 1));
  const Vec3 ext = hi - lo;
  switch (k % 4) {
    case 0:
      break;
    case 1:  // the lower 60%
      r.kind = RegionDesc::Kind::Box;
      r.min = lo - Vec3::Constant(1e-3f);
      r.max = hi + Vec3::Constant(1e-3f);
      r.max.y() = lo.y() + 0.6f * ext.y() + 1e-3f;
      break;
    case 2:  // the half at larger x
      r.kind = RegionDesc::Kind::Box;
      r.min = lo - Vec3::Constant(1e-3f);
      r.max = hi + Vec3::Constant(1e-3f);
      r.min.x() = lo.x() + 0.5f * ext.x();
      break;
    default:
      r.kind = RegionDesc::Kind::Sphere;
      r.center = mean;
      r.radius = std::max(0.35f * ext.maxCoeff(), 0.01f);
      break;
  }
  return r;
}

}  // namespace

double residentMb() {
  return statusMb("VmRSS");
}
double peakResidentMb() {
  return statusMb("VmHWM");
}

SoakResult runSoak(const SoakOptions& o, const BenchBackend& b) {
  if (o.changes < 10) throw Error("--soak-changes: must be at least 10");
  if (o.steps_between < 1) throw Error("--soak-steps: must be at least 1");
  const auto t0 = std::chrono::steady_clock::now();
  SoakResult r;
  r.rss_start_mb = residentMb();
  std::string note;
  Simulation sim(soakScene(o.fluid_side), makeBackend(b.kind, b.device, b.threads, &note));
  sim.setMetricsEvery(b.metrics_every);
  r.backend = sim.backend().name();
  r.device = sim.backend().device();
  r.fluid = sim.scene().fluidCount();
  r.min_controlled = -1;
  const int warm = std::max(1, o.changes / 10);
  FluidState fluid;
  for (int k = 0; k < o.changes && r.ok(); ++k) {
    sim.backend().readFluid(fluid);
    try {
      // As the viewer does it: the region first (without a target), then the
      // new target in it.
      sim.clearTarget();
      sim.setRegion(soakRegion(k, fluid));
      sim.setTarget(soakTarget(k));
      for (int s = 0; s < o.steps_between; ++s) sim.step();
    } catch (const Error& e) {
      r.failure = "change " + std::to_string(k) + ": " + e.what();
      break;
    }
    const long placed = long(sim.target() ? sim.controlledCount() : 0);
    r.min_controlled = r.min_controlled < 0 ? placed : std::min(r.min_controlled, placed);
    r.max_controlled = std::max(r.max_controlled, placed);
    sim.backend().readFluid(fluid);
    const FluidCensus n = countLostFluid(fluid, sim.scene().container);
    r.nonfinite += n.nonfinite;
    r.outside += n.outside;
    if (n.nonfinite || n.outside)
      r.failure = "change " + std::to_string(k) + ": " + std::to_string(n.nonfinite) +
                  " NaN/Inf particles, " + std::to_string(n.outside) + " outside the container";
    ++r.changes;
    if (k + 1 == warm) r.rss_warm_mb = residentMb();
    if ((k + 1) % 50 == 0)
      std::fprintf(stderr, "bench soak (%s): %d changes, t = %.2f s, RSS %.1f MiB\n", b.kind.c_str(), k + 1,
                   sim.time(), residentMb());
  }
  r.steps = sim.stepCount();
  r.sim_time = sim.time();
  r.cache_entries = sim.targetCacheSize();
  r.rss_end_mb = residentMb();
  r.hwm_mb = peakResidentMb();
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (r.ok() && r.rss_end_mb - r.rss_warm_mb > o.max_growth_mb) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "memory grew by %.1f MiB between change %d and change %d (more than %.0f MiB): not flat",
                  r.rss_end_mb - r.rss_warm_mb, warm, r.changes, o.max_growth_mb);
    r.failure = buf;
  }
  return r;
}

void printSoak(std::FILE* out, const std::vector<SoakResult>& results) {
  std::fprintf(out, "\n### Soak: target and region changes\n\n");
  std::fprintf(
      out,
      "| backend | device | fluid | changes | steps | sim s | controlled fluid | NaN/Inf | outside | "
      "cache entries | RSS start MiB | RSS after 10%% MiB | RSS end MiB | peak RSS (VmHWM) MiB | "
      "wall s | result |\n");
  std::fprintf(out, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const SoakResult& r : results)
    std::fprintf(
        out,
        "| %s | %s | %ld | %d | %ld | %.2f | %ld-%ld | %ld | %ld | %zu | %.1f | %.1f | %.1f | %.1f | "
        "%.1f | %s |\n",
        r.backend.c_str(), r.device.c_str(), r.fluid, r.changes, r.steps, r.sim_time, r.min_controlled,
        r.max_controlled, r.nonfinite, r.outside, r.cache_entries, r.rss_start_mb, r.rss_warm_mb,
        r.rss_end_mb, r.hwm_mb, r.wall_s, r.ok() ? "ok" : ("FAILED: " + r.failure).c_str());
}

}  // namespace ff::app
