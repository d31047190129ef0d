// thin_parts.cpp - which thin parts of a target fill: runs a scene on the
// OpenMP backend for SECONDS and counts, in fifths of the target's height
// (its rest frame's y), the thin voxels (the metric filled_thin's:
// local thickness below the control radius, docs/METRICS.md) and the other
// inside voxels that hold fluid at >= 0.5 rho0 at the control particles'
// best rigid fit, the density summed by brute force over every fluid
// particle (docs/RESULTS.md, "Thin parts, part by part").
//   ./build/flowform_thin_parts SECONDS SCENE.json...
// With --faults it prints instead where the target falls short (docs/RESULTS.md,
// "The unseen set"): the inside voxels that do not hold fluid at >= 0.5 rho0,
// by fifth of the rest frame's height and of its longer horizontal axis (and,
// with FF_FAULT_MAP set, maps seen along the third axis of them and of the
// fluid outside the target); the fluid inside the target, outside within a
// voxel, farther, and stray (farther than the control radius from every control
// particle: how far, how high); the heights of the control particles and of the
// fluid; the unfilled control particles (s > 1/2) and their distance from their
// shape-matching goals, and how far the control particles are from their
// best rigid fit (how bent the control set is), by fifth of the height.
//   ./build/flowform_thin_parts --faults SECONDS SCENE.json...
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "control/shape_matching.h"
#include "cpu/backend_cpu.h"
#include "ff_sph.h"
#include "metrics/fluid_shares.h"
#include "metrics/iou.h"
#include "scene/scene.h"
#include "sim/simulation.h"

