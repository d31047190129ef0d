#include "control/placement.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "control/clusters.h"
#include "core/error.h"
#include "target/local_thickness.h"

namespace ff {

namespace {

// A per-voxel array of g (grid index order) at the reference particles:
// reference[p] is the p-th inside voxel in grid index order (at most n).
template <class T>
std::vector<T> atReference(const VoxelGrid& g, const std::vector<T>& per_voxel, size_t n) {
  std::vector<T> out;
  out.reserve(n);
  for (size_t c = 0; c < g.inside.size() && out.size() < n; ++c)
    if (g.inside[c]) out.push_back(per_voxel[c]);
  return out;
}

}  // namespace

AdaptiveControl adaptiveControl(const ControlParams& cp, float voxel, float fluid_spacing) {
  AdaptiveControl a;
  a.on = cp.adaptive != 0;
  a.radius = cp.radius;
  a.min_radius = std::fmin(cp.radius, std::fmax(1.5f * voxel, 2.0f * fluid_spacing));
  return a;
}

ClusterSize clusterSize(const ShapeMatchParams& sm, int extent, bool limbs) {
  ClusterSize c;
  c.half_width = sm.cluster_half_width;
  if (limbs) c.half_width = std::max(c.half_width, int(std::lround(double(extent) / kClusterSpanShare)));
  c.stride = std::max(1, int(std::lround(double(sm.cluster_stride) * c.half_width / sm.cluster_half_width)));
  return c;
}

Standing standingFor(const float gravity[3]) {
  Standing s;
  float most = 0.0f;
  for (int d = 0; d < 3; ++d)
    if (std::fabs(gravity[d]) > most)
      most = std::fabs(gravity[d]), s.axis = d, s.side = gravity[d] < 0 ? -1 : 1;
  return s;
}

float blendTime(const ControlSet& set, float falls, const float gravity[3]) {
  if (!(falls > 0.0f) || set.size() == 0) return 0.0f;
  double b[3], r[3];
  centreOfMass(set.x, set.y, set.z, b);
  centreOfMass(set.x0, set.y0, set.z0, r);
  double d2 = 0.0;
  for (size_t p = 0; p < set.size(); ++p) {
    const double dx = (double(set.x0[p]) - r[0]) - (double(set.x[p]) - b[0]);
    const double dy = (double(set.y0[p]) - r[1]) - (double(set.y[p]) - b[1]);
    const double dz = (double(set.z0[p]) - r[2]) - (double(set.z[p]) - b[2]);
    d2 = std::max(d2, dx * dx + dy * dy + dz * dz);
  }
  double g = std::sqrt(double(gravity[0]) * gravity[0] + double(gravity[1]) * gravity[1] +
                       double(gravity[2]) * gravity[2]);
  if (!(g > 0.0)) g = 9.81;
  return float(double(falls) * std::sqrt(2.0 * std::sqrt(d2) / g));
}

void startBlend(ControlSet& set, float falls, const float gravity[3]) {
  startBlendOver(set, blendTime(set, falls, gravity));
}

void startBlendOver(ControlSet& set, float t) {
  set.bx0.clear(), set.by0.clear(), set.bz0.clear();
  Clusters& cl = set.clusters;
  cl.from_cx.clear(), cl.from_cy.clear(), cl.from_cz.clear();
  set.blend_time = 0.0f, set.blend_elapsed = 0.0;
  if (!(t > 0.0f)) return;
  set.bx0 = set.x, set.by0 = set.y, set.bz0 = set.z;
  // Each cluster's start centre, summed as its rest centre (buildClusters).
  clusterCentres(cl, set.bx0, set.by0, set.bz0, cl.from_cx, cl.from_cy, cl.from_cz);
  set.blend_time = t;
}

ControlSet placeControlParticles(const TargetShape& target, const Vec3& lo, const Vec3& hi,
                                 const ShapeMatchParams& sm, const Vec3& box_lo, const Vec3& box_hi,
                                 const AdaptiveControl& adaptive, const Standing& standing) {
  const size_t n = target.reference.size();
  if (n == 0) throw Error("target '" + target.label + "' has no reference particles");
  Vec3 tlo = target.reference[0], thi = target.reference[0];
  for (const Vec3& r : target.reference) tlo = tlo.cwiseMin(r), thi = thi.cwiseMax(r);
  Vec3 text = thi - tlo, rext = hi - lo;

  ControlSet set;
  for (auto* a : {&set.x, &set.y, &set.z, &set.vx, &set.vy, &set.vz, &set.x0, &set.y0, &set.z0}) a->resize(n);
  std::vector<int> vi(n), vj(n), vk(n);
  const VoxelGrid& g = target.grid;
  double sx = 0, sy = 0, sz = 0;
  for (size_t p = 0; p < n; ++p) {
    const Vec3& r = target.reference[p];
    Vec3 pos;
    for (int d = 0; d < 3; ++d) {
      float u = text[d] > 0 ? (r[d] - tlo[d]) / text[d] : 0.5f;
      pos[d] = lo[d] + u * rext[d];
      if (d == standing.axis && standing.unstretched &&
          text[d] < rext[d])  // stands on the region's floor, unstretched
        pos[d] = standing.side < 0 ? lo[d] + (r[d] - tlo[d]) : hi[d] - (thi[d] - r[d]);
    }
    set.x[p] = pos.x(), set.y[p] = pos.y(), set.z[p] = pos.z();
    set.vx[p] = set.vy[p] = set.vz[p] = 0.0f;
    set.x0[p] = r.x(), set.y0[p] = r.y(), set.z0[p] = r.z();
    sx += r.x(), sy += r.y(), sz += r.z();
    vi[p] = int(std::floor((r.x() - g.origin.x()) / g.voxel));
    vj[p] = int(std::floor((r.y() - g.origin.y()) / g.voxel));
    vk[p] = int(std::floor((r.z() - g.origin.z()) / g.voxel));
  }
  set.particle_volume = g.voxel * g.voxel * g.voxel;
  set.rest_cx = float(sx / double(n)), set.rest_cy = float(sy / double(n)),
  set.rest_cz = float(sz / double(n));

  // Fit the rigid goal shape (rest shape around the placed centre of mass) into the container.
  double px = 0, py = 0, pz = 0;
  for (size_t p = 0; p < n; ++p) px += set.x[p], py += set.y[p], pz += set.z[p];
  const Vec3 com(float(px / double(n)), float(py / double(n)), float(pz / double(n)));
  const Vec3 rest_c(set.rest_cx, set.rest_cy, set.rest_cz);
  const float margin = 0.5f * g.voxel;
  Vec3 shift(0, 0, 0);
  for (int d = 0; d < 3; ++d) {
    const float glo = com[d] + (tlo[d] - rest_c[d]) - margin, ghi = com[d] + (thi[d] - rest_c[d]) + margin;
    if (ghi - glo >= box_hi[d] - box_lo[d])
      shift[d] = 0.5f * (box_lo[d] + box_hi[d]) - 0.5f * (glo + ghi);
    else if (glo < box_lo[d])
      shift[d] = box_lo[d] - glo;
    else if (ghi > box_hi[d])
      shift[d] = box_hi[d] - ghi;
    // The anchor (ff_anchor.h) holds the set where the rigid shape fits,
    // however far that is from the region.
    // Along gravity, where it stands on the floor if it would be held out
    // of reach above it (Standing).
    float anchor = com[d] + shift[d];
    if (d == standing.axis && ghi - glo < box_hi[d] - box_lo[d]) {
      const float floor_shift = standing.side < 0 ? box_lo[d] - glo : box_hi[d] - ghi;
      if (std::fabs(shift[d] - floor_shift) > standing.reach) anchor = com[d] + floor_shift;
    }
    (d == 0 ? set.anchor_x : d == 1 ? set.anchor_y : set.anchor_z) = anchor;
    // Never by more than half the region: the particles must start over
    // their fluid, or they would form the shape away from it. Except, at a
    // target change, along gravity: a shape taller than its region (the
    // capsule over the torus's flat fluid) then starts standing on the floor,
    // not partly under it, from where it would rise with its fluid after it
    // formed (2.3 cm, docs/CONTROL_UNITS.md, "Anchor"); the blend starts its
    // goals where its particles are. The first target keeps the cap: the
    // runner, squashed 3x into its fluid column, forms faster from there
    // (0.911 against 0.864 at 3 s).
    const float cap =
        d == standing.axis && standing.unstretched ? std::numeric_limits<float>::infinity() : 0.5f * rext[d];
    shift[d] = std::fmax(-cap, std::fmin(cap, shift[d]));
  }
  for (size_t p = 0; p < n; ++p) set.x[p] += shift.x(), set.y[p] += shift.y(), set.z[p] += shift.z();
  set.radius_scale.assign(n, 1.0f);
  if (adaptive.on && adaptive.radius > 0.0f) {
    const std::vector<float> t = atReference(g, localThickness(g, adaptive.radius), n);
    for (size_t p = 0; p < t.size(); ++p)
      set.radius_scale[p] =
          std::fmin(adaptive.radius, std::fmax(adaptive.min_radius, t[p])) / adaptive.radius;
  }
  int extent = 0;  // voxels along the longest axis
  for (const std::vector<int>* v : {&vi, &vj, &vk}) {
    const auto [mn, mx] = std::minmax_element(v->begin(), v->end());
    extent = std::max(extent, *mx - *mn + 1);
  }
  const bool limbs = std::lround(double(extent) / kClusterSpanShare) > sm.cluster_half_width &&
                     thinRidgeVoxels(g, float(2 * sm.cluster_half_width + 1)) * kLimbLengthShare >= extent;
  const ClusterSize cs = clusterSize(sm, extent, limbs);
  // The coarse level on bars alone (docs/CONTROL_UNITS.md, "Coarse clusters
  // on bars") with coarse_bars, from each particle's part of the shape; over
  // the whole shape without it, and on a shape with a closed loop (a ring, a
  // letter O or A: Euler characteristic <= 0) and no limbs
  // (docs/CONTROL_UNITS.md, "Coarse clusters on loops"), or whose strokes
  // meet at a junction of three or more branches and no limbs (an X, Y or
  // H: "Coarse clusters on crossings").
  CoarseLevel coarse;
  coarse.factor = sm.coarse_clusters;
  if (sm.coarse_clusters >= 2 && sm.coarse_bars &&
      (limbs || (eulerCharacteristic(g) > 0 && mostBranches(g) < kJunctionBranches))) {
    coarse.parts = atReference(g, shapeParts(g, float(2 * cs.half_width + 1)), n);
    if (coarse.parts.size() == n) coarse.scope = CoarseLevel::Scope::Bars;
  }
  buildClusters(set, vi, vj, vk, cs.stride, cs.half_width, adaptive.on, coarse);
  return set;
}

}  // namespace ff
