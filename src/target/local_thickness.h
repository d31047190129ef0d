// local_thickness.h - how thick a voxelised shape is around each of its
// voxels: the diameter of the largest ball inside the shape that contains the
// voxel (Hildebrand & Rüegsegger 1997's local thickness), from the Euclidean
// distance transform of the voxel grid. Adaptive control
// (docs/CONTROL_UNITS.md, "Thin features") reads it.
#pragma once
#include <cstdint>
#include <vector>

#include "target/target_shape.h"

namespace ff {

// Per voxel (grid index order): the squared distance, in voxels, from its
// centre to the nearest outside voxel's centre; 0 outside. Exact (separable
// lower envelopes of parabolas, Felzenszwalb & Huttenlocher 2012). The grid
// must have outside voxels (makeVoxelGrid leaves a border of them).
std::vector<float> squaredDistanceToOutside(const VoxelGrid& g);

// Per voxel (grid index order): the local thickness in the grid's length
// unit, at most `cap`; 0 outside. The balls are centred on voxel centres and
// reach the shape's surface, taken half a voxel short of the nearest outside
// voxel's centre: a slab k voxels thick has thickness k voxels for odd k and
// k - 1 for even k (its middle lies between two voxel centres; a single
// voxel has thickness 1 voxel). The balls are stamped up to a diameter of
// 2 `cap` (a voxel inside a thicker part gets `cap`), which bounds the work by
// the voxels times (2 cap / voxel)^3.
std::vector<float> localThickness(const VoxelGrid& g, float cap);

// How many voxels of the shape's medial ridge are at most `thickness` voxels
// thick: of the inside voxels at least sqrt(2) voxels deep whose squared
// distance to the outside is at least each of their 26 neighbours' (the
// centre lines and sheets of limbs, bars and plates, where the largest
// inside balls sit), those whose ball is at most that thick (2 sqrt(d2) - 1,
// as localThickness). A limb k voxels across adds about one to four voxels
// per voxel of its length; a thick letter's strokes add none, nor do the
// thin rims every box-like shape has along its edges (they lie off the
// ridge), nor single voxels standing out of a staircase surface (1 deep).
long thinRidgeVoxels(const VoxelGrid& g, float thickness);

// Per voxel (grid index order): 1 where the voxel is inside and its local
// thickness (localThickness) is below `thickness` (in the grid's length
// unit), else 0: the thin parts of the metric `filled_thin`
// (docs/METRICS.md), below the control radius.
std::vector<uint8_t> thinVoxels(const VoxelGrid& g, float thickness);

// The parts of a shape (docs/CONTROL_UNITS.md, "Coarse clusters on bars"),
// per voxel (grid index order): kPartOutside, kPartLump, kPartBar or
// kPartLimb. A lump is a thick part: the voxels within r of a voxel at least
// r deep (distance to the outside, in voxels), r = kLumpDepthShare of the
// shape's largest depth (a morphological opening by a ball of radius r),
// 26-connected, holding at least kLumpVolumeShare of the shape's voxels. The
// rest of the shape falls into 26-connected thin parts. A thin part that
// touches two different lumps, with at least `min_length` voxels between the
// centres of its patches of contact, is a bar (two lumps joined by a bar);
// every other thin part (a limb with a free end, a handle on one lump, a
// neck shorter than min_length, a rim, a shape with no lump at all) is a
// limb. Depths are relative to the shape's own, so a scaled or finer
// voxelised shape has the same lumps.
constexpr uint8_t kPartOutside = 0, kPartLump = 1, kPartBar = 2, kPartLimb = 3;
constexpr float kLumpDepthShare = 0.4f;
constexpr double kLumpVolumeShare = 0.05;
std::vector<uint8_t> shapeParts(const VoxelGrid& g, float min_length);

// The Euler characteristic of the union of the inside voxels as closed unit
// cubes: vertices - edges + faces - cubes. A solid ball gives 1, a solid
// torus (a ring, a letter O) 0, a body with two holes -1: each handle
// (closed loop through the shape) lowers it by one, each sealed cavity
// raises it by one.
long eulerCharacteristic(const VoxelGrid& g);

// The most branches that meet at one point of the shape (docs/CONTROL_UNITS.md,
// "Coarse clusters on crossings"): for each centre, an inside voxel at least
// half the shape's largest depth D deep (every second voxel along each axis),
// the inside voxels reached from it without leaving the ball of radius
// R = kBranchShellDepths D + 1 are flooded (26-connected), and the reached
// voxels farther than R - 2 from the centre fall into 26-connected pieces:
// each is a branch that leaves the ball. A point along a stroke or a bar has
// 2, a free end 1, a plate (a ring around the centre) 1, a lump wider than
// the ball 0, the crossing of an X 4, the junction of a Y, K or T 3. Branches
// shorter than about R from the centre (a bump, a serif) do not reach the
// shell, and a stroke that bends back into the ball (an S) is not reached
// from the centre inside it. Relative to D, so a scaled or finer voxelised
// shape has the same count.
constexpr float kBranchShellDepths = 3.0f;
constexpr int kJunctionBranches = 3;  // a junction: at least this many branches
int mostBranches(const VoxelGrid& g);

}  // namespace ff
