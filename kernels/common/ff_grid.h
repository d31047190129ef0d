// ff_grid.h - the uniform neighbour grid's cell arithmetic, as in
// src/grid/uniform_grid.h, for the OpenCL kernels (and C++ tests that check it
// against UniformGrid). Cell (ix, iy, iz) has index ix + nx * (iy + ny * iz);
// start[c] .. start[c+1] are the sorted positions of the points in cell c.
#ifndef FF_GRID_H
#define FF_GRID_H
#include "ff_compat.h"

#ifdef __OPENCL_VERSION__
#define FF_GLOBAL __global
#else
#define FF_GLOBAL
#endif

/* Cell coordinate of v along one axis: origin o, 1 / cell size inv_cell, n cells. */
FF_FN int ff_cell_coord(float v, float o, float inv_cell, int n) {
  int c = (int)((v - o) * inv_cell);
  return c < 0 ? 0 : (c >= n ? n - 1 : c);
}

FF_FN uint ff_cell_index(int ix, int iy, int iz, int nx, int ny) {
  return (uint)ix + (uint)nx * ((uint)iy + (uint)ny * (uint)iz);
}

/* The 9 contiguous sorted ranges [begin[r], end[r]) that make up the 27 cells
 * around cell (cx, cy, cz): z-major, then y, each a row of up to 3 cells along x
 * (UniformGrid::forEachRange). Rows outside the grid are empty ranges. */
FF_FN void ff_grid_ranges(FF_GLOBAL const uint* start, int cx, int cy, int cz, int nx, int ny, int nz,
                          uint* begin, uint* end) {
  int x0 = cx > 0 ? cx - 1 : 0, x1 = cx + 1 < nx ? cx + 1 : nx - 1;
  int r = 0;
  for (int z = cz - 1; z <= cz + 1; ++z) {
    for (int y = cy - 1; y <= cy + 1; ++y, ++r) {
      begin[r] = 0, end[r] = 0;
      if (z < 0 || z >= nz || y < 0 || y >= ny) continue;
      uint row = (uint)nx * ((uint)y + (uint)ny * (uint)z);
      begin[r] = start[row + (uint)x0];
      end[r] = start[row + (uint)x1 + 1u];
    }
  }
}

/* ---------------------------------------------------------------------------
 * Pruned neighbour queries: the cells that points within `reach` of a query
 * box [lo, hi] (a point: lo = hi) can lie in, for any cell size. Rows of cells
 * along x (contiguous in the sorted order) are visited z-major, then y; a row
 * whose y-z slab is farther than `reach` from the box is skipped, and a row is
 * cut to the chord of the sphere-swept box. The sorted positions visited
 * ascend, so a sum over the points within reach, in visiting order, is the
 * same however much is pruned. `reach` must exceed the query radius by a
 * margin (ff_query_reach) that covers the rounding of the cell assignment.
 * ------------------------------------------------------------------------- */

/* The radius to prune with: `radius` plus a thousandth of a cell. */
FF_FN float ff_query_reach(float radius, float cell) {
  return radius + 1.0e-3f * cell;
}

/* Distance along one axis from [lo, hi] to the slab of cell c (of n cells,
 * origin o): 0 where they overlap. The outermost cells reach to infinity,
 * since the cell assignment clamps points outside the grid into them. */
FF_FN float ff_slab_gap(float lo, float hi, int c, int n, float o, float cell) {
  const float a = c <= 0 ? -1.0e30f : o + (float)c * cell;
  const float b = c >= n - 1 ? 1.0e30f : o + (float)(c + 1) * cell;
  const float below = a - hi, above = lo - b; /* at most one is positive */
  return below > 0.0f ? below : (above > 0.0f ? above : 0.0f);
}

/* The cells x0..x1 of a row at distance gap_yz^2 = g2 (in y and z) from the
 * box, that can hold points within reach of [lo_x, hi_x]. Returns 0 (and no
 * cells) when the row is out of reach. */
FF_FN int ff_row_cells(float lo_x, float hi_x, float g2, float reach, float o, float inv_cell, int n, int* x0,
                       int* x1) {
  const float r2 = reach * reach;
  if (g2 > r2) return 0;
  const float chord = FF_SQRT(r2 - g2);
  *x0 = ff_cell_coord(lo_x - chord, o, inv_cell, n);
  *x1 = ff_cell_coord(hi_x + chord, o, inv_cell, n);
  return 1;
}

/* The sorted range [*b, *e) of row (y, z) that can hold points within reach
 * of the box [lo, hi] (as UniformGrid::rangesNear visits it), for a grid with
 * origin o, cell size `cell` (inverse inv_cell) and n cells per axis. Returns
 * 0 (and an empty range) when the row is out of reach. */
FF_FN int ff_row_span(FF_GLOBAL const uint* start, const float lo[3], const float hi[3], float reach, int y,
                      int z, const float o[3], float cell, float inv_cell, const int n[3], uint* b, uint* e) {
  const float gy = ff_slab_gap(lo[1], hi[1], y, n[1], o[1], cell);
  const float gz = ff_slab_gap(lo[2], hi[2], z, n[2], o[2], cell);
  int x0, x1;
  *b = 0, *e = 0;
  if (!ff_row_cells(lo[0], hi[0], gy * gy + gz * gz, reach, o[0], inv_cell, n[0], &x0, &x1)) return 0;
  const uint row = ff_cell_index(0, y, z, n[0], n[1]);
  *b = start[row + (uint)x0];
  *e = start[row + (uint)x1 + 1u];
  return 1;
}

#endif /* FF_GRID_H */
