// device_grid.h - the uniform neighbour grid on the device, the same grid as
// src/grid/uniform_grid.h builds on the host: over the container's box (known
// on the host, so nothing is read back) plus one cell of padding, counting
// sort by cell (atomic counts, block prefix scan, scatter), made stable by
// ranking the points of a cell by input index.
#pragma once
#include <CL/opencl.hpp>
#include <cstdint>
#include <deque>
#include <vector>

#include "host/cl_kernel.h"

namespace ff {

// Dimensions and origin; cell index = ix + nx * (iy + ny * iz).
struct GridGeom {
  float ox = 0, oy = 0, oz = 0, cell = 1, inv_cell = 1;
  int nx = 1, ny = 1, nz = 1;
  size_t cells() const { return size_t(nx) * size_t(ny) * size_t(nz); }
  cl_float4 geo() const { return f4(ox, oy, oz, inv_cell); }
  cl_int4 dims() const { return i4(nx, ny, nz, 0); }
};

// UniformGrid::build's geometry for points with bounding box [lo, hi]: one
// cell of padding on each side, the cell size raised by 1.25x while the grid
// would need more than max_cells cells. (Same float operations, same result.)
GridGeom gridGeometry(const float lo[3], const float hi[3], float cell, size_t max_cells = size_t(1) << 24);

// One grid's device arrays. After a build, the points of cell c are
// order[start[c] .. start[c+1]) (positions in the input arrays).
struct DeviceGrid {
  GridGeom geom;
  size_t n = 0;
  DeviceBuffer start;  // uint, cells + 1
  DeviceBuffer order;  // uint, n
  size_t memoryBytes() const { return start.capacity() + order.capacity(); }
};

class GridBuilder {
 public:
  GridBuilder(ClContext& cl, const cl::Program& program);

  // Builds `g` over the n points with cell size `cell` over the box [lo, hi],
  // which holds every point (at most gridCellCap(n) cells).
  void build(DeviceGrid& g, const cl::Buffer& x, const cl::Buffer& y, const cl::Buffer& z, size_t n,
             float cell, const float lo[3], const float hi[3]);
  // The prefix scan as serial chunks per work-item (CPU devices, the default
  // there) or as work-group scans (GPUs). Either gives the same grid.
  void setChunkedScan(bool on) { chunked_scan_ = on; }
  // Bytes of the build's scratch (shared by every grid) and the scan's block sums.
  size_t memoryBytes() const {
    size_t b = cell_of_.capacity() + slots_.capacity() + fill_.capacity();
    for (const DeviceBuffer& s : scan_sums_) b += s.capacity();
    return b;
  }

 private:
  void scan(cl::Buffer data, size_t m, size_t level);
  ClContext& cl_;
  ClKernel count_, scan_block_, scan_add_, scatter_, rank_;
  ClKernel scan_chunk_, scan_chunk_add_;  // the scan on CPU devices: serial chunks, no barriers
  bool chunked_scan_ = false;
  size_t scan_local_ = 1;
  DeviceBuffer cell_of_, slots_, fill_;  // build scratch: cell of each point, scatter slots, per-cell fill
  std::deque<DeviceBuffer> scan_sums_;   // one per level (a deque keeps references valid as it grows)
};

}  // namespace ff
