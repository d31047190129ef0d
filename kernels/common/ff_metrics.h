// ff_metrics.h - where a fluid particle lies relative to the target, for the
// metrics `iou`, `captured` and `stray` (docs/METRICS.md), shared by the
// OpenMP backend (src/metrics/fluid_shares.cpp) and kernels/metrics_shares.cl.
#ifndef FF_METRICS_H
#define FF_METRICS_H
#include "ff_compat.h"
#include "ff_rotation.h"

/* A voxel index of the target's grid (it may lie outside the grid). */
typedef struct {
  int i, j, k;
} ff_voxel;

/* One coordinate of a point in voxels of the grid (origin o, edge voxel),
 * clamped far outside any grid so that the conversion to int is defined. */
FF_FN int ff_voxel_coord(float x, float o, float voxel) {
  return (int)ff_clampf(FF_FLOOR((x - o) / voxel), -1.0e8f, 1.0e8f);
}

/* The voxel holding world point p when the target sits at the rigid frame
 * x_world = R (x_rest - rest_c) + c (r: the columns of R): x_rest = R^T (p - c)
 * + rest_c. The products are written out so that both compilers round them
 * alike. */
FF_FN ff_voxel ff_target_voxel_of(ff_mat3 r, ff_float3 c, ff_float3 rest_c, ff_float3 o, float voxel,
                                  ff_float3 p) {
  const ff_float3 d = p - c;
  const float xr = ((r.c0.x * d.x + r.c0.y * d.y) + r.c0.z * d.z) + rest_c.x;
  const float yr = ((r.c1.x * d.x + r.c1.y * d.y) + r.c1.z * d.z) + rest_c.y;
  const float zr = ((r.c2.x * d.x + r.c2.y * d.y) + r.c2.z * d.z) + rest_c.z;
  ff_voxel v;
  v.i = ff_voxel_coord(xr, o.x, voxel);
  v.j = ff_voxel_coord(yr, o.y, voxel);
  v.k = ff_voxel_coord(zr, o.z, voxel);
  return v;
}

/* The index of voxel v in a grid of nx x ny x nz (x fastest), or -1 outside it. */
FF_FN int ff_voxel_index(ff_voxel v, int nx, int ny, int nz) {
  const int in = v.i >= 0 && v.j >= 0 && v.k >= 0 && v.i < nx && v.j < ny && v.k < nz;
  return in ? v.i + nx * (v.j + ny * v.k) : -1;
}

/* 1 if voxel v lies in the grid padded by `pad` voxels on every side: the
 * voxels whose fluid the iou measures by its density. */
FF_FN int ff_voxel_in_padded(ff_voxel v, int nx, int ny, int nz, int pad) {
  return v.i >= -pad && v.j >= -pad && v.k >= -pad && v.i < nx + pad && v.j < ny + pad && v.k < nz + pad;
}

#endif /* FF_METRICS_H */
