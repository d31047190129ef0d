// The target cache is bounded (src/target/target_shape.h): hundreds of
// targets (each region change is a new volume) keep at most
// TargetCache::kMaxEntries shapes, the least recently used go first, and the
// shape the caller still uses is never dropped. (Unbounded, a long viewer
// session or `flowform bench --soak` grew without end.)
#include <gtest/gtest.h>

#include <vector>

#include "target/target_shape.h"

namespace {

using ff::TargetKind;
using ff::TargetShape;
using ff::TargetSpec;

constexpr double kVolume = 3000 * 0.0002 / 800.0;  // 3000 particles of the paper preset
constexpr float kVoxel = 0.0063f;

TargetSpec box(int k) {
  TargetSpec t;
  t.kind = TargetKind::Box;
  t.box_size = ff::Vec3(1.0f + 0.01f * float(k), 1.0f, 1.0f);  // a new shape each time
  return t;
}

TEST(TargetCacheBound, ManyTargetsKeepAtMostTheBoundAndTheShapeInUse) {
  ff::TargetCache cache;
  const TargetShape* in_use = &cache.get(box(0), kVolume, kVoxel);
  const size_t in_use_count = in_use->reference.size();
  const float in_use_voxel = in_use->grid.voxel;
  // The caller keeps shape 0 while it asks for 3 x kMaxEntries others.
  const int n = 3 * int(ff::TargetCache::kMaxEntries);
  for (int k = 1; k <= n; ++k) {
    cache.get(box(k), kVolume, kVoxel, in_use);
    EXPECT_LE(cache.size(), ff::TargetCache::kMaxEntries) << k;
  }
  EXPECT_LE(cache.bytes(), ff::TargetCache::kMaxBytes);
  // Shape 0 is still there, intact, and found again without a new voxelisation.
  EXPECT_EQ(in_use->reference.size(), in_use_count);
  EXPECT_EQ(in_use->grid.voxel, in_use_voxel);
  const size_t voxelised = cache.voxelisations();
  EXPECT_EQ(&cache.get(box(0), kVolume, kVoxel, in_use), in_use);
  EXPECT_EQ(cache.voxelisations(), voxelised);
  // The most recent shape is still cached; one of the first ones was dropped
  // and is voxelised again when asked for.
  cache.get(box(n), kVolume, kVoxel, in_use);
  EXPECT_EQ(cache.voxelisations(), voxelised);
  cache.get(box(1), kVolume, kVoxel, in_use);
  EXPECT_EQ(cache.voxelisations(), voxelised + 1);
  EXPECT_EQ(size_t(n + 2), cache.voxelisations());
}

TEST(TargetCacheBound, TheSameShapeAtManyVolumesIsRescaledWithinTheBound) {
  // A region change makes the same shape at another volume: rescaled copies,
  // one voxelisation, still bounded.
  ff::TargetCache cache;
  const TargetShape* current = nullptr;
  for (int k = 0; k < 100; ++k) current = &cache.get(box(0), kVolume * (1.0 + 0.01 * k), kVoxel, current);
  EXPECT_EQ(cache.voxelisations(), 1u);
  EXPECT_LE(cache.size(), ff::TargetCache::kMaxEntries);
  EXPECT_GT(current->reference.size(), 0u);
}

}  // namespace
