// voxelize.cpp - inside/outside of voxel centres by ray parity.
//
// Method (chosen over the generalised winding number, which costs O(triangles)
// per voxel unless a hierarchy is built): for each axis, one ray per voxel
// column runs through the column's voxel centres. Every triangle is binned
// onto the columns whose centres its projection can cover (its 2-D bounding
// box in the column plane, so each triangle only meets the few columns it
// touches), the crossing depths of each column are sorted, and a voxel centre
// is inside for that axis when an odd number of crossings lie below it. The
// final answer is a 2-of-3 majority vote over x, y and z: a small hole, or a
// duplicated (non-manifold) face, flips the parity of the columns through it
// along one axis, but the other two rays through those voxels still agree.
// Cost: O(triangles + voxels), a few milliseconds for 60k triangles.
//
// Robust counting: the column centres are nudged by a tiny irrational fraction
// of a voxel, so that meshes built on round numbers are not hit exactly on
// edges and vertices. Remaining exact hits are settled consistently: edge
// functions are evaluated with the edge's endpoints in a canonical order (the
// two triangles sharing an edge get exactly opposite values), and a point on
// an edge or vertex belongs to the triangle that contains it after a symbolic
// shift by (eps, eps^2) in the column plane. A triangle parallel to the ray is
// skipped: its neighbours account for the crossing.
#include "target/voxelize.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"

namespace ff {
namespace {

constexpr double kNudgeU = 0.73162e-4;  // fractions of a voxel
constexpr double kNudgeV = 0.41421e-4;

struct P {
  double u, v, a;  // column-plane coordinates, and depth along the ray
};

// 2-D orientation of c relative to the edge a->b (> 0: c on the left), computed
// with the endpoints in lexicographic order so it is exactly antisymmetric.
inline double edgeFunction(const P& a, const P& b, double cu, double cv) {
  if (a.u < b.u || (a.u == b.u && a.v < b.v)) return (b.u - a.u) * (cv - a.v) - (b.v - a.v) * (cu - a.u);
  return -((a.u - b.u) * (cv - b.v) - (a.v - b.v) * (cu - b.u));
}

// For a point exactly on the edge a->b of a counter-clockwise triangle: does
// the point shifted by (eps, eps^2) lie on the triangle's side?
inline bool ownsEdgePoint(const P& a, const P& b) {
  const double du = b.u - a.u, dv = b.v - a.v;
  return dv < 0.0 || (dv == 0.0 && du > 0.0);
}

inline bool insideEdge(double w, const P& a, const P& b) {
  return w > 0.0 || (w == 0.0 && ownsEdgePoint(a, b));
}

// Candidate column range [first, last] (clamped to [0, n - 1]) for a
// triangle spanning t in [tmin, tmax], t being the position in units of the
// voxel size relative to the centre of column 0. `margin` (in voxels) covers
// the rounding of the float centres; extra candidates are rejected by the
// exact edge test.
inline void columnRange(float tmin, float tmax, float margin, int n, int& first, int& last) {
  if (!(tmin <= tmax)) {  // NaN coordinates: no columns
    first = 1;
    last = 0;
    return;
  }
  first = int(std::ceil(std::max(tmin - margin, -1.0f)));
  last = int(std::floor(std::min(tmax + margin, float(n))));
  first = std::max(first, 0);
  last = std::min(last, n - 1);
}

struct Hit {
  int column;
  double depth;
};

}  // namespace

VoxelGrid makeVoxelGrid(const Vec3& lo, const Vec3& hi, float voxel, const Vec3& shift) {
  if (!(voxel > 0.0f) || !std::isfinite(voxel)) {
    std::ostringstream msg;
    msg << "voxel size must be a positive number (got " << voxel << ")";
    throw Error(msg.str());
  }
  VoxelGrid grid;
  grid.voxel = voxel;
  int* n[3] = {&grid.nx, &grid.ny, &grid.nz};
  double total = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double extent = std::max(0.0, double(hi[a]) - double(lo[a]));
    const double count = std::ceil(extent / voxel) + 2.0 + (shift[a] != 0.0f ? 1.0 : 0.0);
    total *= count;
    if (!(count <= kMaxVoxelsPerAxis) || !(total <= kMaxVoxels)) {
      std::ostringstream msg;
      msg << "voxel size " << voxel << " is too small for a shape " << (hi - lo).transpose()
          << " across: the voxel grid would be too large";
      throw Error(msg.str());
    }
    *n[a] = int(count);
    const double centre = 0.5 * (double(lo[a]) + double(hi[a]));
    grid.origin[a] = float(centre - 0.5 * count * voxel + double(shift[a]) * voxel);
  }
  grid.inside.assign(size_t(grid.nx) * size_t(grid.ny) * size_t(grid.nz), 0);
  return grid;
}

