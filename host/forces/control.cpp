// control.cpp - the control plug-in of the OpenCL backend, as
// src/cpu/forces/control.cpp: the density scale of the control particles
// (kernels/control_scale.cl, phase control_scale) and their forces on the
// fluid with the recapture (kernels/control_forces.cl and
// kernels/recapture_field.cl, phase control_forces), in Controller's order.
#include <memory>
#include <utility>

#include "control/control_args.h"
#include "control/recapture_field.h"
#include "ff_control.h"
#include "ff_sph.h"
#include "host/backend_opencl_impl.h"
#include "host/forces/cl_force.h"

namespace ff {

namespace {

// 4-byte fields with no padding: the kernels read the same bytes.
static_assert(sizeof(FfScaleArgs) == 13 * 4, "FfScaleArgs must hold 4-byte fields only");

class ClControl : public ClForce {
 public:
  ClControl(const cl::Program& program, const ClContext& ctx)
      : scale_(makeKernel(program, "control_scale", ctx)),
        scale_by_lane_(makeKernel(program, "control_scale_by_lane", ctx, 256, 4 * sizeof(float))),
        gather_(makeKernel(program, "control_gather", ctx)),
        forces_(makeKernel(program, "control_forces", ctx)),
        forces_lanes_(makeKernel(program, "control_forces_lanes", ctx, kLaneGroupCap)),
        recapture_centre_(makeKernel(program, "control_recapture_centre", ctx)),
        recapture_seed_(makeKernel(program, "recapture_seed", ctx)),
        recapture_flood_(makeKernel(program, "recapture_flood", ctx)) {}
  const char* name() const override { return "control"; }
  Phase phase() const override { return Phase::ControlForces; }
  void prepare(ClForceContext& c) override;
  void apply(ClForceContext& c, float dt) override;

