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

#endif
#endif /* FF_LANES_H */