void rayParity(const TriangleMesh& mesh, const VoxelGrid& grid, int axis, std::vector<uint8_t>& parity) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const int n[3] = {grid.nx, grid.ny, grid.nz};
  const int nu = n[u], nv = n[v], na = n[axis];
  const float h = grid.voxel;
  const double hd = h;
  const double nudge_u = kNudgeU * hd, nudge_v = kNudgeV * hd;
  // Column centres as VoxelGrid::center computes them, then nudged.
  auto centreU = [&](int i) { return double(grid.origin[u] + h * (float(i) + 0.5f)) + nudge_u; };
  auto centreV = [&](int i) { return double(grid.origin[v] + h * (float(i) + 0.5f)) + nudge_v; };

  // t = (x - centre of column 0) / h, and the rounding margin for it: float
  // centres are off by a few ulps of the largest coordinate.
  const float base_u = float(centreU(0)), base_v = float(centreV(0)), inv_h = 1.0f / h;
  const float margin_u = 0.01f + 1e-6f * (std::abs(grid.origin[u]) + float(nu) * h) * inv_h;
  const float margin_v = 0.01f + 1e-6f * (std::abs(grid.origin[v]) + float(nv) * h) * inv_h;

  std::vector<Hit> hits;
  hits.reserve(size_t(nu) * size_t(nv) / 2 + 16);
  for (const auto& tri : mesh.triangles) {
    const Vec3& x0 = mesh.vertices[size_t(tri[0])];
    const Vec3& x1 = mesh.vertices[size_t(tri[1])];
    const Vec3& x2 = mesh.vertices[size_t(tri[2])];
    int iu0, iu1, iv0, iv1;
    columnRange((std::min({x0[u], x1[u], x2[u]}) - base_u) * inv_h,
                (std::max({x0[u], x1[u], x2[u]}) - base_u) * inv_h, margin_u, nu, iu0, iu1);
    if (iu0 > iu1) continue;  // no column centre near it (most triangles, on one of the axes)
    columnRange((std::min({x0[v], x1[v], x2[v]}) - base_v) * inv_h,
                (std::max({x0[v], x1[v], x2[v]}) - base_v) * inv_h, margin_v, nv, iv0, iv1);
    if (iv0 > iv1) continue;
    P p[3] = {{x0[u], x0[v], x0[axis]}, {x1[u], x1[v], x1[axis]}, {x2[u], x2[v], x2[axis]}};
    const double area2 = (p[1].u - p[0].u) * (p[2].v - p[0].v) - (p[1].v - p[0].v) * (p[2].u - p[0].u);
    if (!(area2 != 0.0) || !std::isfinite(area2)) continue;  // parallel to the ray (or garbage)
    if (area2 < 0.0) std::swap(p[1], p[2]);                  // counter-clockwise in the column plane
    for (int iv = iv0; iv <= iv1; ++iv) {
      const double cv = centreV(iv);
      for (int iu = iu0; iu <= iu1; ++iu) {
        const double cu = centreU(iu);
        const double w0 = edgeFunction(p[1], p[2], cu, cv);
        const double w1 = edgeFunction(p[2], p[0], cu, cv);
        const double w2 = edgeFunction(p[0], p[1], cu, cv);
        if (!insideEdge(w0, p[1], p[2]) || !insideEdge(w1, p[2], p[0]) || !insideEdge(w2, p[0], p[1]))
          continue;
        const double sum = w0 + w1 + w2;
        const double depth =
            sum > 0.0 ? (w0 * p[0].a + w1 * p[1].a + w2 * p[2].a) / sum : (p[0].a + p[1].a + p[2].a) / 3.0;
        hits.push_back({iu + nu * iv, depth});
      }
    }
  }

  // Group the hits by column (counting sort), then sort each column by depth.
  std::vector<int> start(size_t(nu) * size_t(nv) + 1, 0);
  for (const Hit& hit : hits) ++start[size_t(hit.column) + 1];
  for (size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<double> depth(hits.size());
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (const Hit& hit : hits) depth[size_t(fill[size_t(hit.column)]++)] = hit.depth;
  }

  parity.assign(size_t(grid.nx) * size_t(grid.ny) * size_t(grid.nz), 0);
  const float oa = grid.origin[axis];
  for (int iv = 0; iv < nv; ++iv) {
    for (int iu = 0; iu < nu; ++iu) {
      const int column = iu + nu * iv;
      auto first = depth.begin() + start[size_t(column)], last = depth.begin() + start[size_t(column) + 1];
      if (first == last) continue;
      std::sort(first, last);
      int ijk[3];
      ijk[u] = iu;
      ijk[v] = iv;
      uint8_t odd = 0;
      for (int k = 0; k < na; ++k) {
        const double z = double(oa + h * (float(k) + 0.5f));
        while (first != last && *first < z) {
          odd ^= 1;
          ++first;
        }
        ijk[axis] = k;
        parity[grid.index(ijk[0], ijk[1], ijk[2])] = odd;
      }
    }
  }
}

void voxelizeMesh(const TriangleMesh& mesh, VoxelGrid& grid) {
  std::vector<uint8_t> votes[3];
#pragma omp parallel for schedule(static, 1)
  for (int axis = 0; axis < 3; ++axis) rayParity(mesh, grid, axis, votes[axis]);
  grid.inside.resize(votes[0].size());
  for (size_t i = 0; i < grid.inside.size(); ++i)
    grid.inside[i] = uint8_t(votes[0][i] + votes[1][i] + votes[2][i] >= 2);
}

}  // namespace ff
