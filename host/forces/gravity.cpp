// gravity.cpp - the gravity plug-in of the OpenCL backend (kernel `gravity`
// in kernels/forces.cl), as src/cpu/forces/gravity.cpp.
#include <memory>

#include "host/backend_opencl_impl.h"
#include "host/forces/cl_force.h"

namespace ff {

namespace {

class ClGravity : public ClForce {
 public:
  ClGravity(const cl::Program& program, const ClContext& ctx) : k_(makeKernel(program, "gravity", ctx)) {}
  const char* name() const override { return "gravity"; }
  void apply(ClForceContext& c, float) override {
    const ClFluidRefs& f = c.fluid;
    if (f.n == 0) return;
    const float* g = c.params.fluid.gravity;
    launch(*f.queue, k_, f.n, *f.ax, *f.ay, *f.az, cl_uint(f.n), f4(g[0], g[1], g[2], 0.0f), *f.bad,
           cl_int(c.tag));
  }

 private:
  ClKernel k_;
};

}  // namespace

std::unique_ptr<ClForce> makeClGravity(const cl::Program& program, const ClContext& ctx) {
  return std::make_unique<ClGravity>(program, ctx);
}

}  // namespace ff
