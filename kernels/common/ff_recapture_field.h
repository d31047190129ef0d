// ff_recapture_field.h - where the recapture aims each fluid particle: at the
// nearest unfilled control particle (the nearest of all of them while none is
// unfilled), so never outside the shape (the centre of a torus's unfilled part
// lies in its hole). Shared by the OpenMP backend
// (Controller::addForces) and the OpenCL kernels (recapture_field.cl,
// control_forces.cl), bit for bit.
//
// A coarse field over the control particles' grid (cells of radius /
// FF_CONTROL_GRID_DIVISIONS) holds, per field cell of FF_RECAPTURE_FIELD_SPAN^3
// grid cells, the sorted position of a candidate (unfilled) control particle near its
// centre: seeded from the control particles in the cell, then spread by jump
// flooding (Rong & Tan 2006: passes with steps N/2, N/4, .., 1, and one more
// of step 1), every pass reading only the previous one. A fluid particle takes
// the nearest to itself of the seeds of its field cell and the 26 around it.
// Candidates are ranked by squared distance, ties by the lower sorted
// position: a total order, so the result does not depend on the order in which
// a backend visits them.
#ifndef FF_RECAPTURE_FIELD_H
#define FF_RECAPTURE_FIELD_H
#include "ff_compat.h"
#include "ff_control.h"
#include "ff_grid.h"

/* No control particle (an empty field cell). */
#define FF_RECAPTURE_NONE 0xffffffffu

/* Grid cells per field cell and axis: field cells as wide as the control
 * radius (the grid's cells are radius / FF_CONTROL_GRID_DIVISIONS). */
#define FF_RECAPTURE_FIELD_SPAN FF_CONTROL_GRID_DIVISIONS

/* Field cells along an axis of n grid cells. */
FF_FN int ff_recapture_field_dim(int n) {
  return (n + FF_RECAPTURE_FIELD_SPAN - 1) / FF_RECAPTURE_FIELD_SPAN;
}

/* The first jump-flooding step for a field of at most m cells along an axis:
 * half the smallest power of two >= m (0 for a single cell: no pass but the
 * final one of step 1). */
FF_FN int ff_recapture_first_step(int m) {
  int p = 1;
  while (p < m) p *= 2;
  return p / 2;
}

/* Whether a control particle is unfilled: its kernel is less than half
 * filled (ff_recapture_weight > 0). */
FF_FN int ff_recapture_unfilled(float s) {
  return ff_recapture_weight(s) > 0.0f;
}

/* Whether the field may name a control particle of density scale s: an
 * unfilled one, or any while none is unfilled (`any`: the unfilled weight is
 * 0): the shape reads full, and fluid still out of reach is drawn to the
 * nearest control particle, where eq. 4-5 take in only what has room. */
FF_FN int ff_recapture_candidate(float s, int any) {
  return any || ff_recapture_unfilled(s);
}

/* Whether the field seeds from every control particle: none is unfilled
 * (the unfilled weight u = sum_i ff_recapture_weight(s_i) is 0). */
FF_FN int ff_recapture_seed_any(float u) {
  return u <= 0.0f;
}

FF_FN float ff_recapture_d2(float ax, float ay, float az, float bx, float by, float bz) {
  const float dx = bx - ax, dy = by - ay, dz = bz - az;
  return (dx * dx + dy * dy) + dz * dz;
}

/* Whether candidate k at squared distance d2 ranks before the best so far. */
FF_FN int ff_recapture_before(float d2, uint k, float best_d2, uint best) {
  return best == FF_RECAPTURE_NONE || d2 < best_d2 || (d2 == best_d2 && k < best);
}

/* Centre of field cell c along an axis: origin o, field cell size fcell. */
FF_FN float ff_recapture_cell_centre(int c, float o, float fcell) {
  return o + ((float)c + 0.5f) * fcell;
}

