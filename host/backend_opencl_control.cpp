// backend_opencl_control.cpp - the control phases of the OpenCL backend:
// control scale, control forces and shape matching (Controller's phases).
#include <utility>

#include "control/recapture_field.h"
#include "ff_control.h"
#include "ff_sph.h"
#include "host/backend_opencl.h"
#include "host/backend_opencl_impl.h"
#include "host/cl_errors.h"

namespace ff {

void OpenClBackend::computeControlScale() {
  clGuard("phase 'control_scale'", [&] {
    Impl& d = *d_;
    const int tag = beginPhase(Phase::ControlScale);
    if (nc_ == 0 || n_ == 0) return;
    // The fluid as the grid phase sorted it (cell h).
    const DeviceGrid& g = d.fluid_h;
    // The scalar variant (GPUs): 8 work-items per control particle, one per
    // lane of the float8 sums, in work-groups of a power of two >= 8.
    ClKernel& by_lane = d.control_scale_by_lane;
    if (!lanes_ && by_lane.pow2_local >= 8) {
      const size_t local = by_lane.pow2_local, groups = (8 * nc_ + local - 1) / local;
      launchGroups(d.queue(), by_lane, groups, local, d.cx.get(), d.cy.get(), d.cz.get(), d.crs.get(),
                   cl_uint(nc_), d.X(), d.Y(), d.Z(), d.VX(), d.VY(), d.VZ(), g.start.get(), g.geom.geo(),
                   g.geom.dims(), g.geom.cell, params_.control.radius, params_.fluid.restVolume(), d.s.get(),
                   d.ux.get(), d.uy.get(), d.uz.get(), d.bad.get(), cl_int(tag),
                   cl::Local(local * 4 * sizeof(float)));
    } else {
      launch(d.queue(), d.control_scale, nc_, d.cx.get(), d.cy.get(), d.cz.get(), d.crs.get(), cl_uint(nc_),
             d.X(), d.Y(), d.Z(), d.VX(), d.VY(), d.VZ(), g.start.get(), g.geom.geo(), g.geom.dims(),
             g.geom.cell, params_.control.radius, params_.fluid.restVolume(), d.s.get(), d.ux.get(),
             d.uy.get(), d.uz.get(), d.bad.get(), cl_int(tag));
    }
    endPhase();
  });
}

void OpenClBackend::applyControlForces(float dt) {
  clGuard("phase 'control_forces'", [&] {
    Impl& d = *d_;
    const int tag = beginPhase(Phase::ControlForces);
    if (nc_ == 0 || n_ == 0) return;
    const ControlParams& cp = params_.control;
    const float r = cp.radius;
    d.grids.build(d.control_r, d.cx.get(), d.cy.get(), d.cz.get(), nc_, r / float(FF_CONTROL_GRID_DIVISIONS),
                  boxMin(box_), boxMax(box_));
    launch(d.queue(), d.control_gather, nc_, d.control_r.order.get(), cl_uint(nc_), d.cx.get(), d.cy.get(),
           d.cz.get(), d.s.get(), d.cvx.get(), d.cvy.get(), d.cvz.get(), d.crs.get(), r, d.sx.get(),
           d.sy.get(), d.sz.get(), d.ss.get(), d.svx.get(), d.svy.get(), d.svz.get(), d.sr2.get(),
           d.scoef.get());
    const int pull_mode = cp.pullMode();
    const float unit_scale = cp.units == ControlForceUnits::Force ? 1.0f / params_.fluid.particle_mass : 1.0f;
    const float cp_volume = control_.particle_volume;
    const float full_at = ff_control_full_coverage(cp_volume, r, ff_poly6_coef(r));
    const float* g = params_.fluid.gravity;
    const DeviceGrid& cg = d.control_r;
    // Recapture (as Controller::addForces): its centre, fade and aim, then its
    // field of targets (seeded, flooded into rseeds[0]; read only while the
    // recapture acts and its centre lies outside the shape: the field's
    // kernels read that from rcentre and otherwise do nothing), then the forces.
    const int gn[3] = {cg.geom.nx, cg.geom.ny, cg.geom.nz};
    const float go[3] = {cg.geom.ox, cg.geom.oy, cg.geom.oz};
    const RecaptureFieldGeom fg = recaptureFieldGeom(gn, go, cg.geom.cell);
    rfield_cells_ = fg.cells();
    d.rcentre.ensure(d.ctx.context(), 5 * sizeof(float));
    launch(d.queue(), d.control_recapture_centre, 1, d.cx.get(), d.cy.get(), d.cz.get(), d.s.get(),
           cl_uint(nc_), cl_int(cp.recapture > 0.0f ? 1 : 0), d.sx.get(), d.sy.get(), d.sz.get(),
           cg.start.get(), cg.geom.geo(), cg.geom.dims(), cg.geom.cell, FF_CBRT(cp_volume), d.rcentre.get());
    for (DeviceBuffer& b : d.rseeds) b.ensure(d.ctx.context(), rfield_cells_ * sizeof(cl_uint));
    if (cp.recapture > 0.0f) {  // else the fade is 0 and the forces never read the field
      launch(d.queue(), d.recapture_seed, rfield_cells_, cg.start.get(), d.sx.get(), d.sy.get(), d.sz.get(),
             d.ss.get(), f4(go[0], go[1], go[2], cg.geom.cell), cg.geom.dims(),
             i4(fg.m[0], fg.m[1], fg.m[2], 0), d.rcentre.get(), d.rseeds[0].get());
      for (int step : recaptureFloodSteps(fg)) {
        launch(d.queue(), d.recapture_flood, rfield_cells_, d.rseeds[0].get(), d.sx.get(), d.sy.get(),
               d.sz.get(), cl_int(step), f4(fg.o[0], fg.o[1], fg.o[2], fg.fcell),
               i4(fg.m[0], fg.m[1], fg.m[2], 0), d.rcentre.get(), d.rseeds[1].get());
        std::swap(d.rseeds[0], d.rseeds[1]);
      }
    }
    const cl::Buffer& mask = masked_ ? d.controlled.get() : d.reach.get();  // unread without a mask
    const cl_float4 rparams = f4(cp.recaptureSpeed(g), cp.recaptureRate(g), r, 0.0f);
    ClKernel& k = lanes_ ? d.control_forces_lanes : d.control_forces;
    launch(d.queue(), k, lanes_ ? padded8(n_) / 8 : n_, d.X(), d.Y(), d.Z(), d.VX(), d.VY(), d.VZ(),
           d.rho.get(), cl_uint(n_), d.sx.get(), d.sy.get(), d.sz.get(), d.ss.get(), d.svx.get(), d.svy.get(),
           d.svz.get(), d.sr2.get(), d.scoef.get(), cg.start.get(), cg.geom.geo(), cg.geom.dims(),
           cg.geom.cell, r, cp_volume, full_at, cp.pullAttraction(g), cp.pullVelocity(g),
           cp.gravity_compensation, pull_mode, unit_scale, f4(g[0], g[1], g[2], 0.0f), dt, d.rcentre.get(),
           d.rseeds[0].get(), f4(fg.o[0], fg.o[1], fg.o[2], fg.inv_fcell), i4(fg.m[0], fg.m[1], fg.m[2], 0),
           d.id[d.cur].get(), mask, cl_int(masked_ ? 1 : 0), rparams, d.ax.get(), d.ay.get(), d.az.get(),
           d.reach.get(), d.bad.get(), cl_int(tag));
    endPhase();
  });
}

int OpenClBackend::shapeMatching(float dt) {
  return clGuard("phase 'shape_matching'", [&] {
    const int tag = beginPhase(Phase::ShapeMatching);
    if (nc_ == 0) return 0;
    // The shape-matching clock of Controller::advance.
    clock_ += dt;
    int steps = 0;
    const double h = params_.shape.time_step;
    while (clock_ >= h * (1.0 - 1e-9)) {
      runShapeMatchStep(tag);
      clock_ -= h;
      ++steps;
    }
    endPhase();
    return steps;
  });
}

void OpenClBackend::runShapeMatchStep(int tag) {
  Impl& d = *d_;
  const ShapeMatchParams& sm = params_.shape;
  // The scalar variant (GPUs): 8 work-items per cluster, one per lane of its
  // sums (ff_cluster_sums.h), in work-groups of a power of two >= 8.
  ClKernel& by_lane = d.sm_frames_by_lane;
  const bool spread = !lanes_ && by_lane.pow2_local >= 8;
  ClKernel& frames = spread ? by_lane : d.sm_frames;
  const size_t local = by_lane.pow2_local, groups = (8 * nclusters_ + local - 1) / local;
  auto run = [&](const auto&... args) {
    if (spread)
      launchGroups(d.queue(), frames, groups, local, args..., cl::Local(local * 15 * sizeof(float)));
    else
      launch(d.queue(), frames, nclusters_, args...);
  };
  run(d.cx.get(), d.cy.get(), d.cz.get(), d.cvx.get(), d.cvy.get(), d.cvz.get(), d.x0.get(), d.y0.get(),
      d.z0.get(), d.cl_start.get(), d.cl_members.get(), d.rest_cx.get(), d.rest_cy.get(), d.rest_cz.get(),
      cl_uint(nclusters_), cl_int(sm.rotation_iterations), d.q.get(), d.com_x.get(), d.com_y.get(),
      d.com_z.get(), d.ccv_x.get(), d.ccv_y.get(), d.ccv_z.get());
  launch(d.queue(), d.sm_particles, nc_, d.cx.get(), d.cy.get(), d.cz.get(), d.cvx.get(), d.cvy.get(),
         d.cvz.get(), d.x0.get(), d.y0.get(), d.z0.get(), cl_uint(nc_), d.of_start.get(), d.of.get(),
         d.rest_cx.get(), d.rest_cy.get(), d.rest_cz.get(), d.q.get(), d.com_x.get(), d.com_y.get(),
         d.com_z.get(), d.ccv_x.get(), d.ccv_y.get(), d.ccv_z.get(), d.ux.get(), d.uy.get(), d.uz.get(),
         sm.time_step, sm.stiffness, params_.control.feedback, sm.damping, boxLo(box_), boxHi(box_),
         d.gx.get(), d.gy.get(), d.gz.get(), d.bad.get(), cl_int(tag));
}

}  // namespace ff
