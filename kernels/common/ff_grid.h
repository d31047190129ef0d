// ff_grid.h - the uniform neighbour grid's cell arithmetic, as in
// src/cpu/uniform_grid.h, for the OpenCL kernels (and C++ tests that check it
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

#endif /* FF_GRID_H */
