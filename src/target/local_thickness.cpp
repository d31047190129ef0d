#include "target/local_thickness.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace ff {

namespace {

// One pass of the exact 1-D squared distance transform along a line of n
// values f (squared distances so far, infinity where unknown), in place.
// v, z: scratch of n and n + 1.
void distance1d(float* f, int n, size_t stride, std::vector<int>& v, std::vector<float>& z,
                std::vector<float>& out) {
  const float inf = std::numeric_limits<float>::infinity();
  v.resize(size_t(n)), z.resize(size_t(n) + 1), out.resize(size_t(n));
  int k = -1;
  for (int q = 0; q < n; ++q) {
    const float fq = f[size_t(q) * stride];
    if (fq == inf) continue;
    float s = 0.0f;
    while (k >= 0) {
      const int p = v[size_t(k)];
      const float fp = f[size_t(p) * stride];
      s = ((fq + float(q) * float(q)) - (fp + float(p) * float(p))) / (2.0f * float(q - p));
      if (s > z[size_t(k)]) break;
      --k;
    }
    ++k;
    v[size_t(k)] = q, z[size_t(k)] = k == 0 ? -inf : s, z[size_t(k) + 1] = inf;
  }
  if (k < 0) return;  // nothing known on this line
  for (int q = 0, j = 0; q < n; ++q) {
    while (z[size_t(j) + 1] < float(q)) ++j;
    const int p = v[size_t(j)];
    out[size_t(q)] = float(q - p) * float(q - p) + f[size_t(p) * stride];
  }
  for (int q = 0; q < n; ++q) f[size_t(q) * stride] = out[size_t(q)];
}

// Calls visit(a, b, c) on the voxels of g within w of (i, j, k) along each
// axis (w = 1: the voxel and its 26 neighbours), in grid index order, until
// visit returns false.
template <class Visit>
void forBox(const VoxelGrid& g, int i, int j, int k, int w, Visit&& visit) {
  for (int c = std::max(0, k - w); c <= std::min(g.nz - 1, k + w); ++c)
    for (int b = std::max(0, j - w); b <= std::min(g.ny - 1, j + w); ++b)
      for (int a = std::max(0, i - w); a <= std::min(g.nx - 1, i + w); ++a)
        if (!visit(a, b, c)) return;
}

// The 26-connected components of the voxels where mask is set: a component
// number per voxel (-1 elsewhere), numbered in grid index order of their
// first voxel; n gets the count.
std::vector<int> components(const VoxelGrid& g, const std::vector<uint8_t>& mask, int& n) {
  std::vector<int> comp(mask.size(), -1);
  std::vector<size_t> stack;
  n = 0;
  for (size_t s = 0; s < mask.size(); ++s) {
    if (!mask[s] || comp[s] >= 0) continue;
    comp[s] = n, stack.assign(1, s);
    while (!stack.empty()) {
      const size_t q = stack.back();
      stack.pop_back();
      const int i = int(q % size_t(g.nx)), j = int((q / size_t(g.nx)) % size_t(g.ny)),
                k = int(q / (size_t(g.nx) * size_t(g.ny)));
      forBox(g, i, j, k, 1, [&](int a, int b, int c) {
        const size_t r = g.index(a, b, c);
        if (mask[r] && comp[r] < 0) comp[r] = n, stack.push_back(r);
        return true;
      });
    }
    ++n;
  }
  return comp;
}

}  // namespace

std::vector<float> squaredDistanceToOutside(const VoxelGrid& g) {
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> d(g.inside.size());
  for (size_t i = 0; i < d.size(); ++i) d[i] = g.inside[i] ? inf : 0.0f;
  std::vector<int> v;
  std::vector<float> z, out;
  const size_t sx = 1, sy = size_t(g.nx), sz = size_t(g.nx) * size_t(g.ny);
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j) distance1d(&d[g.index(0, j, k)], g.nx, sx, v, z, out);
  for (int k = 0; k < g.nz; ++k)
    for (int i = 0; i < g.nx; ++i) distance1d(&d[g.index(i, 0, k)], g.ny, sy, v, z, out);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) distance1d(&d[g.index(i, j, 0)], g.nz, sz, v, z, out);
  return d;
}

