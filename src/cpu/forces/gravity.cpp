// gravity.cpp - the gravity plug-in of the OpenMP backend (params.fluid.gravity).
#include <cmath>
#include <memory>

#include "cpu/forces/cpu_force.h"
#include "ff_sph.h"
#include "parallel/parallel_grain.h"

namespace ff {

namespace {

class CpuGravity : public CpuForce {
 public:
  const char* name() const override { return "gravity"; }
  bool apply(CpuForceContext& c, float) override {
    CpuFluid& f = c.fluid;
    const long n = long(f.size());
    const float* g = c.params.fluid.gravity;
    int bad = 0;
#pragma omp parallel for schedule(static) reduction(| : bad) if (n > kParallelLightLoop)
    for (long i = 0; i < n; ++i) {
      float a[3] = {f.ax[i], f.ay[i], f.az[i]};
      ff_add_gravity_accel(g, a);
      f.ax[i] = a[0], f.ay[i] = a[1], f.az[i] = a[2];
      bad |= std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]) ? 0 : 1;
    }
    return !bad;
  }
};

}  // namespace

std::unique_ptr<CpuForce> makeCpuGravity() {
  return std::make_unique<CpuGravity>();
}

}  // namespace ff
