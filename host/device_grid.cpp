#include "host/device_grid.h"

#include <algorithm>
#include <cmath>

#include "grid/uniform_grid.h"

namespace ff {

GridGeom gridGeometry(const float lo[3], const float hi[3], float cell, size_t max_cells) {
  GridGeom g;
  g.cell = cell;
  auto dims = [&](float c, int d) { return int(std::floor((hi[d] - lo[d]) / c)) + 3; };
  while (true) {
    g.nx = dims(g.cell, 0), g.ny = dims(g.cell, 1), g.nz = dims(g.cell, 2);
    if (size_t(g.nx) * g.ny * g.nz <= max_cells) break;
    g.cell *= 1.25f;
  }
  g.inv_cell = 1.0f / g.cell;
  g.ox = lo[0] - g.cell, g.oy = lo[1] - g.cell, g.oz = lo[2] - g.cell;
  return g;
}

GridBuilder::GridBuilder(ClContext& cl, const cl::Program& program) : cl_(cl) {
  count_ = makeKernel(program, "grid_count", cl);
  scan_block_ = makeKernel(program, "scan_block", cl, 256, sizeof(cl_uint));
  scan_add_ = makeKernel(program, "scan_add", cl);
  scatter_ = makeKernel(program, "grid_scatter", cl);
  rank_ = makeKernel(program, "grid_rank", cl);
  scan_chunk_ = makeKernel(program, "scan_chunk", cl);
  scan_chunk_add_ = makeKernel(program, "scan_chunk_add", cl);
  scan_local_ = std::min(scan_block_.pow2_local, scan_add_.pow2_local);
  chunked_scan_ = (cl.info().type & CL_DEVICE_TYPE_CPU) != 0;
}

// Values per work-item of the CPU devices' scan.
constexpr size_t kScanChunk = 256;

void GridBuilder::scan(cl::Buffer data, size_t m, size_t level) {
  if (scan_sums_.size() <= level) scan_sums_.resize(level + 1);
  DeviceBuffer& sums = scan_sums_[level];
  if (chunked_scan_) {
    const size_t chunks = (m + kScanChunk - 1) / kScanChunk;
    sums.ensure(cl_.context(), chunks * sizeof(cl_uint));
    launch(cl_.queue(), scan_chunk_, chunks, data, cl_uint(m), cl_uint(kScanChunk), sums.get());
    if (chunks > 1) {
      scan(sums.get(), chunks, level + 1);
      launch(cl_.queue(), scan_chunk_add_, chunks, data, cl_uint(m), cl_uint(kScanChunk), sums.get());
    }
    return;
  }
  const size_t local = scan_local_, blocks = (m + local - 1) / local;
  sums.ensure(cl_.context(), blocks * sizeof(cl_uint));
  launchGroups(cl_.queue(), scan_block_, blocks, local, data, cl_uint(m), sums.get(),
               cl::Local(local * sizeof(cl_uint)));
  if (blocks > 1) {
    scan(sums.get(), blocks, level + 1);
    launchGroups(cl_.queue(), scan_add_, blocks, local, data, cl_uint(m), sums.get());
  }
}

void GridBuilder::build(DeviceGrid& g, const cl::Buffer& x, const cl::Buffer& y, const cl::Buffer& z,
                        size_t n, float cell, const float lo[3], const float hi[3]) {
  g.geom = gridGeometry(lo, hi, cell, gridCellCap(n));
  g.n = n;
  const size_t cells = g.geom.cells();
  const cl::Context& ctx = cl_.context();
  cl::CommandQueue& q = cl_.queue();
  g.start.ensure(ctx, (cells + 1) * sizeof(cl_uint));
  fill_.ensure(ctx, cells * sizeof(cl_uint));
  for (DeviceBuffer* b : {&g.order, &cell_of_, &slots_}) b->ensure(ctx, n * sizeof(cl_uint));
  fillBuffer(q, g.start, cl_uint(0), cells + 1);
  fillBuffer(q, fill_, cl_uint(0), cells);
  launch(q, count_, n, x, y, z, cl_uint(n), g.geom.geo(), g.geom.dims(), cell_of_.get(), g.start.get());
  scan(g.start.get(), cells + 1, 0);
  launch(q, scatter_, n, cell_of_.get(), cl_uint(n), g.start.get(), fill_.get(), slots_.get());
  launch(q, rank_, n, cell_of_.get(), cl_uint(n), g.start.get(), slots_.get(), g.order.get());
}

}  // namespace ff
