// backend_opencl_impl.h - the OpenCL backend's device state: context,
// program, kernels and buffers (shared by the backend_opencl*.cpp files).
#pragma once
#include <vector>

#include "host/backend_opencl.h"
#include "host/cl_context.h"
#include "host/cl_kernel.h"
#include "host/cl_program.h"
#include "host/device_grid.h"
#include "sim/backend.h"

namespace ff {

struct OpenClBackend::Impl {
  explicit Impl(int device_index);

  ClContext ctx;
  cl::Program program;
  GridBuilder grids;
  // The non-pressure forces' kernels belong to their plug-ins (host/forces/).
  ClKernel reorder, density, pressure_wcsph, integrate;
  ClKernel sm_frames, sm_velocities, sm_anchor, sm_integrate;
  ClKernel sm_frames_by_lane;                    // 8 work-items per shape-matching cluster (GPUs)
  ClKernel density_lanes, pressure_wcsph_lanes;  // 8 particles per work-item
  ClKernel m_iou_lanes;                          // 8 voxels per work-item
  ClKernel m_fluid, m_coverage, m_com, m_apq, m_iou, m_shares;

  // Fluid, double-buffered for the reorder: [cur] holds the current state.
  DeviceBuffer x[2], y[2], z[2], vx[2], vy[2], vz[2], id[2];
  int cur = 0;
  DeviceBuffer rho, p, ax, ay, az;
  DeviceGrid fluid_h;    // cell h over the fluid (sorts it; control scale; the metrics' index grid)
  DeviceGrid control_r;  // cell = control radius / FF_CONTROL_GRID_DIVISIONS over the control particles

  // Control particles (fixed order) and their per-step fields.
  DeviceBuffer cx, cy, cz, cvx, cvy, cvz, x0, y0, z0, s, ux, uy, uz, gx, gy, gz;
  DeviceBuffer crs;                            // radius scales (adaptive control)
  DeviceBuffer sx, sy, sz, ss, svx, svy, svz;  // copies in control_r's cell order
  DeviceBuffer rcentre;     // the recapture's centre (xyz), fade, aim, on, seeds (control_forces.cl)
  DeviceBuffer rseeds[2];   // the recapture's field of targets and its flooding scratch
  size_t rfield_cells = 0;  // cells of the field (rseeds[0]) after the last control forces
  // Clusters (CSR both ways) and their per-step frames.
  DeviceBuffer cl_start, cl_members, rest_cx, rest_cy, rest_cz, of_start, of;
  // The rest-shape blend's start configuration and cluster start centres
  // (ControlSet::bx0, Clusters::from_cx; uploaded only with a blend).
  DeviceBuffer bx0, by0, bz0, from_cx, from_cy, from_cz;
  DeviceBuffer q, com_x, com_y, com_z, ccv_x, ccv_y, ccv_z;
  DeviceBuffer anchor_fix;  // the anchor's correction: dv, dw, com (9 floats; ff_anchor.h)

  DeviceBuffer inside;      // the metrics target's voxels (uchar: 1 inside, 3 inside and thin)
  DeviceBuffer reach;       // per fluid particle: a control particle within reach in control_forces (uchar)
  DeviceBuffer controlled;  // per particle id: controlled fluid (uchar; unused when all the fluid is)
  DeviceBuffer partial;
  std::vector<float> partial_host;
  std::vector<cl_uint> partial_uint;
  DeviceBuffer clamps;  // velocity clamps in integrate since the metrics last read them (one uint)
  DeviceBuffer bad;     // the tag of the first kernel that wrote a NaN or Inf (ff_check.h), else 0

  const cl::Buffer& X() const { return x[cur].get(); }
  const cl::Buffer& Y() const { return y[cur].get(); }
  const cl::Buffer& Z() const { return z[cur].get(); }
  const cl::Buffer& VX() const { return vx[cur].get(); }
  const cl::Buffer& VY() const { return vy[cur].get(); }
  const cl::Buffer& VZ() const { return vz[cur].get(); }
  cl::CommandQueue& queue() { return ctx.queue(); }
  // Work-groups for a reduction over n items: at most 64, so the host sums few partials.
  static size_t reduceGroups(size_t n, size_t local) {
    size_t g = (n + local - 1) / local;
    return g < 1 ? 1 : (g > 64 ? 64 : g);
  }
  // Work-groups for a count (an integer sum: any number of groups gives the
  // same result): one work-item per element up to 16384 groups, so a large
  // device is filled; the kernels stride beyond that.
  static size_t countGroups(size_t n, size_t local) {
    size_t g = (n + local - 1) / local;
    return g < 1 ? 1 : (g > 16384 ? 16384 : g);
  }
};

// Fluid buffers hold a multiple of 8 floats: kernels read 8 at a time (control_scale.cl, *_lanes).
inline size_t padded8(size_t n) {
  return (n + 7) / 8 * 8;
}
// Work-groups of the lane kernels: at most this many work-items (of 8
// particles each), so that a few thousand particles still make several
// work-groups per CPU thread.
constexpr size_t kLaneGroupCap = 32;
inline const float* boxMin(const ContainerDesc& b) {
  return b.min.data();
}
inline const float* boxMax(const ContainerDesc& b) {
  return b.max.data();
}

inline cl_float4 boxLo(const ContainerDesc& b) {
  return f4(b.min.x(), b.min.y(), b.min.z(), 0.0f);
}
inline cl_float4 boxHi(const ContainerDesc& b) {
  return f4(b.max.x(), b.max.y(), b.max.z(), 0.0f);
}

}  // namespace ff
