/* ff_lanes.h - (OpenCL only) 8 particles per work-item, as the OpenMP
 * backend's 8-lane loops (src/parallel/simd8.h): work-item g holds the sorted
 * positions 8g .. 8g+7 as the lanes of float8 values and walks the neighbours
 * within reach of their bounding box (ff_row_span) one at a time, in
 * ascending order. Each lane adds its own terms in that order; a neighbour out
 * of a lane's reach adds an exact zero, which leaves a float sum unchanged, so
 * every lane's sums are those of the one-particle-per-work-item kernels bit for
 * bit. Buffers read 8 at a time hold a multiple of 8 floats (padded8 on the host). */
#ifndef FF_LANES_H
#define FF_LANES_H
#ifdef __OPENCL_VERSION__

/* Lanes past the last particle sit this far away: out of every neighbour's reach. */
#define FF_LANE_FAR 1.0e18f

/* The lanes that hold particles (i0 + l < n) as -1, the rest 0. */
inline int8 ff_lane_valid(uint i0, uint n) {
  return ((int8)(0, 1, 2, 3, 4, 5, 6, 7) + (int)i0) < (int)n;
}

/* a[i0 .. i0+7], with `fill` in the lanes that hold no particle. */
inline float8 ff_load_lanes(__global const float* a, uint i0, int8 valid, float fill) {
  return select((float8)(fill), vload8(0, a + i0), valid);
}

/* Smallest and largest of the lanes that hold particles (lane 0 always does). */
inline float ff_lanes_min(float8 v, int8 valid) {
  v = select((float8)(v.s0), v, valid);
  float4 a = fmin(v.lo, v.hi);
  float2 b = fmin(a.lo, a.hi);
  return fmin(b.x, b.y);
}
inline float ff_lanes_max(float8 v, int8 valid) {
  v = select((float8)(v.s0), v, valid);
  float4 a = fmax(v.lo, v.hi);
  float2 b = fmax(a.lo, a.hi);
  return fmax(b.x, b.y);
}

/* The grid rows an 8-lane neighbour query visits: the lanes' bounding box,
   grown by `reach`, as z and y cell ranges (ff_row_span prunes x per row). */
typedef struct {
  float lo[3], hi[3], o[3];
  int nn[3];
  int z0, z1, y0, y1;
} FfLanesRows;
inline FfLanesRows ff_lanes_rows(float8 x, float8 y, float8 z, int8 valid, float4 geo, int4 dims,
                                 float reach) {
  FfLanesRows q;
  q.lo[0] = ff_lanes_min(x, valid), q.lo[1] = ff_lanes_min(y, valid), q.lo[2] = ff_lanes_min(z, valid);
  q.hi[0] = ff_lanes_max(x, valid), q.hi[1] = ff_lanes_max(y, valid), q.hi[2] = ff_lanes_max(z, valid);
  q.o[0] = geo.x, q.o[1] = geo.y, q.o[2] = geo.z;
  q.nn[0] = dims.x, q.nn[1] = dims.y, q.nn[2] = dims.z;
  q.z0 = ff_cell_coord(q.lo[2] - reach, q.o[2], geo.w, q.nn[2]);
  q.z1 = ff_cell_coord(q.hi[2] + reach, q.o[2], geo.w, q.nn[2]);
  q.y0 = ff_cell_coord(q.lo[1] - reach, q.o[1], geo.w, q.nn[1]);
  q.y1 = ff_cell_coord(q.hi[1] + reach, q.o[1], geo.w, q.nn[1]);
  return q;
}

#endif
#endif /* FF_LANES_H */