/* The seed of field cell (cx, cy, cz): of the candidate control particles
 * in its grid cells (ff_recapture_candidate: the unfilled ones, or all of
 * them where `any`), the one nearest its centre (FF_RECAPTURE_NONE if none).
 * start: the grid's cell ranges (n grid cells per axis, origin o, cell size
 * `cell`); sx, sy, sz, ss: the control particles in the grid's order. */
FF_FN uint ff_recapture_seed(FF_GLOBAL const uint* start, FF_GLOBAL const float* sx,
                             FF_GLOBAL const float* sy, FF_GLOBAL const float* sz, FF_GLOBAL const float* ss,
                             int any, int cx, int cy, int cz, const int n[3], const float o[3], float cell) {
  const float fcell = cell * (float)FF_RECAPTURE_FIELD_SPAN;
  const float px = ff_recapture_cell_centre(cx, o[0], fcell), py = ff_recapture_cell_centre(cy, o[1], fcell),
              pz = ff_recapture_cell_centre(cz, o[2], fcell);
  const int x0 = cx * FF_RECAPTURE_FIELD_SPAN, y0 = cy * FF_RECAPTURE_FIELD_SPAN,
            z0 = cz * FF_RECAPTURE_FIELD_SPAN;
  const int x1 = x0 + FF_RECAPTURE_FIELD_SPAN < n[0] ? x0 + FF_RECAPTURE_FIELD_SPAN : n[0];
  const int y1 = y0 + FF_RECAPTURE_FIELD_SPAN < n[1] ? y0 + FF_RECAPTURE_FIELD_SPAN : n[1];
  const int z1 = z0 + FF_RECAPTURE_FIELD_SPAN < n[2] ? z0 + FF_RECAPTURE_FIELD_SPAN : n[2];
  uint best = FF_RECAPTURE_NONE;
  float best_d2 = 0.0f;
  for (int z = z0; z < z1; ++z)
    for (int y = y0; y < y1; ++y) {
      const uint row = ff_cell_index(0, y, z, n[0], n[1]);
      const uint b = start[row + (uint)x0], e = start[row + (uint)x1];
      for (uint k = b; k < e; ++k) {
        if (!ff_recapture_candidate(ss[k], any)) continue;
        const float d2 = ff_recapture_d2(px, py, pz, sx[k], sy[k], sz[k]);
        if (ff_recapture_before(d2, k, best_d2, best)) best = k, best_d2 = d2;
      }
    }
  return best;
}

/* Of the seeds of field cell (cx, cy, cz) and of the 26 cells `step` cells
 * away from it (in a field of m cells per axis), the nearest to (px, py, pz). */
FF_FN uint ff_recapture_nearest(FF_GLOBAL const uint* seeds, FF_GLOBAL const float* sx,
                                FF_GLOBAL const float* sy, FF_GLOBAL const float* sz, float px, float py,
                                float pz, int cx, int cy, int cz, int step, const int m[3]) {
  uint best = FF_RECAPTURE_NONE;
  float best_d2 = 0.0f;
  for (int dz = -1; dz <= 1; ++dz) {
    const int z = cz + dz * step;
    if (z < 0 || z >= m[2]) continue;
    for (int dy = -1; dy <= 1; ++dy) {
      const int y = cy + dy * step;
      if (y < 0 || y >= m[1]) continue;
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = cx + dx * step;
        if (x < 0 || x >= m[0]) continue;
        const uint k = seeds[ff_cell_index(x, y, z, m[0], m[1])];
        if (k == FF_RECAPTURE_NONE) continue;
        const float d2 = ff_recapture_d2(px, py, pz, sx[k], sy[k], sz[k]);
        if (ff_recapture_before(d2, k, best_d2, best)) best = k, best_d2 = d2;
      }
    }
  }
  return best;
}

/* One jump-flooding pass for field cell (cx, cy, cz) of a field of m cells
 * per axis (origin o, cell size fcell): the nearest to its centre of its own
 * seed and those of the 26 cells `step` cells away, in the previous pass's
 * seeds. */