 private:
  ClKernel scale_, scale_by_lane_, gather_, forces_, forces_lanes_, recapture_centre_, recapture_seed_,
      recapture_flood_;
};

void ClControl::prepare(ClForceContext& c) {
  const ClFluidRefs& f = c.fluid;
  OpenClBackend::Impl& d = c.device;
  const size_t nc = c.control_count;
  if (nc == 0 || f.n == 0) return;
  // The fluid as the grid phase sorted it (cell h).
  const DeviceGrid& g = *f.grid;
  FfScaleArgs A{};
  const cl_float4 geo = g.geom.geo();
  const cl_int4 dims = g.geom.dims();
  for (int k = 0; k < 4; ++k) A.geo[k] = geo.s[k], A.dims[k] = dims.s[k];
  A.cell = g.geom.cell, A.radius = c.params.control.radius, A.volume = c.params.fluid.restVolume();
  A.nc = cl_uint(nc), A.tag = cl_int(c.tag);
  // The scalar variant (GPUs): 8 work-items per control particle, one per
  // lane of the float8 sums, in work-groups of a power of two >= 8.
  if (!f.lanes && scale_by_lane_.pow2_local >= 8) {
    const size_t local = scale_by_lane_.pow2_local, groups = (8 * nc + local - 1) / local;
    launchGroups(*f.queue, scale_by_lane_, groups, local, d.cx.get(), d.cy.get(), d.cz.get(), d.crs.get(),
                 *f.x, *f.y, *f.z, *f.vx, *f.vy, *f.vz, g.start.get(), A, d.s.get(), d.ux.get(), d.uy.get(),
                 d.uz.get(), *f.bad, cl::Local(local * 4 * sizeof(float)));
  } else {
    launch(*f.queue, scale_, nc, d.cx.get(), d.cy.get(), d.cz.get(), d.crs.get(), *f.x, *f.y, *f.z, *f.vx,
           *f.vy, *f.vz, g.start.get(), A, d.s.get(), d.ux.get(), d.uy.get(), d.uz.get(), *f.bad);
  }
}

void ClControl::apply(ClForceContext& c, float dt) {
  const ClFluidRefs& f = c.fluid;
  OpenClBackend::Impl& d = c.device;
  const size_t nc = c.control_count, n = f.n;
  if (nc == 0 || n == 0) return;
  cl::CommandQueue& q = *f.queue;
  const ControlParams& cp = c.params.control;
  const float r = cp.radius;
  d.grids.build(d.control_r, d.cx.get(), d.cy.get(), d.cz.get(), nc, r / float(FF_CONTROL_GRID_DIVISIONS),
                boxMin(c.box), boxMax(c.box));
  launch(q, gather_, nc, d.control_r.order.get(), cl_uint(nc), d.cx.get(), d.cy.get(), d.cz.get(), d.s.get(),
         d.cvx.get(), d.cvy.get(), d.cvz.get(), d.sx.get(), d.sy.get(), d.sz.get(), d.ss.get(), d.svx.get(),
         d.svy.get(), d.svz.get());
  const float cp_volume = c.control.particle_volume;
  const float* g = c.params.fluid.gravity;
  const DeviceGrid& cg = d.control_r;
  // Recapture (as Controller::addForces): its centre, fade and aim, then its
  // field of targets (seeded, flooded into rseeds[0]; read only while the
  // recapture acts and its centre lies outside the shape: the field's
  // kernels read that from rcentre and otherwise do nothing), then the forces.
  const int gn[3] = {cg.geom.nx, cg.geom.ny, cg.geom.nz};
  const float go[3] = {cg.geom.ox, cg.geom.oy, cg.geom.oz};
  const RecaptureFieldGeom fg = recaptureFieldGeom(gn, go, cg.geom.cell);
  d.rfield_cells = fg.cells();
  d.rcentre.ensure(d.ctx.context(), 7 * sizeof(float));
  launch(q, recapture_centre_, 1, d.cx.get(), d.cy.get(), d.cz.get(), d.s.get(), cl_uint(nc),
         cl_int(cp.recapture > 0.0f ? 1 : 0), d.sx.get(), d.sy.get(), d.sz.get(), cg.start.get(),
         cg.geom.geo(), cg.geom.dims(), cg.geom.cell, FF_CBRT(cp_volume), d.rcentre.get());
  for (DeviceBuffer& b : d.rseeds) b.ensure(d.ctx.context(), d.rfield_cells * sizeof(cl_uint));
  if (cp.recapture > 0.0f) {  // else the forces never read the field
    launch(q, recapture_seed_, d.rfield_cells, cg.start.get(), d.sx.get(), d.sy.get(), d.sz.get(), d.ss.get(),
           f4(go[0], go[1], go[2], cg.geom.cell), cg.geom.dims(), i4(fg.m[0], fg.m[1], fg.m[2], 0),
           d.rcentre.get(), d.rseeds[0].get());
    for (int step : recaptureFloodSteps(fg)) {
      launch(q, recapture_flood_, d.rfield_cells, d.rseeds[0].get(), d.sx.get(), d.sy.get(), d.sz.get(),
             cl_int(step), f4(fg.o[0], fg.o[1], fg.o[2], fg.fcell), i4(fg.m[0], fg.m[1], fg.m[2], 0),
             d.rcentre.get(), d.rseeds[1].get());
      std::swap(d.rseeds[0], d.rseeds[1]);
    }
  }
  const cl::Buffer& mask = c.masked ? d.controlled.get() : d.reach.get();  // unread without a mask
  const FfControlArgs P =
      controlArgs(cp, g, c.params.fluid.particle_mass, cp_volume, dt, cg.geom.cell, fg, c.masked, c.tag);
  ClKernel& k = f.lanes ? forces_lanes_ : forces_;
  launch(q, k, f.lanes ? padded8(n) / 8 : n, *f.x, *f.y, *f.z, *f.vx, *f.vy, *f.vz, *f.rho, cl_uint(n),
         d.sx.get(), d.sy.get(), d.sz.get(), d.ss.get(), d.svx.get(), d.svy.get(), d.svz.get(),
         cg.start.get(), cg.geom.geo(), cg.geom.dims(), P, d.rcentre.get(), d.rseeds[0].get(),
         d.id[d.cur].get(), mask, *f.ax, *f.ay, *f.az, d.reach.get(), *f.bad);
}

}  // namespace

std::unique_ptr<ClForce> makeClControl(const cl::Program& program, const ClContext& ctx) {
  return std::make_unique<ClControl>(program, ctx);
}

}  // namespace ff
