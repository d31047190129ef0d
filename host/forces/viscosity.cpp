// viscosity.cpp - the viscosity plug-in of the OpenCL backend (kernels
// `viscosity` and `viscosity_lanes` in kernels/forces.cl), as
// src/cpu/forces/viscosity.cpp.
#include <memory>

#include "host/backend_opencl_impl.h"
#include "host/forces/cl_force.h"
#include "host/sph_args.h"

namespace ff {

namespace {

class ClViscosity : public ClForce {
 public:
  ClViscosity(const cl::Program& program, const ClContext& ctx)
      : k_(makeKernel(program, "viscosity", ctx)),
        lanes_(makeKernel(program, "viscosity_lanes", ctx, kLaneGroupCap)) {}
  const char* name() const override { return "viscosity"; }
  void apply(ClForceContext& c, float) override {
    const ClFluidRefs& f = c.fluid;
    const FluidParams& p = c.params.fluid;
    if (f.n == 0 || !(p.viscosity > 0.0f)) return;  // adds exactly 0
    const DeviceGrid& g = *f.grid;
    launch(*f.queue, f.lanes ? lanes_ : k_, f.lanes ? padded8(f.n) / 8 : f.n, *f.x, *f.y, *f.z, *f.vx, *f.vy,
           *f.vz, *f.rho, cl_uint(f.n), g.start.get(), g.geom.geo(), g.geom.dims(),
           sphArgs(p, c.box, g.geom.cell), *f.ax, *f.ay, *f.az, *f.bad, cl_int(c.tag));
  }

 private:
  ClKernel k_, lanes_;
};

}  // namespace

std::unique_ptr<ClForce> makeClViscosity(const cl::Program& program, const ClContext& ctx) {
  return std::make_unique<ClViscosity>(program, ctx);
}

}  // namespace ff
