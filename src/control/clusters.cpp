#include "control/clusters.h"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "core/error.h"
#include "target/local_thickness.h"

namespace ff {

namespace {
// Lattice coordinates are voxel indices divided by the stride: well inside
// +-2^20 for any grid the target module makes (at most 4096 voxels per axis).
int64_t key(int64_t a, int64_t b, int64_t c) {
  return (a + (1 << 20)) | ((b + (1 << 20)) << 21) | ((c + (1 << 20)) << 42);
}
// In 64 bits: a voxel index +- half_width must not overflow.
int64_t floorDiv(int64_t a, int64_t b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

// The members of one cube (ascending) split into their connected parts
// (26-neighbour voxels), each in ascending order, ordered by their first member.
std::vector<std::vector<uint32_t>> connectedParts(const std::vector<uint32_t>& m, const std::vector<int>& vi,
                                                  const std::vector<int>& vj, const std::vector<int>& vk) {
  std::unordered_map<int64_t, uint32_t> at;  // voxel -> position in m
  for (uint32_t q = 0; q < m.size(); ++q) at.emplace(key(vi[m[q]], vj[m[q]], vk[m[q]]), q);
  std::vector<int> part(m.size(), -1);
  std::vector<std::vector<uint32_t>> parts;
  std::vector<uint32_t> stack;
  for (uint32_t q0 = 0; q0 < m.size(); ++q0) {
    if (part[q0] >= 0) continue;
    const int id = int(parts.size());
    parts.emplace_back();
    part[q0] = id, stack.assign(1, q0);
    while (!stack.empty()) {
      const uint32_t q = stack.back();
      stack.pop_back();
      parts.back().push_back(m[q]);
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            auto it = at.find(key(vi[m[q]] + dx, vj[m[q]] + dy, vk[m[q]] + dz));
            if (it == at.end() || part[it->second] >= 0) continue;
            part[it->second] = id, stack.push_back(it->second);
          }
    }
    std::sort(parts.back().begin(), parts.back().end());
  }
  return parts;
}
}  // namespace

void buildClusters(ControlSet& set, const std::vector<int>& vi, const std::vector<int>& vj,
                   const std::vector<int>& vk, int stride, int half_width, bool connected,
                   const CoarseLevel& coarse) {
  const size_t n = set.size();
  const bool bars = coarse.scope == CoarseLevel::Scope::Bars;
  if (bars && coarse.parts.size() != n)
    throw Error("buildClusters: the coarse level on bars needs the part of each of the " + std::to_string(n) +
                " particles (got " + std::to_string(coarse.parts.size()) + ")");
  std::vector<std::vector<uint32_t>> kept;
  std::vector<int> kx, ky, kz;
  std::vector<int> covered(n, 0);  // in a cluster of the fine level
  // One level of clusters, centred every `stride` voxels, `half_width` wide.
  auto level = [&](int stride, int half_width, bool fine) {
    // Candidate centres: lattice points (multiples of stride) within half_width of any particle.
    std::unordered_map<int64_t, std::vector<uint32_t>> groups;
    std::vector<int64_t> centre_keys;
    std::vector<int> cxs, cys, czs;
    for (size_t p = 0; p < n; ++p) {
      if (!fine && bars && coarse.parts[p] == kPartLimb) continue;  // limbs: the fine level alone
      const int64_t w = half_width, s = stride;
      const int64_t lo[3] = {floorDiv(vi[p] - w + s - 1, s), floorDiv(vj[p] - w + s - 1, s),
                             floorDiv(vk[p] - w + s - 1, s)};
      const int64_t hi[3] = {floorDiv(vi[p] + w, s), floorDiv(vj[p] + w, s), floorDiv(vk[p] + w, s)};
      for (int64_t c = lo[2]; c <= hi[2]; ++c)
        for (int64_t b = lo[1]; b <= hi[1]; ++b)
          for (int64_t a = lo[0]; a <= hi[0]; ++a) {
            int64_t k = key(a, b, c);
            auto it = groups.find(k);
            if (it == groups.end()) {
              it = groups.emplace(k, std::vector<uint32_t>()).first;
              centre_keys.push_back(k);
              cxs.push_back(int(a * s)), cys.push_back(int(b * s)), czs.push_back(int(c * s));
            }
            it->second.push_back(uint32_t(p));
          }
    }
    // Keep clusters with at least 4 members, in deterministic (creation) order.
    for (size_t c = 0; c < centre_keys.size(); ++c) {
      auto& m = groups[centre_keys[c]];
      std::vector<std::vector<uint32_t>> parts;
      if (connected)
        parts = connectedParts(m, vi, vj, vk);
      else
        parts.push_back(std::move(m));
      for (auto& part : parts) {
        if (part.size() < 4) continue;
        // With the shape's parts, a coarse cluster holds a bar.
        if (!fine && bars &&
            std::none_of(part.begin(), part.end(), [&](uint32_t p) { return coarse.parts[p] == kPartBar; }))
          continue;
        if (fine)
          for (uint32_t p : part) covered[p] = 1;
        kept.push_back(std::move(part));
        kx.push_back(cxs[c]), ky.push_back(cys[c]), kz.push_back(czs[c]);
      }
    }
  };
  level(stride, half_width, true);
  // The coarse level (params.shape_matching.coarse_clusters): `coarse` times
  // as wide and as far apart, so that a long thin part (a bar between two
  // lumps) is matched as one piece with its ends and does not bend under the
  // fluid it holds (docs/CONTROL_UNITS.md, "Coarse clusters").
  if (coarse.factor >= 2) level(stride * coarse.factor, half_width * coarse.factor, false);
  // A particle in no cluster joins the nearest kept cluster (or, with no
  // cluster at all, every particle forms one cluster together).
  if (kept.empty() && n > 0) {
    kept.emplace_back();
    for (size_t p = 0; p < n; ++p) kept.back().push_back(uint32_t(p));
    kx.push_back(0), ky.push_back(0), kz.push_back(0);
  } else {
    for (size_t p = 0; p < n; ++p) {
      if (covered[p]) continue;
      size_t best = 0;
      long bestd = LONG_MAX;
      for (size_t c = 0; c < kept.size(); ++c) {
        long dx = long(kx[c]) - vi[p], dy = long(ky[c]) - vj[p], dz = long(kz[c]) - vk[p];
        long d = dx * dx + dy * dy + dz * dz;
        if (d < bestd) bestd = d, best = c;
      }
      kept[best].push_back(uint32_t(p));
    }
  }

  Clusters& cl = set.clusters;
  cl = Clusters();
  cl.start.push_back(0);
  for (auto& m : kept) {
    std::sort(m.begin(), m.end());
    cl.members.insert(cl.members.end(), m.begin(), m.end());
    cl.start.push_back(uint32_t(cl.members.size()));
  }
  clusterCentres(cl, set.x0, set.y0, set.z0, cl.rest_cx, cl.rest_cy, cl.rest_cz);
  // particle -> clusters
  cl.of_start.assign(n + 1, 0);
  for (uint32_t p : cl.members) ++cl.of_start[p + 1];
  for (size_t p = 0; p < n; ++p) cl.of_start[p + 1] += cl.of_start[p];
  cl.of.resize(cl.members.size());
  std::vector<uint32_t> fill(cl.of_start.begin(), cl.of_start.end() - 1);
  for (size_t c = 0; c + 1 < cl.start.size(); ++c)
    for (uint32_t k = cl.start[c]; k < cl.start[c + 1]; ++k) cl.of[fill[cl.members[k]]++] = uint32_t(c);
}

void clusterCentres(const Clusters& cl, const std::vector<float>& x, const std::vector<float>& y,
                    const std::vector<float>& z, std::vector<float>& cx, std::vector<float>& cy,
                    std::vector<float>& cz) {
  cx.clear(), cy.clear(), cz.clear();
  for (size_t c = 0; c < cl.count(); ++c) {
    double sx = 0, sy = 0, sz = 0;
    for (uint32_t k = cl.start[c]; k < cl.start[c + 1]; ++k) {
      const uint32_t p = cl.members[k];
      sx += x[p], sy += y[p], sz += z[p];
    }
    const double m = double(cl.start[c + 1] - cl.start[c]);
    cx.push_back(float(sx / m)), cy.push_back(float(sy / m)), cz.push_back(float(sz / m));
  }
}

}  // namespace ff
