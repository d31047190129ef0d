// thin_parts.cpp - which thin parts of a target fill: runs a scene on the
// OpenMP backend for SECONDS and counts, in fifths of the target's height
// (its rest frame's y), the thin voxels (the metric filled_thin's:
// local thickness below the control radius, docs/METRICS.md) and the other
// inside voxels that hold fluid at >= 0.5 rho0 at the control particles'
// best rigid fit, the density summed by brute force over every fluid
// particle (docs/RESULTS.md, "Thin parts, part by part").
//   ./build/flowform_thin_parts SECONDS SCENE.json...
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>

#include "control/shape_matching.h"
#include "cpu/backend_cpu.h"
#include "ff_sph.h"
#include "metrics/fluid_shares.h"
#include "metrics/iou.h"
#include "scene/scene.h"
#include "sim/simulation.h"

namespace {

void measure(double seconds, const char* path) {
  ff::Simulation sim(ff::loadScene(path), std::make_unique<ff::CpuBackend>(1));
  if (!sim.target()) throw std::runtime_error(std::string(path) + ": the scene has no target");
  while (sim.time() < seconds - 1e-6) sim.step();
  // The control particles' best rigid fit, as the metrics take it.
  const ff::ControlSet& set = static_cast<ff::CpuBackend&>(sim.backend()).controller().set();
  ff::RigidFrame frame;
  ff::bestFitFrame(set, frame.q, frame.c, 50);
  frame.rest_c[0] = set.rest_cx, frame.rest_c[1] = set.rest_cy, frame.rest_c[2] = set.rest_cz;
  const ff_mat3 r = ff_quat_to_mat3(frame.q);
  const ff::VoxelGrid& g = sim.target()->grid;
  const ff::Params& p = sim.scene().params;
  const ff::ThinVoxels thin = ff::metricsThinVoxels(*sim.target(), p.control.radius);
  const double mass = p.fluid.particle_mass, h = p.fluid.smoothing_radius, rho0 = p.fluid.rest_density;
  const double h2 = h * h, coef = ff_poly6_coef(float(h));
  const ff::FluidState& s = static_cast<ff::CpuBackend&>(sim.backend()).fluid().s;
  int lo = g.ny, hi = -1;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        if (g.inside[g.index(i, j, k)]) lo = std::min(lo, j), hi = std::max(hi, j);
  long thin_voxels[5] = {0}, thin_filled[5] = {0}, thick_voxels[5] = {0}, thick_filled[5] = {0};
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const size_t v = g.index(i, j, k);
        if (!g.inside[v]) continue;
        const int band = std::min(4, int(5.0 * double(j - lo) / double(hi - lo + 1)));
        const ff::Vec3 centre = g.center(i, j, k);
        const ff_float3 w = ff_mat3_mul_vec(
            r,
            FF_F3(centre.x() - frame.rest_c[0], centre.y() - frame.rest_c[1], centre.z() - frame.rest_c[2]));
        const double px = double(w.x) + frame.c[0], py = double(w.y) + frame.c[1],
                     pz = double(w.z) + frame.c[2];
        double rho = 0.0;
        for (size_t e = 0; e < s.size(); ++e) {
          const double dx = s.x[e] - px, dy = s.y[e] - py, dz = s.z[e] - pz, d2 = dx * dx + dy * dy + dz * dz;
          if (d2 < h2) rho += mass * coef * std::pow(h2 - d2, 3.0);
        }
        const long full = rho >= 0.5 * rho0 ? 1 : 0;
        if (thin.thin[v])
          ++thin_voxels[band], thin_filled[band] += full;
        else
          ++thick_voxels[band], thick_filled[band] += full;
      }
  const ff::StepMetrics& m = sim.metrics();
  std::printf("%s t=%.3f s: iou %.3f filled %.3f stray %.3f filled_thin %.3f (%ld thin of %zu voxels)\n",
              path, sim.time(), m.iou, m.filled, m.stray, m.filled_thin, thin.count,
              sim.target()->reference.size());
  std::printf(
      "  fifth of the height (bottom first): thin filled / thin voxels | other filled / other voxels\n");
  for (int b = 0; b < 5; ++b)
    std::printf("  %d: %ld / %ld | %ld / %ld\n", b, thin_filled[b], thin_voxels[b], thick_filled[b],
                thick_voxels[b]);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: flowform_thin_parts SECONDS SCENE.json...\n");
    return 2;
  }
  const double seconds = std::atof(argv[1]);
  if (!(seconds > 0.0)) {
    std::fprintf(stderr, "flowform_thin_parts: SECONDS must be a positive number, got '%s'\n", argv[1]);
    return 2;
  }
  try {
    for (int a = 2; a < argc; ++a) measure(seconds, argv[a]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "flowform_thin_parts: %s\n", e.what());
    return 1;
  }
  return 0;
}
