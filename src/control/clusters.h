// clusters.h - overlapping shape-matching clusters over the reference voxels.
#pragma once
#include <cstdint>
#include <vector>

#include "control/control_set.h"

namespace ff {

// Builds clusters for control particles whose rest positions sit on a voxel
// lattice of spacing `voxel` (coordinates vi, vj, vk per particle). A cluster is
// centred on every lattice point whose coordinates are multiples of `stride`
// and holds the particles within `half_width` voxels of it (a cube). Clusters
// with fewer than 4 particles are dropped; a particle left in no cluster joins
// the cluster whose centre is nearest. Fills set.clusters (members in
// ascending particle order, rest centres, particle -> cluster lists).
// connected (adaptive control, "clusters follow limbs"): the particles in a
// cube that are not connected to each other inside it (voxels touching by a
// face, edge or corner) form separate clusters, so that two limbs, or a limb
// and the body, that pass through one cube are not matched as one rigid piece.
// coarse.factor >= 2 adds a second level of clusters (CoarseLevel) after the
// first (a particle's goal is the mean over the clusters of both levels that
// hold it).
struct CoarseLevel {
  // Where the coarse clusters are (params.shape_matching.coarse_bars,
  // docs/CONTROL_UNITS.md, "Coarse clusters on bars"): over the whole shape,
  // or only those that hold a bar particle, built without the limb particles.
  enum class Scope { WholeShape, Bars };
  int factor = 0;  // params.shape_matching.coarse_clusters: times the stride and half_width; < 2: none
  Scope scope = Scope::WholeShape;
  std::vector<uint8_t> parts;  // Bars: each particle's part of the shape (kPartLump, kPartBar, kPartLimb)
};
void buildClusters(ControlSet& set, const std::vector<int>& vi, const std::vector<int>& vj,
                   const std::vector<int>& vk, int stride, int half_width, bool connected = false,
                   const CoarseLevel& coarse = CoarseLevel());

// Each cluster's centre of mass over the points (x, y, z)[p], summed in
// double in member order (the rest centres of buildClusters, the blend's
// start centres of startBlend).
void clusterCentres(const Clusters& cl, const std::vector<float>& x, const std::vector<float>& y,
                    const std::vector<float>& z, std::vector<float>& cx, std::vector<float>& cy,
                    std::vector<float>& cz);

}  // namespace ff