std::vector<float> localThickness(const VoxelGrid& g, float cap) {
  const std::vector<float> d2 = squaredDistanceToOutside(g);
  std::vector<float> t(d2.size(), 0.0f);
  // Balls are stamped up to twice the radius that reaches the cap: a voxel at
  // the surface of a thick part (its own ball small, where the surface runs
  // diagonally to the grid) then lies in a deeper voxel's ball that reaches
  // the cap.
  const float cap_r = 0.5f * cap / g.voxel;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const size_t c = g.index(i, j, k);
        if (!g.inside[c]) continue;
        // The largest inside ball centred here: to the surface, half a voxel
        // short of the nearest outside centre (>= 1/2: a voxel is inside).
        const float full = std::sqrt(d2[c]) - 0.5f, r = std::min(full, 2.0f * cap_r);
        const float value = std::min(2.0f * full, 2.0f * cap_r);
        const int w = int(std::floor(r));
        const float r2 = r * r;
        forBox(g, i, j, k, w, [&](int a, int b, int c2) {
          const float dx = float(a - i), dy = float(b - j), dz = float(c2 - k);
          const size_t q = g.index(a, b, c2);
          if (g.inside[q] && dx * dx + dy * dy + dz * dz <= r2) t[q] = std::max(t[q], value);
          return true;
        });
      }
  for (float& x : t) x = std::min(x * g.voxel, cap);
  return t;
}

long thinRidgeVoxels(const VoxelGrid& g, float thickness) {
  const std::vector<float> d2 = squaredDistanceToOutside(g);
  long thin = 0;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const float d = d2[g.index(i, j, k)];
        if (d < 2.0f) continue;
        bool top = true;
        forBox(g, i, j, k, 1, [&](int a, int b, int c) { return top = d2[g.index(a, b, c)] <= d; });
        if (top && 2.0f * std::sqrt(d) - 1.0f <= thickness) ++thin;
      }
  return thin;
}

std::vector<uint8_t> thinVoxels(const VoxelGrid& g, float thickness) {
  std::vector<uint8_t> thin(g.inside.size(), 0);
  if (!(thickness > 0.0f)) return thin;
  // Capped at `thickness`: a voxel below it has its exact local thickness.
  const std::vector<float> t = localThickness(g, thickness);
  for (size_t i = 0; i < thin.size(); ++i) thin[i] = g.inside[i] && t[i] < thickness ? 1 : 0;
  return thin;
}

