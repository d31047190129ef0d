// recapture_field.cl - the recapture's field of targets (ff_recapture_field.h):
// one work-item per field cell, seeded from the control particles in the
// control grid's order, then flooded one pass per launch (host: the steps of
// recaptureFloodSteps). Mirrors RecaptureField::build in src/control/recapture_field.cpp.
// Both kernels do nothing while the forces will not read the field: rcentre
// (control_recapture_centre in control_forces.cl) says the recapture is off
// (rcentre[5] == 0) or aims at its centre (rcentre[4] != 0), as the OpenMP
// backend then skips RecaptureField::build. rcentre[6] != 0: seed from every
// control particle (none is unfilled).
#pragma OPENCL FP_CONTRACT OFF
#include "ff_recapture_field.h"

// Field cell c of a field of m cells per axis, and a grid's (or the field's)
// cells per axis n and origin g.xyz as arrays. 0 if c is past the field's end
// or the field is unused.
inline int recapture_field_cell(uint c, int4 m, __global const float* rcentre, int4 n, float4 g, int cc[3],
                                int n3[3], float o3[3]) {
  if (c >= (uint)m.x * (uint)m.y * (uint)m.z || rcentre[5] == 0.0f || rcentre[4] != 0.0f) return 0;
  cc[0] = (int)(c % (uint)m.x), cc[1] = (int)(c / (uint)m.x % (uint)m.y),
  cc[2] = (int)(c / ((uint)m.x * (uint)m.y));
  n3[0] = n.x, n3[1] = n.y, n3[2] = n.z, o3[0] = g.x, o3[1] = g.y, o3[2] = g.z;
  return 1;
}

// grid: the control grid's origin (xyz) and cell size (w); n: its cells per
// axis; m: the field's cells per axis.
__kernel void recapture_seed(__global const uint* start, __global const float* sx, __global const float* sy,
                             __global const float* sz, __global const float* ss, float4 grid, int4 n, int4 m,
                             __global const float* rcentre, __global uint* seeds) {
  int cc[3], n3[3];
  float o3[3];
  const uint c = get_global_id(0);
  if (recapture_field_cell(c, m, rcentre, n, grid, cc, n3, o3))
    seeds[c] =
        ff_recapture_seed(start, sx, sy, sz, ss, rcentre[6] != 0.0f, cc[0], cc[1], cc[2], n3, o3, grid.w);
}

// field: the field's origin (xyz) and cell size (w).
__kernel void recapture_flood(__global const uint* seeds, __global const float* sx, __global const float* sy,
                              __global const float* sz, int step, float4 field, int4 m,
                              __global const float* rcentre, __global uint* out) {
  int cc[3], m3[3];
  float o3[3];
  const uint c = get_global_id(0);
  if (recapture_field_cell(c, m, rcentre, m, field, cc, m3, o3))
    out[c] = ff_recapture_flood(seeds, sx, sy, sz, cc[0], cc[1], cc[2], step, m3, o3, field.w);
}
