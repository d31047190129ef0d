#include "control/recapture_field.h"

#include <algorithm>

#include "ff_recapture_field.h"
#include "parallel/parallel_grain.h"

namespace ff {

RecaptureFieldGeom recaptureFieldGeom(const int n[3], const float o[3], float cell) {
  RecaptureFieldGeom g;
  for (int d = 0; d < 3; ++d) g.m[d] = ff_recapture_field_dim(n[d]), g.o[d] = o[d];
  g.fcell = cell * float(FF_RECAPTURE_FIELD_SPAN);
  g.inv_fcell = 1.0f / g.fcell;
  return g;
}

RecaptureFloodSteps recaptureFloodSteps(const RecaptureFieldGeom& g) {
  RecaptureFloodSteps steps;
  for (int k = ff_recapture_first_step(std::max({g.m[0], g.m[1], g.m[2]})); k >= 1; k /= 2)
    steps.step[steps.count++] = k;
  steps.step[steps.count++] = 1;
  return steps;
}

void RecaptureField::build(const UniformGrid& grid, const float* sx, const float* sy, const float* sz,
                           const float* ss, bool any) {
  const int n[3] = {grid.nx(), grid.ny(), grid.nz()};
  const float o[3] = {grid.originX(), grid.originY(), grid.originZ()};
  const float cell = grid.cellSize();
  geom_ = recaptureFieldGeom(n, o, cell);
  const RecaptureFieldGeom& g = geom_;
  const long cells = long(g.cells());
  seeds_.resize(size_t(cells)), scratch_.resize(size_t(cells));
  const uint32_t* start = grid.cellStart().data();
  const int mx = g.m[0], my = g.m[1];
#pragma omp parallel for schedule(static) if (cells > kParallelLightLoop)
  for (long c = 0; c < cells; ++c)
    seeds_[size_t(c)] = ff_recapture_seed(start, sx, sy, sz, ss, any ? 1 : 0, int(c % mx), int(c / mx % my),
                                          int(c / (long(mx) * my)), n, o, cell);
  for (int step : recaptureFloodSteps(g)) {
#pragma omp parallel for schedule(static) if (cells > kParallelLightLoop / 8)
    for (long c = 0; c < cells; ++c)
      scratch_[size_t(c)] = ff_recapture_flood(seeds_.data(), sx, sy, sz, int(c % mx), int(c / mx % my),
                                               int(c / (long(mx) * my)), step, g.m, g.o, g.fcell);
    seeds_.swap(scratch_);
  }
}

}  // namespace ff