std::vector<uint8_t> shapeParts(const VoxelGrid& g, float min_length) {
  std::vector<uint8_t> part(g.inside.size(), kPartOutside);
  const std::vector<float> d2 = squaredDistanceToOutside(g);
  float most = 0.0f;
  size_t n = 0;
  for (size_t q = 0; q < d2.size(); ++q)
    if (g.inside[q]) most = std::max(most, d2[q]), ++n;
  const float r = kLumpDepthShare * std::sqrt(most), r2 = r * r;
  const int w = int(std::ceil(r));
  // The opening: within r of a voxel at least r deep.
  std::vector<uint8_t> thick(d2.size(), 0);
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const size_t q = g.index(i, j, k);
        if (!g.inside[q]) continue;
        bool near = d2[q] >= r2;
        if (!near)
          forBox(g, i, j, k, w, [&](int a, int b, int c) {
            const float dx = float(a - i), dy = float(b - j), dz = float(c - k);
            near = dx * dx + dy * dy + dz * dz <= r2 && d2[g.index(a, b, c)] >= r2;
            return !near;
          });
        thick[q] = near;
      }
  // Lumps: the opening's components of at least kLumpVolumeShare of the shape.
  int nl = 0;
  std::vector<int> lump = components(g, thick, nl);
  std::vector<size_t> size(size_t(nl), 0);
  for (int l : lump)
    if (l >= 0) ++size[size_t(l)];
  for (size_t q = 0; q < lump.size(); ++q)
    if (lump[q] >= 0 && double(size[size_t(lump[q])]) < kLumpVolumeShare * double(n)) lump[q] = -1;
  // The thin parts, and of each the lumps it touches and its contact voxels
  // (those with a lump voxel among their 26 neighbours).
  std::vector<uint8_t> thin(d2.size(), 0), contact(d2.size(), 0);
  for (size_t q = 0; q < d2.size(); ++q) thin[q] = g.inside[q] && lump[q] < 0;
  int nt = 0;
  const std::vector<int> part_of = components(g, thin, nt);
  std::vector<std::set<int>> lumps_of(static_cast<size_t>(nt)), patches_of(static_cast<size_t>(nt));
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const size_t q = g.index(i, j, k);
        if (!thin[q]) continue;
        forBox(g, i, j, k, 1, [&](int a, int b, int c) {
          const int l = lump[g.index(a, b, c)];
          if (l >= 0) contact[q] = 1, lumps_of[size_t(part_of[q])].insert(l);
          return true;
        });
      }
  // Each contact patch's centre; a thin part's length is the largest
  // distance between the centres of its patches.
  int np = 0;
  const std::vector<int> patch = components(g, contact, np);
  std::vector<double> pc(4 * size_t(np), 0.0);
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const int c = patch[g.index(i, j, k)];
        if (c < 0) continue;
        double* e = &pc[4 * size_t(c)];
        e[0] += i, e[1] += j, e[2] += k, e[3] += 1.0;
        patches_of[size_t(part_of[g.index(i, j, k)])].insert(c);
      }
  std::vector<uint8_t> is_bar(size_t(nt), 0);
  for (size_t t = 0; t < size_t(nt); ++t) {
    double longest = 0.0;
    for (int a : patches_of[t])
      for (int b : patches_of[t]) {
        const double* e = &pc[4 * size_t(a)];
        const double* f = &pc[4 * size_t(b)];
        double d2ab = 0.0;
        for (int x = 0; x < 3; ++x) d2ab += (e[x] / e[3] - f[x] / f[3]) * (e[x] / e[3] - f[x] / f[3]);
        longest = std::max(longest, std::sqrt(d2ab));
      }
    is_bar[t] = lumps_of[t].size() >= 2 && longest >= double(min_length);
  }
  for (size_t q = 0; q < d2.size(); ++q)
    if (g.inside[q]) part[q] = lump[q] >= 0 ? kPartLump : is_bar[size_t(part_of[q])] ? kPartBar : kPartLimb;
  return part;
}

long eulerCharacteristic(const VoxelGrid& g) {
  const auto in = [&g](int i, int j, int k) {
    return i >= 0 && j >= 0 && k >= 0 && i < g.nx && j < g.ny && k < g.nz && g.inside[g.index(i, j, k)];
  };
  // Each cell of the cubical complex is present when any voxel that holds it
  // is inside; the voxels that hold the cell at (i, j, k) spanning the axes in
  // `span` are (i - a, j - b, k - c) with a, b, c in {0, 1} along the axes the
  // cell does not span, 0 along those it spans.
  long chi = 0;
  for (int span = 0; span < 8; ++span) {
    const int sx = span & 1, sy = (span >> 1) & 1, sz = (span >> 2) & 1;
    const int dim = sx + sy + sz;
    long count = 0;
    for (int k = 0; k <= g.nz - sz; ++k)
      for (int j = 0; j <= g.ny - sy; ++j)
        for (int i = 0; i <= g.nx - sx; ++i) {
          bool present = false;
          for (int c = 0; c <= 1 - sz && !present; ++c)
            for (int b = 0; b <= 1 - sy && !present; ++b)
              for (int a = 0; a <= 1 - sx && !present; ++a) present = in(i - a, j - b, k - c);
          count += present;
        }
    chi += (dim % 2 == 0 ? 1 : -1) * count;
  }
  return chi;
}