namespace {

// The fluid's density at (px, py, pz) by poly6 of support h (h2 = h^2,
// coefficient coef), summed by brute force over every fluid particle.
double densityAt(const ff::FluidState& s, double px, double py, double pz, double mass, double coef,
                 double h2) {
  double rho = 0.0;
  for (size_t e = 0; e < s.size(); ++e) {
    const double dx = s.x[e] - px, dy = s.y[e] - py, dz = s.z[e] - pz, d2 = dx * dx + dy * dy + dz * dz;
    if (d2 < h2) rho += mass * coef * std::pow(h2 - d2, 3.0);
  }
  return rho;
}

// The fluid's density at the centre of voxel (i, j, k) of g, taken to the
// frame (r: its rotation).
double voxelDensity(const ff::VoxelGrid& g, int i, int j, int k, const ff::RigidFrame& frame,
                    const ff_mat3& r, const ff::FluidState& s, double mass, double coef, double h2) {
  const ff::Vec3 centre = g.center(i, j, k);
  const ff_float3 w = ff_mat3_mul_vec(
      r, FF_F3(centre.x() - frame.rest_c[0], centre.y() - frame.rest_c[1], centre.z() - frame.rest_c[2]));
  return densityAt(s, double(w.x) + frame.c[0], double(w.y) + frame.c[1], double(w.z) + frame.c[2], mass,
                   coef, h2);
}

// The control particles' best rigid fit, as the metrics take it.
ff::RigidFrame fitFrame(const ff::ControlSet& set) {
  ff::RigidFrame frame;
  ff::bestFitFrame(set, frame.q, frame.c, 50);
  frame.rest_c[0] = set.rest_cx, frame.rest_c[1] = set.rest_cy, frame.rest_c[2] = set.rest_cz;
  return frame;
}

void measure(double seconds, const char* path) {
  ff::Simulation sim(ff::loadScene(path), std::make_unique<ff::CpuBackend>(1));
  if (!sim.target()) throw std::runtime_error(std::string(path) + ": the scene has no target");
  while (sim.time() < seconds - 1e-6) sim.step();
  const ff::ControlSet& set = static_cast<ff::CpuBackend&>(sim.backend()).controller().set();
  const ff::RigidFrame frame = fitFrame(set);
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
        const double rho = voxelDensity(g, i, j, k, frame, r, s, mass, coef, h2);
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

ff_mat3 transpose(const ff_mat3& m) {
  ff_mat3 t;
  t.c0 = FF_F3(m.c0.x, m.c1.x, m.c2.x);
  t.c1 = FF_F3(m.c0.y, m.c1.y, m.c2.y);
  t.c2 = FF_F3(m.c0.z, m.c1.z, m.c2.z);
  return t;
}

void faults(double seconds, const char* path) {
  ff::Simulation sim(ff::loadScene(path), std::make_unique<ff::CpuBackend>(2));
  if (!sim.target()) throw std::runtime_error(std::string(path) + ": the scene has no target");
  while (sim.time() < seconds - 1e-6) sim.step();
  const ff::Controller& ctl = static_cast<ff::CpuBackend&>(sim.backend()).controller();
  const ff::ControlSet& set = ctl.set();
  const ff::RigidFrame frame = fitFrame(set);
  const ff_mat3 r = ff_quat_to_mat3(frame.q);
  const ff_mat3 rt = transpose(r);
  const ff::VoxelGrid& g = sim.target()->grid;
  const ff::Params& p = sim.scene().params;
  const double mass = p.fluid.particle_mass, h = p.fluid.smoothing_radius, rho0 = p.fluid.rest_density;
  const double h2 = h * h, coef = ff_poly6_coef(float(h)), rc = p.control.radius;
  const ff::FluidState& s = static_cast<ff::CpuBackend&>(sim.backend()).fluid().s;
  // The rest frame's extent: height (y) and the longer horizontal axis.
  int lo[3] = {1 << 30, 1 << 30, 1 << 30}, hi[3] = {-1, -1, -1};
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        if (g.inside[g.index(i, j, k)]) {
          const int c[3] = {i, j, k};
          for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], c[d]), hi[d] = std::max(hi[d], c[d]);
        }
  const int ax = (hi[0] - lo[0]) >= (hi[2] - lo[2]) ? 0 : 2;
  long vox[5][5] = {}, empty[5][5] = {}, total = 0, total_empty = 0;
  // A map over (axis ax, y) seen along the third axis: per column of voxels,
  // '#' every one filled, digits the unfilled share in tenths, ' ' none inside.
  const bool draw = std::getenv("FF_FAULT_MAP") != nullptr;
  const int mw = hi[ax] - lo[ax] + 1, mh = hi[1] - lo[1] + 1;
  std::vector<int> map_in(size_t(mw) * size_t(mh), 0), map_empty(map_in.size(), 0);
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        if (!g.inside[g.index(i, j, k)]) continue;
        const int c[3] = {i, j, k};
        const int by = std::min(4, int(5.0 * (j - lo[1]) / double(hi[1] - lo[1] + 1)));
        const int bx = std::min(4, int(5.0 * (c[ax] - lo[ax]) / double(hi[ax] - lo[ax] + 1)));
        const double rho = voxelDensity(g, i, j, k, frame, r, s, mass, coef, h2);
        ++vox[by][bx], ++total;
        const size_t mi = size_t(c[ax] - lo[ax]) + size_t(mw) * size_t(j - lo[1]);
        ++map_in[mi];
        if (rho < 0.5 * rho0) ++empty[by][bx], ++total_empty, ++map_empty[mi];
      }
  const ff::StepMetrics& m = sim.metrics();
  std::printf(
      "%s t=%.3f s: iou %.3f filled %.3f stray %.3f filled_thin %.3f tilt %.1f; %zu control particles\n",
      path, sim.time(), m.iou, m.filled, m.stray, m.filled_thin, m.tilt, set.size());
  std::printf("  unfilled voxels %ld of %ld; rows: fifths of the height (top first), columns: of axis %c\n",
              total_empty, total, ax == 0 ? 'x' : 'z');
  for (int by = 4; by >= 0; --by) {
    std::printf("   ");
    for (int bx = 0; bx < 5; ++bx) std::printf(" %4ld/%-4ld", empty[by][bx], vox[by][bx]);
    std::printf("\n");
  }
  if (draw)
    for (int j = mh - 1; j >= 0; --j) {
      std::printf("    |");
      for (int i = 0; i < mw; ++i) {
        const size_t mi = size_t(i) + size_t(mw) * size_t(j);
        std::printf("%c", map_in[mi] == 0      ? ' '
                          : map_empty[mi] == 0 ? '#'
                                               : char('0' + std::min(9, 10 * map_empty[mi] / map_in[mi])));
      }
      std::printf("|\n");
    }
  // The fluid, against the target at the frame and the control particles.
  long inside = 0, near = 0, far = 0, stray = 0, below = 0;
  // The fluid outside the target on the same map (2 voxels of margin): '.'
  // up to 2 particles per column, digits in tens of particles.
  const int om = 3, ow = mw + 2 * om, oh = mh + 2 * om;
  std::vector<int> out_map(size_t(ow) * size_t(oh), 0);
  double sd_min = 1e30, sd_max = 0.0, sd_sum = 0.0, sy_min = 1e30, sy_max = -1e30;
  const double voxel = g.voxel;
  for (size_t e = 0; e < s.size(); ++e) {
    // Into the rest frame.
    const ff_float3 q = ff_mat3_mul_vec(
        rt, FF_F3(float(s.x[e] - frame.c[0]), float(s.y[e] - frame.c[1]), float(s.z[e] - frame.c[2])));
    const double rx = q.x + frame.rest_c[0], ry = q.y + frame.rest_c[1], rz = q.z + frame.rest_c[2];
    bool in = false, nearby = false;
    for (int dz = -1; dz <= 1 && !in; ++dz)
      for (int dy = -1; dy <= 1 && !in; ++dy)
        for (int dx = -1; dx <= 1 && !in; ++dx) {
          const int i = int(std::floor((rx - g.origin.x()) / voxel)) + dx;
          const int j = int(std::floor((ry - g.origin.y()) / voxel)) + dy;
          const int k = int(std::floor((rz - g.origin.z()) / voxel)) + dz;
          if (i < 0 || j < 0 || k < 0 || i >= g.nx || j >= g.ny || k >= g.nz) continue;
          if (!g.inside[g.index(i, j, k)]) continue;
          if (dx == 0 && dy == 0 && dz == 0) in = true;
          nearby = true;
        }
    {
      const int ci[3] = {int(std::floor((rx - g.origin.x()) / voxel)),
                         int(std::floor((ry - g.origin.y()) / voxel)),
                         int(std::floor((rz - g.origin.z()) / voxel))};
      const int mx = std::clamp(ci[ax] - lo[ax] + om, 0, ow - 1),
                my = std::clamp(ci[1] - lo[1] + om, 0, oh - 1);
      if (!in) ++out_map[size_t(mx) + size_t(ow) * size_t(my)];
    }
    if (in)
      ++inside;
    else if (nearby)
      ++near;
    else
      ++far;
    double d2 = 1e30;
    for (size_t c = 0; c < set.size(); ++c) {
      const double dx = set.x[c] - s.x[e], dy = set.y[c] - s.y[e], dz = set.z[c] - s.z[e];
      d2 = std::min(d2, dx * dx + dy * dy + dz * dz);
    }
    if (d2 > rc * rc) {
      const double d = std::sqrt(d2);
      ++stray, sd_sum += d, sd_min = std::min(sd_min, d), sd_max = std::max(sd_max, d);
      sy_min = std::min(sy_min, double(s.y[e])), sy_max = std::max(sy_max, double(s.y[e]));
      if (s.y[e] < p.fluid.smoothing_radius * 2.0) ++below;
    }
  }
  const double n = double(s.size());
  std::printf("  fluid: inside %.3f, within a voxel outside %.3f, farther %.3f; stray %.3f", inside / n,
              near / n, far / n, stray / n);
  if (stray > 0)
    std::printf(
        " (%.1f-%.1f cm from the nearest control particle, mean %.1f; y %.1f-%.1f cm, %.2f of it "
        "on the floor)",
        100 * sd_min, 100 * sd_max, 100 * sd_sum / stray, 100 * sy_min, 100 * sy_max,
        double(below) / double(stray));
  std::printf("\n");
  if (draw)
    for (int j = oh - 1; j >= 0; --j) {
      std::printf("    |");
      for (int i = 0; i < ow; ++i) {
        const int c = out_map[size_t(i) + size_t(ow) * size_t(j)];
        std::printf("%c", c == 0 ? ' ' : c <= 2 ? '.' : char('0' + std::min(9, c / 10)));
      }
      std::printf("|\n");
    }
  // The control particles: unfilled, and off their goals.
  {
    std::vector<float> fy(s.y.begin(), s.y.end());
    std::sort(fy.begin(), fy.end());
    const float cy0 = *std::min_element(set.y.begin(), set.y.end()),
                cy1 = *std::max_element(set.y.begin(), set.y.end());
    std::printf(
        "  heights: control %.2f-%.2f cm; fluid quantiles 1/5/50/95/99%%: %.2f %.2f %.2f %.2f %.2f cm\n",
        100 * cy0, 100 * cy1, 100 * fy[fy.size() / 100], 100 * fy[fy.size() / 20], 100 * fy[fy.size() / 2],
        100 * fy[fy.size() * 19 / 20], 100 * fy[fy.size() * 99 / 100]);
  }
  long unfilled = 0;
  double off_sum = 0.0, off_max = 0.0;
  const auto& gx = ctl.goalX();
  const auto& gy = ctl.goalY();
  const auto& gz = ctl.goalZ();
  for (size_t c = 0; c < set.size(); ++c) {
    if (ctl.fields().s[c] > 0.5f) ++unfilled;
    if (gx.size() == set.size()) {
      const double dx = gx[c] - set.x[c], dy = gy[c] - set.y[c], dz = gz[c] - set.z[c];
      const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
      off_sum += d, off_max = std::max(off_max, d);
    }
  }
  std::printf(
      "  control: %ld unfilled (s > 1/2) of %zu; off their goals: mean %.2f cm, max %.2f cm; radius %.2f "
      "cm, voxel %.2f cm\n",
      unfilled, set.size(), 100 * off_sum / double(set.size()), 100 * off_max, 100 * rc, 100 * voxel);
  // How far the control set is bent: each control particle's distance from
  // its place at the best rigid fit, by fifth of the rest shape's height.
  {
    const auto [y0lo, y0hi] = std::minmax_element(set.y0.begin(), set.y0.end());
    double dev_sum[5] = {}, dev_max = 0.0, all = 0.0;
    long dev_n[5] = {};
    for (size_t c = 0; c < set.size(); ++c) {
      const ff_float3 w = ff_mat3_mul_vec(
          r, FF_F3(set.x0[c] - frame.rest_c[0], set.y0[c] - frame.rest_c[1], set.z0[c] - frame.rest_c[2]));
      const double dx = w.x + frame.c[0] - set.x[c], dy = w.y + frame.c[1] - set.y[c],
                   dz = w.z + frame.c[2] - set.z[c], d = std::sqrt(dx * dx + dy * dy + dz * dz);
      const int f = std::min(4, int(5.0 * (set.y0[c] - *y0lo) / double(*y0hi - *y0lo + 1e-9f)));
      dev_sum[f] += d, ++dev_n[f], all += d, dev_max = std::max(dev_max, d);
    }
    std::printf(
        "  control off its best rigid fit: mean %.2f cm, max %.2f cm; by fifth of the height (top first):",
        100 * all / double(set.size()), 100 * dev_max);
    for (int f = 4; f >= 0; --f) std::printf(" %.2f", dev_n[f] ? 100 * dev_sum[f] / double(dev_n[f]) : 0.0);
    std::printf(" cm\n");
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const bool fault_mode = argc > 1 && std::string(argv[1]) == "--faults";
  const int first = fault_mode ? 2 : 1;
  if (argc < first + 2) {
    std::fprintf(stderr, "usage: flowform_thin_parts [--faults] SECONDS SCENE.json...\n");
    return 2;
  }
  const double seconds = std::atof(argv[first]);
  if (!(seconds > 0.0)) {
    std::fprintf(stderr, "flowform_thin_parts: SECONDS must be a positive number, got '%s'\n", argv[first]);
    return 2;
  }
  try {
    for (int a = first + 1; a < argc; ++a) fault_mode ? faults(seconds, argv[a]) : measure(seconds, argv[a]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "flowform_thin_parts: %s\n", e.what());
    return 1;
  }
  return 0;
}
