// backend_opencl_metrics.cpp - phase "metrics" of the OpenCL backend: the
// device reduces to per-group partials, the host adds those up in double
// precision (as CpuBackend::computeMetrics, src/metrics/iou.cpp).
#include <algorithm>
#include <cmath>

#include "host/backend_opencl.h"
#include "host/backend_opencl_impl.h"
#include "host/cl_errors.h"
#include "host/dfsph_cl.h"
#include "metrics/pose.h"

namespace ff {

namespace {

// Sums (or, for the columns in max_mask, takes the max of) `groups` partials of `width` floats.
std::vector<double> finish(const std::vector<float>& partial, size_t groups, size_t width,
                           unsigned max_mask) {
  std::vector<double> out(width, 0.0);
  for (size_t g = 0; g < groups; ++g)
    for (size_t k = 0; k < width; ++k) {
      const double v = partial[g * width + k];
      out[k] = ((max_mask >> k) & 1u) ? std::max(out[k], v) : out[k] + v;
    }
  return out;
}

}  // namespace

StepMetrics OpenClBackend::computeMetrics(bool with_shape) {
  return clGuard("phase 'metrics'", [&] {
    Impl& d = *d_;
    cl::CommandQueue& q = d.queue();
    const cl::Context& c = d.ctx.context();
    StepMetrics m;
    if (dfsph_) dfsph_->take(m.solver_iterations, m.solver_capped);
    const float rho0 = params_.fluid.rest_density, mass = params_.fluid.particle_mass;
    // Reduces n items with kernel k (width floats per item), returns the finished sums.
    auto reduce = [&](ClKernel& k, size_t n, size_t width, unsigned max_mask, auto&&... args) {
      const size_t local = k.pow2_local, groups = Impl::reduceGroups(n, local);
      d.partial.ensure(c, groups * width * sizeof(float));
      launchGroups(q, k, groups, local, args..., d.partial.get(), cl::Local(local * width * sizeof(float)));
      d.partial_host.resize(groups * width);
      blockingRead(q, d.partial.get(), groups * width * sizeof(float), d.partial_host.data());
      return finish(d.partial_host, groups, width, max_mask);
    };
    cl_uint clamps = 0;
    blockingRead(q, d.clamps.get(), sizeof(cl_uint), &clamps);
    fillBuffer(q, d.clamps, cl_uint(0), 1);
    m.velocity_clamps = long(clamps);
    if (n_ > 0) {
      const std::vector<double> f = reduce(d.m_fluid, n_, 6, (1u << 2) | (1u << 3) | (1u << 5), d.rho.get(),
                                           d.p.get(), d.VX(), d.VY(), d.VZ(), cl_uint(n_), rho0);
      m.density_error = f[0] / double(n_);
      m.kinetic_energy = 0.5 * double(mass) * f[1];
      m.max_speed = std::sqrt(f[2]);
      m.max_density = f[3];
      m.compression = f[4] / double(n_);
      m.max_pressure = f[5];
    }
    if (nc_ == 0) return m;
    m.coverage = reduce(d.m_coverage, nc_, 1, 0u, d.s.get(), cl_uint(nc_))[0] / double(nc_);
    m.control_count = long(nc_);
    if (!target_ || n_ == 0) return m;

    // bestFitFrame: centre of mass, A_pq about it, rotation warm-started from the last frame.
    const std::vector<double> sum =
        reduce(d.m_com, nc_, 3, 0u, d.cx.get(), d.cy.get(), d.cz.get(), cl_uint(nc_));
    const float com[3] = {float(sum[0] / double(nc_)), float(sum[1] / double(nc_)),
                          float(sum[2] / double(nc_))};
    const std::vector<double> a =
        reduce(d.m_apq, nc_, 9, 0u, d.cx.get(), d.cy.get(), d.cz.get(), d.x0.get(), d.y0.get(), d.z0.get(),
               cl_uint(nc_), f4(com[0], com[1], com[2], 0.0f),
               f4(frame_.rest_c[0], frame_.rest_c[1], frame_.rest_c[2], 0.0f));
    ff_mat3 apq;
    apq.c0 = FF_F3(float(a[0]), float(a[1]), float(a[2]));
    apq.c1 = FF_F3(float(a[3]), float(a[4]), float(a[5]));
    apq.c2 = FF_F3(float(a[6]), float(a[7]), float(a[8]));
    frame_.q = ff_extract_rotation(apq, frame_.q, params_.shape.rotation_iterations * 4);
    for (int k = 0; k < 3; ++k) frame_.c[k] = com[k];
    if (!with_shape) return m;
    // The thin voxels follow the control radius: a params edit since the
    // target was set (viewer, script, Python) finds them again.
    if (thin_radius_ != params_.control.radius) setMetricsTarget(target_);

    // The fluid's index grid (cell h) over the current positions; the next
    // buildGrid sorts by it instead of building it again.
    const float h = params_.fluid.smoothing_radius;
    if (grid_state_ != GridState::Index) {
      d.grids.build(d.fluid_h, d.X(), d.Y(), d.Z(), n_, h, boxMin(box_), boxMax(box_));
      grid_state_ = GridState::Index;
    }
    const VoxelGrid& g = target_->grid;
    const int pad = 2;
    // Voxels (one per work-item), or runs of 8 along x (float8 lanes).
    const size_t runs = lanes_ ? size_t(g.nx + 2 * pad + 7) / 8 : size_t(g.nx + 2 * pad);
    const size_t total = runs * size_t(g.ny + 2 * pad) * size_t(g.nz + 2 * pad);
    const ff_mat3 r = ff_quat_to_mat3(frame_.q);
    ClKernel& k = lanes_ ? d.m_iou_lanes : d.m_iou;
    const size_t local = k.pow2_local, groups = Impl::countGroups(total, local);
    d.partial.ensure(c, groups * 3 * sizeof(cl_uint));
    const cl_int4 tdims = i4(g.nx, g.ny, g.nz, pad);
    const cl_float4 torigin = f4(g.origin.x(), g.origin.y(), g.origin.z(), g.voxel);
    const cl_float4 r0 = f4(r.c0.x, r.c0.y, r.c0.z, 0.0f), r1 = f4(r.c1.x, r.c1.y, r.c1.z, 0.0f),
                    r2 = f4(r.c2.x, r.c2.y, r.c2.z, 0.0f);
    const cl_float4 fc = f4(frame_.c[0], frame_.c[1], frame_.c[2], 0.0f),
                    rc = f4(frame_.rest_c[0], frame_.rest_c[1], frame_.rest_c[2], 0.0f);
    const DeviceGrid& fg = d.fluid_h;
    const cl::LocalSpaceArg tmp = cl::Local(local * 3 * sizeof(cl_uint));
    if (lanes_)
      launchGroups(q, k, groups, local, d.inside.get(), tdims, torigin, r0, r1, r2, fc, rc, d.X(), d.Y(),
                   d.Z(), fg.order.get(), fg.start.get(), fg.geom.geo(), fg.geom.dims(), fg.geom.cell, h,
                   mass, 0.5f * rho0, d.partial.get(), tmp);
    else
      launchGroups(q, k, groups, local, d.inside.get(), tdims, torigin, r0, r1, r2, fc, rc, d.X(), d.Y(),
                   d.Z(), fg.order.get(), fg.start.get(), fg.geom.geo(), fg.geom.dims(), h, mass, 0.5f * rho0,
                   d.partial.get(), tmp);
    d.partial_uint.resize(groups * 3);
    blockingRead(q, d.partial.get(), groups * 3 * sizeof(cl_uint), d.partial_uint.data());
    IouCounts counts;
    for (size_t k = 0; k < groups; ++k) {
      counts.inter += long(d.partial_uint[3 * k]), counts.uni += long(d.partial_uint[3 * k + 1]);
      counts.inter_thin += long(d.partial_uint[3 * k + 2]);
    }

    // Where the fluid lies: (controlled, captured, stray, far) per group.
    ClKernel& ks = d.m_shares;
    const size_t sgroups = Impl::reduceGroups(n_, ks.pow2_local);
    d.partial.ensure(c, sgroups * 4 * sizeof(cl_uint));
    // Without a mask the kernel never reads `controlled`: any buffer will do.
    const cl::Buffer& mask = masked_ ? d.controlled.get() : d.reach.get();
    launchGroups(q, ks, sgroups, ks.pow2_local, d.X(), d.Y(), d.Z(), d.id[d.cur].get(), cl_uint(n_), mask,
                 cl_int(masked_ ? 1 : 0), d.reach.get(), d.inside.get(), tdims, torigin, r0, r1, r2, fc, rc,
                 d.partial.get(), cl::Local(ks.pow2_local * 4 * sizeof(cl_uint)));
    d.partial_uint.resize(sgroups * 4);
    blockingRead(q, d.partial.get(), sgroups * 4 * sizeof(cl_uint), d.partial_uint.data());
    FluidShares sh;
    for (size_t k = 0; k < sgroups; ++k) {
      sh.controlled += long(d.partial_uint[4 * k]), sh.captured += long(d.partial_uint[4 * k + 1]);
      sh.stray += long(d.partial_uint[4 * k + 2]), sh.far += long(d.partial_uint[4 * k + 3]);
    }
    setShapeMetrics(m, counts, sh, target_voxels_, particleVoxels(params_.fluid.restVolume(), *target_),
                    thin_voxels_);
    const ShapePose pose = shapePose(*target_, frame_, params_.fluid.gravity, box_.min, box_.max);
    m.tilt = pose.tilt, m.base_height = pose.base_height;
    return m;
  });
}

}  // namespace ff
