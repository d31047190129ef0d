// grid.cl - phase "grid": the uniform neighbour grid by counting sort
// (cell count, prefix scan, scatter, rank, reorder), the same
// grid as src/grid/uniform_grid.cpp builds. The scatter is made stable by
// ranking each point among the points of its cell by input index, so the
// sorted order (and every neighbour sum after it) does not depend on the
// order in which atomics happen to run.
#pragma OPENCL FP_CONTRACT OFF
#include "ff_grid.h"

// Cell of every point, and the number of points per cell (counts zeroed before).
__kernel void grid_count(__global const float* x, __global const float* y, __global const float* z, uint n,
                         float4 geo /* origin xyz, 1 / cell */, int4 dims, __global uint* cell_of,
                         __global uint* counts) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const int cx = ff_cell_coord(x[i], geo.x, geo.w, dims.x);
  const int cy = ff_cell_coord(y[i], geo.y, geo.w, dims.y);
  const int cz = ff_cell_coord(z[i], geo.z, geo.w, dims.z);
  const uint c = ff_cell_index(cx, cy, cz, dims.x, dims.y);
  cell_of[i] = c;
  atomic_inc(&counts[c]);
}

// Exclusive prefix sum of one block of get_local_size(0) values in place;
// the block's total goes to block_sums. Local size must be a power of two.
__kernel void scan_block(__global uint* data, uint n, __global uint* block_sums, __local uint* tmp) {
  const uint lid = get_local_id(0), ls = get_local_size(0), i = get_global_id(0);
  const uint v = i < n ? data[i] : 0u;
  tmp[lid] = v;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint off = 1; off < ls; off <<= 1) {  // Hillis-Steele inclusive scan
    const uint add = lid >= off ? tmp[lid - off] : 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    tmp[lid] += add;
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (i < n) data[i] = tmp[lid] - v;
  if (lid == ls - 1) block_sums[get_group_id(0)] = tmp[lid];
}

// The same for CPU devices, where barriers are costly: each work-item scans
// `chunk` consecutive values in place, one after the other (exclusive), and
// writes their total to block_sums[its index].
__kernel void scan_chunk(__global uint* data, uint n, uint chunk, __global uint* block_sums) {
  const uint g = get_global_id(0), b = g * chunk;
  if (b >= n) return;
  const uint e = n - b < chunk ? n : b + chunk;
  uint total = 0u;
  for (uint i = b; i < e; ++i) {
    const uint v = data[i];
    data[i] = total;
    total += v;
  }
  block_sums[g] = total;
}

// Adds the scanned totals of scan_chunk to the values of their chunk.
__kernel void scan_chunk_add(__global uint* data, uint n, uint chunk, __global const uint* block_offsets) {
  const uint g = get_global_id(0), b = g * chunk;
  if (b >= n) return;
  const uint e = n - b < chunk ? n : b + chunk, add = block_offsets[g];
  for (uint i = b; i < e; ++i) data[i] += add;
}

// Adds the scanned block totals to every value of their block.
__kernel void scan_add(__global uint* data, uint n, __global const uint* block_offsets) {
  const uint i = get_global_id(0);
  if (i < n) data[i] += block_offsets[get_group_id(0)];
}

// Puts every point into a free slot of its cell's range (in any order).
__kernel void grid_scatter(__global const uint* cell_of, uint n, __global const uint* start,
                           __global uint* fill, __global uint* slots) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const uint c = cell_of[i];
  slots[start[c] + atomic_inc(&fill[c])] = i;
}

// Stable order: a point's place in its cell is the number of points of the
// same cell with a smaller input index.
__kernel void grid_rank(__global const uint* cell_of, uint n, __global const uint* start,
                        __global const uint* slots, __global uint* order) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const uint c = cell_of[i], b = start[c], e = start[c + 1];
  uint rank = 0;
  for (uint s = b; s < e; ++s) rank += slots[s] < i ? 1u : 0u;
  order[b + rank] = i;
}

// out[k] = in[order[k]] for every fluid array.
__kernel void grid_reorder_fluid(__global const uint* order, uint n, __global const float* x,
                                 __global const float* y, __global const float* z, __global const float* vx,
                                 __global const float* vy, __global const float* vz, __global const uint* id,
                                 __global float* ox, __global float* oy, __global float* oz,
                                 __global float* ovx, __global float* ovy, __global float* ovz,
                                 __global uint* oid) {
  const uint k = get_global_id(0);
  if (k >= n) return;
  const uint i = order[k];
  ox[k] = x[i], oy[k] = y[i], oz[k] = z[i];
  ovx[k] = vx[i], ovy[k] = vy[i], ovz[k] = vz[i];
  oid[k] = id[i];
}
