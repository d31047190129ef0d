// recapture_field.cl - the recapture's field of targets (ff_recapture_field.h):
// one work-item per field cell, seeded from the control particles in the
// control grid's order, then flooded one pass per launch (host: the steps of
// recaptureFloodSteps). Mirrors RecaptureField::build in src/control/recapture_field.cpp.
#pragma OPENCL FP_CONTRACT OFF
#include "ff_recapture_field.h"

// Field cell c's coordinates in a field of m cells per axis; 0 if c is past its end.
inline int recapture_field_cell(uint c, int4 m, int* cx, int* cy, int* cz) {
  if (c >= (uint)m.x * (uint)m.y * (uint)m.z) return 0;
  *cx = (int)(c % (uint)m.x), *cy = (int)(c / (uint)m.x % (uint)m.y),
  *cz = (int)(c / ((uint)m.x * (uint)m.y));
  return 1;
}

// grid: the control grid's origin (xyz) and cell size (w); n: its cells per
// axis; m: the field's cells per axis.
__kernel void recapture_seed(__global const uint* start, __global const float* sx, __global const float* sy,
                             __global const float* sz, __global const float* ss, float4 grid, int4 n, int4 m,
                             __global uint* seeds) {
  const uint c = get_global_id(0);
  int cx, cy, cz;
  if (!recapture_field_cell(c, m, &cx, &cy, &cz)) return;
  const int n3[3] = {n.x, n.y, n.z};
  const float o3[3] = {grid.x, grid.y, grid.z};
  seeds[c] = ff_recapture_seed(start, sx, sy, sz, ss, cx, cy, cz, n3, o3, grid.w);
}

// field: the field's origin (xyz) and cell size (w).
__kernel void recapture_flood(__global const uint* seeds, __global const float* sx, __global const float* sy,
                              __global const float* sz, int step, float4 field, int4 m, __global uint* out) {
  const uint c = get_global_id(0);
  int cx, cy, cz;
  if (!recapture_field_cell(c, m, &cx, &cy, &cz)) return;
  const int m3[3] = {m.x, m.y, m.z};
  const float o3[3] = {field.x, field.y, field.z};
  out[c] = ff_recapture_flood(seeds, sx, sy, sz, cx, cy, cz, step, m3, o3, field.w);
}