int mostBranches(const VoxelGrid& g) {
  const std::vector<float> d2 = squaredDistanceToOutside(g);
  float most = 0.0f;
  for (size_t q = 0; q < d2.size(); ++q)
    if (g.inside[q]) most = std::max(most, d2[q]);
  if (!(most > 0.0f)) return 0;
  const float depth = std::sqrt(most), outer = kBranchShellDepths * depth + 1.0f, inner = outer - 2.0f;
  const float outer2 = outer * outer, inner2 = inner * inner, deep2 = 0.25f * most;
  const int w = int(std::ceil(outer)), side = 2 * w + 1;
  // Per centre, over the cube of side 2 w + 1 around it: reached, and of the
  // reached shell voxels the piece they belong to (reset after each centre).
  std::vector<uint8_t> reached(size_t(side) * size_t(side) * size_t(side), 0);
  std::vector<int> piece(reached.size(), -1);
  std::vector<int> todo, seen, shell_voxels, stack;
  int best = 0;
  for (int k = 0; k < g.nz; k += 2)
    for (int j = 0; j < g.ny; j += 2)
      for (int i = 0; i < g.nx; i += 2) {
        if (!g.inside[g.index(i, j, k)] || d2[g.index(i, j, k)] < deep2) continue;
        const auto local = [&](int a, int b, int c) {
          return (a - i + w) + side * ((b - j + w) + side * (c - k + w));
        };
        const auto in_ball = [&](int a, int b, int c) {
          const float dx = float(a - i), dy = float(b - j), dz = float(c - k);
          return dx * dx + dy * dy + dz * dz <= outer2;
        };
        const auto shell = [&](int a, int b, int c) {
          const float dx = float(a - i), dy = float(b - j), dz = float(c - k);
          return dx * dx + dy * dy + dz * dz > inner2;
        };
        const auto at = [&](int q, int& a, int& b, int& c) {
          a = q % side - w + i, b = (q / side) % side - w + j, c = q / (side * side) - w + k;
        };
        // The flood from the centre through the inside voxels of the ball.
        todo.assign(1, local(i, j, k)), seen.assign(1, todo[0]), shell_voxels.clear();
        reached[size_t(todo[0])] = 1;
        while (!todo.empty()) {
          const int q = todo.back();
          todo.pop_back();
          int a, b, c;
          at(q, a, b, c);
          if (shell(a, b, c)) shell_voxels.push_back(q);
          forBox(g, a, b, c, 1, [&](int a2, int b2, int c2) {
            if (!g.inside[g.index(a2, b2, c2)] || !in_ball(a2, b2, c2)) return true;
            const int r = local(a2, b2, c2);
            if (!reached[size_t(r)]) reached[size_t(r)] = 1, todo.push_back(r), seen.push_back(r);
            return true;
          });
        }
        // The reached shell voxels' pieces; a piece is a branch if it leaves
        // the ball (one of its voxels has an inside neighbour outside it).
        int pieces = 0, branches = 0;
        for (const int s0 : shell_voxels) {
          if (piece[size_t(s0)] >= 0) continue;
          piece[size_t(s0)] = pieces, stack.assign(1, s0);
          bool leaves = false;
          while (!stack.empty()) {
            const int q = stack.back();
            stack.pop_back();
            int a, b, c;
            at(q, a, b, c);
            forBox(g, a, b, c, 1, [&](int a2, int b2, int c2) {
              if (!g.inside[g.index(a2, b2, c2)]) return true;
              if (!in_ball(a2, b2, c2)) {
                leaves = true;
                return true;
              }
              const int r = local(a2, b2, c2);
              if (reached[size_t(r)] && piece[size_t(r)] < 0 && shell(a2, b2, c2))
                piece[size_t(r)] = pieces, stack.push_back(r);
              return true;
            });
          }
          ++pieces, branches += leaves;
        }
        best = std::max(best, branches);
        for (const int q : seen) reached[size_t(q)] = 0, piece[size_t(q)] = -1;
      }
  return best;
}

}  // namespace ff
