// uniform_grid.h - neighbour search on a uniform grid, rebuilt by counting sort.
//
// Cell (ix, iy, iz) has linear index ix + nx * (iy + ny * iz): the cells of a
// row along x are contiguous in the sorted order, so a neighbour query visits
// a few contiguous ranges (rows), pruned to the sphere around the query
// (ff_grid.h). With cells at least `cell` wide, every point within `cell` of a
// point lies in the 27 surrounding cells (forEachRange).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "ff_grid.h"

namespace ff {

// The most cells a grid over the container gets for n points: 8 per point,
// at least 2^16. A container much larger than its fluid then costs memory in
// proportion to the particles (the cells grow instead). Both backends use it.
inline size_t gridCellCap(size_t n) {
  return n * 8 > (size_t(1) << 16) ? n * 8 : (size_t(1) << 16);
}

class UniformGrid {
 public:
  // Builds the grid over the box [lo, hi], which must hold every point (the
  // container): the geometry then depends on the box only, not on where the
  // points are. `order` receives the permutation that sorts the points by cell
  // (stable: equal cells keep their input order). The grid is enlarged by one
  // cell on each side, and the cell size is raised if the box would need more
  // than `max_cells` cells.
  void build(size_t n, const float* x, const float* y, const float* z, float cell, const float lo[3],
             const float hi[3], size_t max_cells = size_t(1) << 24);
  // The same over the bounding box of the n points.
  void build(size_t n, const float* x, const float* y, const float* z, float cell,
             size_t max_cells = size_t(1) << 24);

  // After build: points of cell c (in sorted order) are order()[start[c] .. start[c+1]).
  const std::vector<uint32_t>& order() const { return order_; }
  const std::vector<uint32_t>& cellStart() const { return start_; }
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int nz() const { return nz_; }
  float cellSize() const { return cell_; }
  float invCellSize() const { return inv_cell_; }
  float originX() const { return ox_; }
  float originY() const { return oy_; }
  float originZ() const { return oz_; }

  int cellCoord(float v, float o, int n) const { return ff_cell_coord(v, o, inv_cell_, n); }

  // Calls f(begin, end) for each of the 9 contiguous sorted ranges that make up
  // the 27 cells around (px, py, pz). Indices are positions in sorted order.
  template <class F>
  void forEachRange(float px, float py, float pz, F&& f) const {
    int cx = cellCoord(px, ox_, nx_), cy = cellCoord(py, oy_, ny_), cz = cellCoord(pz, oz_, nz_);
    int x0 = cx > 0 ? cx - 1 : 0, x1 = cx + 1 < nx_ ? cx + 1 : nx_ - 1;
    for (int z = cz - 1; z <= cz + 1; ++z) {
      if (z < 0 || z >= nz_) continue;
      for (int y = cy - 1; y <= cy + 1; ++y) {
        if (y < 0 || y >= ny_) continue;
        size_t row = ff_cell_index(0, y, z, nx_, ny_);
        uint32_t b = start_[row + x0], e = start_[row + x1 + 1];
        if (b < e) f(b, e);
      }
    }
  }

  // Replaces `out` with the non-empty sorted ranges [out[2k], out[2k+1]) that
  // can hold points within `radius` of the box [lo, hi] (a point: lo = hi),
  // any cell size: ascending, pruned to the sphere-swept box (ff_row_cells).
  void rangesNear(const float lo[3], const float hi[3], float radius, std::vector<uint32_t>& out) const;

  // Replaces `out` with groups of up to `width` consecutive sorted positions
  // that lie in one row of cells (so they are close together), as ranges
  // [out[2k], out[2k+1]), ascending and covering all points.
  void rowGroups(uint32_t width, std::vector<uint32_t>& out) const;

  // Bytes held (capacity of every array).
  size_t memoryBytes() const;

 private:
  void sort(size_t n, const float* x, const float* y, const float* z);
  float ox_ = 0, oy_ = 0, oz_ = 0, cell_ = 1, inv_cell_ = 1;
  int nx_ = 1, ny_ = 1, nz_ = 1;
  std::vector<uint32_t> start_;  // size ncells + 1
  std::vector<uint32_t> order_;
  std::vector<uint32_t> cell_of_;
};

// Applies a permutation: out[k] = in[order[k]] for every array, in place.
void permute(std::vector<float>& a, const std::vector<uint32_t>& order, std::vector<float>& scratch);
void permute(std::vector<uint32_t>& a, const std::vector<uint32_t>& order, std::vector<uint32_t>& scratch);

}  // namespace ff