FF_FN uint ff_recapture_flood(FF_GLOBAL const uint* seeds, FF_GLOBAL const float* sx,
                              FF_GLOBAL const float* sy, FF_GLOBAL const float* sz, int cx, int cy, int cz,
                              int step, const int m[3], const float o[3], float fcell) {
  return ff_recapture_nearest(seeds, sx, sy, sz, ff_recapture_cell_centre(cx, o[0], fcell),
                              ff_recapture_cell_centre(cy, o[1], fcell),
                              ff_recapture_cell_centre(cz, o[2], fcell), cx, cy, cz, step, m);
}

/* The control particle (sorted position) the recapture aims the fluid
 * particle at (px, py, pz) at: the nearest to it of the seeds of its field
 * cell (clamped into the field: origin o, inverse cell size inv_fcell) and the
 * 26 around it. FF_RECAPTURE_NONE only if the field is empty. */
FF_FN uint ff_recapture_target(FF_GLOBAL const uint* seeds, FF_GLOBAL const float* sx,
                               FF_GLOBAL const float* sy, FF_GLOBAL const float* sz, float px, float py,
                               float pz, const int m[3], const float o[3], float inv_fcell) {
  return ff_recapture_nearest(seeds, sx, sy, sz, px, py, pz, ff_cell_coord(px, o[0], inv_fcell, m[0]),
                              ff_cell_coord(py, o[1], inv_fcell, m[1]),
                              ff_cell_coord(pz, o[2], inv_fcell, m[2]), 1, m);
}

/* Whether the point (px, py, pz) lies among the control particles: one of
 * them (sx, sy, sz, in the order of the grid with cell ranges `start`, origin
 * o, cell size `cell`, inverse inv_cell, n cells per axis) within `dist` of it.
 * The recapture aims at the centre of the unfilled control particles only
 * where it does (inside the shape); elsewhere (a torus's hole) at the field. */
FF_FN int ff_recapture_among(FF_GLOBAL const uint* start, FF_GLOBAL const float* sx,
                             FF_GLOBAL const float* sy, FF_GLOBAL const float* sz, float px, float py,
                             float pz, float dist, const float o[3], float cell, float inv_cell,
                             const int n[3]) {
  const float reach = ff_query_reach(dist, cell), d2max = dist * dist;
  const float p[3] = {px, py, pz};
  const int z0 = ff_cell_coord(pz - reach, o[2], inv_cell, n[2]),
            z1 = ff_cell_coord(pz + reach, o[2], inv_cell, n[2]);
  const int y0 = ff_cell_coord(py - reach, o[1], inv_cell, n[1]),
            y1 = ff_cell_coord(py + reach, o[1], inv_cell, n[1]);
  for (int z = z0; z <= z1; ++z)
    for (int y = y0; y <= y1; ++y) {
      uint b, e;
      if (!ff_row_span(start, p, p, reach, y, z, o, cell, inv_cell, n, &b, &e)) continue;
      for (uint k = b; k < e; ++k)
        if (ff_recapture_d2(px, py, pz, sx[k], sy[k], sz[k]) <= d2max) return 1;
    }
  return 0;
}

/* Where the recapture aims the fluid particle at (px, py, pz): the centre of
 * the unfilled control particles where that lies among them (at_centre, from
 * ff_recapture_among), else the control particle ff_recapture_target names.
 * Returns 0 (and leaves *aim) if there is none. */
FF_FN int ff_recapture_aim(int at_centre, ff_float3 centre, FF_GLOBAL const uint* seeds,
                           FF_GLOBAL const float* sx, FF_GLOBAL const float* sy, FF_GLOBAL const float* sz,
                           float px, float py, float pz, const int m[3], const float o[3], float inv_fcell,
                           ff_float3* aim) {
  if (at_centre) {
    *aim = centre;
    return 1;
  }
  const uint t = ff_recapture_target(seeds, sx, sy, sz, px, py, pz, m, o, inv_fcell);
  if (t == FF_RECAPTURE_NONE) return 0;
  *aim = FF_F3(sx[t], sy[t], sz[t]);
  return 1;
}

#endif /* FF_RECAPTURE_FIELD_H */
