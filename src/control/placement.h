// placement.h - control particles from reference particles (paper Fig. 7).
#pragma once
#include "control/control_set.h"
#include "core/params.h"
#include "core/vec3.h"
#include "target/target_shape.h"

namespace ff {

// Places one control particle per reference particle of `target`, by the
// linear map of the reference particles' bounding box onto [lo, hi] (the
// bounding box of the user's fluid region). Rest positions are the reference
// positions; velocities start at zero; clusters are built from the voxels.
//
// Shape matching keeps the placed particles' centre of mass, so the target
// forms around it. Where the rigid shape around that centre would cross the
// container [box_lo, box_hi], all particles are shifted so that it fits (a
// shape that is larger than the container along an axis is centred on it):
// otherwise the walls would push the forming shape away from its fluid. The
// shift is at most half the region's extent along each axis, so the particles
// still start over the fluid they control; at a target change (`standing`
// given) not along gravity, so that a tall shape starts standing on the floor.
//
// With `adaptive` on (thin features, docs/CONTROL_UNITS.md): each particle's
// radius_scale is the target's local thickness around its voxel
// (target/local_thickness.h), clamped to [min_radius, radius], as a share of
// radius; and the clusters follow limbs (buildClusters' `connected`). Off:
// every radius_scale is 1 and the clusters are the paper's cubes.
struct AdaptiveControl {
  bool on = false;
  float radius = 0.0f;      // params.control.radius: the largest radius
  float min_radius = 0.0f;  // the smallest (adaptiveControl)
};
// The adaptive control of `cp` for a target of voxel size `voxel` and fluid of
// particle spacing `fluid_spacing`: the smallest radius is 2 fluid spacings
// (the fluid sum of eq. 5 then still holds ~30 particles) and 1.5 voxels
// (the control sums of eq. 4 and 6 still hold ~14 control particles), never
// above cp.radius.
AdaptiveControl adaptiveControl(const ControlParams& cp, float voxel, float fluid_spacing);

// The clusters' size for a shape `extent` voxels long along its longest axis
// (docs/CONTROL_UNITS.md, "Thin features"). A shape with `limbs` (a medial
// ridge no thicker than a cluster of sm's is wide, at least 1 /
// kLimbLengthShare of the shape's length: thinRidgeVoxels) gets clusters of half-width at least extent /
// kClusterSpanShare voxels, never below sm's, with the stride grown in
// proportion (so a control particle still belongs to as many clusters).
// Across such a limb there is one cluster, and a chain of small clusters
// bends where a long limb hangs from the body (a stick figure's legs: 2.2 cm
// off its rigid fit at 3 s, iou 0.67); clusters of a fixed share of the shape
// hold it. Where several clusters lie side by side across a part (a letter's
// strokes, 8 voxels thick) they hold it already, and larger ones only slow
// its forming (the letter T: 0.921 -> 0.819 at 3 s on water): a shape
// without limbs, or up to 37 voxels long (the Table 1 shapes, 26-37), keeps
// sm's size.
constexpr int kClusterSpanShare = 15;
constexpr int kLimbLengthShare = 8;
struct ClusterSize {
  int stride = 2, half_width = 2;
};
ClusterSize clusterSize(const ShapeMatchParams& sm, int extent, bool limbs);

// Where a shape lower than its region stands (a target change: the region
// is the fluid of the current shape, which rests on the floor): along `axis`
// (gravity's, -1: none) on the region's low side (side -1) or high side (+1),
// unstretched, instead of stretched over the region's whole extent, whose
// middle the shape would otherwise form around, in the air above the fluid
// that then falls out of its reach (Fig. 12's box, 7% of its fluid, on the
// water preset). A shape at least as tall as the region is placed as before.
//
// Along that axis the anchor (ff_anchor.h) is where the rigid rest shape
// stands on the container's floor wherever the shape would otherwise be
// anchored more than `reach` (the control radius) above it: the standing
// anchor keeps a set from rising above its anchor, so a shape lower than its
// fluid column, placed stretched over it at the first target, was held at the
// column's middle, in the air, with the fluid under it out of the control's
// reach (lying letters and flat discs 6-8 cm up, 2.5-4 % of their fluid
// stray; docs/RESULTS.md, "The unseen set"). A shape anchored within reach
// of the floor keeps its anchor (the water teapot, 1.3 cm up, sinks to the
// floor as it forms). `unstretched` false (the first target) keeps the
// stretched placement and the capped shift and moves only the anchor.
struct Standing {
  int axis = -1, side = -1;
  bool unstretched = true;
  float reach = 0.0f;
};
// Standing on the floor for `gravity`: its largest component's axis, on the
// side it points to (none for zero gravity).
Standing standingFor(const float gravity[3]);

// The rest-shape blend of a target change (params.shape_matching.blend,
// docs/CONTROL_UNITS.md, "Rest-shape blend"): the start configuration is where
// placement put the particles (set.x, y, z), so the goals start where the
// particles are; the blend lasts `falls` times sqrt(2 d / g) with d the
// largest distance a rest position moves relative to the shape's centre of
// mass (g: gravity's magnitude, 9.81 m/s^2 when it is 0). falls <= 0 or
// d = 0: no blend (the arrays stay empty).
float blendTime(const ControlSet& set, float falls, const float gravity[3]);
void startBlend(ControlSet& set, float falls, const float gravity[3]);
// The same blend over `t` seconds (t <= 0: none).
void startBlendOver(ControlSet& set, float t);

ControlSet placeControlParticles(const TargetShape& target, const Vec3& lo, const Vec3& hi,
                                 const ShapeMatchParams& sm, const Vec3& box_lo, const Vec3& box_hi,
                                 const AdaptiveControl& adaptive = AdaptiveControl(),
                                 const Standing& standing = Standing());

}  // namespace ff
