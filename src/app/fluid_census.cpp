#include "app/fluid_census.h"

#include <cmath>

namespace ff::app {

FluidCensus countLostFluid(const FluidState& f, const ContainerDesc& c) {
  FluidCensus n;
  for (size_t i = 0; i < f.size(); ++i) {
    const float v[6] = {f.x[i], f.y[i], f.z[i], f.vx[i], f.vy[i], f.vz[i]};
    bool finite = true;
    for (float x : v) finite = finite && std::isfinite(x);
    if (!finite) {
      ++n.nonfinite;
      continue;
    }
    for (int d = 0; d < 3; ++d)
      if (v[d] < c.min[d] || v[d] > c.max[d]) {
        ++n.outside;
        break;
      }
  }
  return n;
}

}  // namespace ff::app
