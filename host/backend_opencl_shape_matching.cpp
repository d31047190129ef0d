// backend_opencl_shape_matching.cpp - the shape-matching phase of the OpenCL
// backend (Controller::advance); the control's forces on the fluid are its
// plug-in host/forces/control.cpp.

#include "control/shape_match_args.h"
#include "ff_anchor.h"
#include "host/backend_opencl.h"
#include "host/backend_opencl_impl.h"
#include "host/cl_errors.h"

namespace ff {

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
  // The blend weight of this step; without a blend the start configuration
  // arguments are the reference's own buffers (never read at w = 1).
  const float w = control_.blendWeight();
  const bool bl = w < 1.0f;
  const cl::Buffer &bx = bl ? d.bx0.get() : d.x0.get(), &by = bl ? d.by0.get() : d.y0.get(),
                   &bz = bl ? d.bz0.get() : d.z0.get();
  const cl::Buffer &fx = bl ? d.from_cx.get() : d.rest_cx.get(), &fy = bl ? d.from_cy.get() : d.rest_cy.get(),
                   &fz = bl ? d.from_cz.get() : d.rest_cz.get();
  // "Up" for the anchor (ff_anchor.h; A.anchor: it acts), as Controller::shapeMatchStep.
  ff_float3 up = FF_F3(0.0f, 0.0f, 0.0f);
  ff_anchor_up(params_.fluid.gravity, &up);
  const FfShapeMatchArgs A = shapeMatchArgs(sm, params_.control.feedback, cl_uint(nc_), cl_uint(nclusters_),
                                            w, params_.fluid.gravity, boxMin(box_), boxMax(box_), tag);
  auto run = [&](const auto&... args) {
    if (spread)
      launchGroups(d.queue(), frames, groups, local, args..., cl::Local(local * 15 * sizeof(float)));
    else
      launch(d.queue(), frames, nclusters_, args...);
  };
  run(d.cx.get(), d.cy.get(), d.cz.get(), d.cvx.get(), d.cvy.get(), d.cvz.get(), d.x0.get(), d.y0.get(),
      d.z0.get(), bx, by, bz, d.rest_cx.get(), d.rest_cy.get(), d.rest_cz.get(), fx, fy, fz, d.cl_start.get(),
      d.cl_members.get(), A, d.q.get(), d.com_x.get(), d.com_y.get(), d.com_z.get(), d.ccv_x.get(),
      d.ccv_y.get(), d.ccv_z.get());
  launch(d.queue(), d.sm_velocities, nc_, d.cx.get(), d.cy.get(), d.cz.get(), d.cvx.get(), d.cvy.get(),
         d.cvz.get(), d.x0.get(), d.y0.get(), d.z0.get(), bx, by, bz, d.rest_cx.get(), d.rest_cy.get(),
         d.rest_cz.get(), fx, fy, fz, d.of_start.get(), d.of.get(), d.q.get(), d.com_x.get(), d.com_y.get(),
         d.com_z.get(), d.ccv_x.get(), d.ccv_y.get(), d.ccv_z.get(), d.ux.get(), d.uy.get(), d.uz.get(), A,
         d.gx.get(), d.gy.get(), d.gz.get());
  d.anchor_fix.ensure(d.ctx.context(), 9 * sizeof(float));
  if (A.anchor) {
    const ControlSet& s = control_;
    launch(d.queue(), d.sm_anchor, 1, d.cx.get(), d.cy.get(), d.cz.get(), d.cvx.get(), d.cvy.get(),
           d.cvz.get(), d.x0.get(), d.y0.get(), d.z0.get(), f4(s.rest_cx, s.rest_cy, s.rest_cz, 0.0f),
           f4(s.anchor_x, s.anchor_y, s.anchor_z, 0.0f), f4(up.x, up.y, up.z, 0.0f), A, d.q.get(),
           d.anchor_fix.get());
  }
  launch(d.queue(), d.sm_integrate, nc_, d.cx.get(), d.cy.get(), d.cz.get(), d.cvx.get(), d.cvy.get(),
         d.cvz.get(), A, d.anchor_fix.get(), d.bad.get());
  if (bl) control_.blend_elapsed += double(sm.time_step);
}

}  // namespace ff
