// dfsph_cl.h - DFSPH (Bender & Koschier 2015, 2017) on the OpenCL backend,
// the device counterpart of src/cpu/dfsph_solver.* chosen by
// params.fluid.solver = "dfsph". It owns its per-particle device buffers
// (factors, wall gradients, bulk flags, the warm-start k, the solves'
// scratch) and runs kernels/dfsph_sums.cl and kernels/dfsph_solve.cl, which
// call the bodies of kernels/common/ff_dfsph.h in the OpenMP solver's order,
// so that PoCL gives the same numbers bit for bit and the same iteration
// counts. The stopping test runs on the device: the host enqueues the
// iterations every solve runs (its minimum), then kIterationBatch at a time,
// and reads the solve's state (three ints, one counted blocking read) after
// each batch; the iterations enqueued past the stop do nothing.
#pragma once
#include <CL/opencl.hpp>
#include <vector>

#include "core/params.h"
#include "core/stage_time.h"
#include "ff_dfsph.h"
#include "host/cl_context.h"
#include "host/cl_kernel.h"
#include "host/device_grid.h"
#include "scene/scene.h"

namespace ff {

// The backend's current fluid buffers that a solver phase reads and writes.
struct ClFluidRefs {
  cl::CommandQueue* queue = nullptr;
  const cl::Context* context = nullptr;
  const cl::Buffer *x = nullptr, *y = nullptr, *z = nullptr, *vx = nullptr, *vy = nullptr, *vz = nullptr;
  const cl::Buffer *rho = nullptr, *p = nullptr, *ax = nullptr, *ay = nullptr, *az = nullptr;
  const DeviceGrid* grid = nullptr;
  const cl::Buffer* bad = nullptr;  // the non-finite record (ff_check.h)
  size_t n = 0;
  bool lanes = false;  // 8 particles per work-item (else one)
};

class ClDfsphSolver {
 public:
  // Iterations enqueued between two reads of a solve's state.
  static constexpr int kIterationBatch = 4;

  ClDfsphSolver(const cl::Program& program, const ClContext& ctx);

  // Phase "density": rho, alpha, the walls' gradient and the bulk flags.
  void computeDensity(const ClFluidRefs& f, const FluidParams& p, const ContainerDesc& box, int tag);
  // Phase "pressure" for a substep of dt: both solves; sets a to the
  // accelerations that reach the solved velocities and p to the pressure.
  void solve(const ClFluidRefs& f, const FluidParams& p, float dt, int tag);
  // The grid phase reordered the fluid by f.grid->order: the warm starts follow.
  void reorder(const ClFluidRefs& f);

  // While on, each stage (the factor, the divergence solve, the density
  // solve) waits for its kernels and is timed, as the OpenMP solver's stages.
  void setProfiling(bool on) { profiling_ = on; }
  // The stages' times since the last call (empty unless profiling).
  std::vector<StageTime> takeStages() {
    std::vector<StageTime> s;
    s.swap(stages_);
    return s;
  }
  // Iterations and capped solves since the last call.
  void take(long& iterations, long& capped);
  // The last substep's iterations of each solve (for tests).
  int lastDivergenceIterations() const { return last_div_; }
  int lastDensityIterations() const { return last_dens_; }
  size_t memoryBytes() const;

 private:
  void ensure(const ClFluidRefs& f);
  // While profiling: waits for the queue and adds the time since *t0 to the
  // stage `name` of `phase`, then restarts *t0.
  void record(const ClFluidRefs& f, const char* phase, const char* name, double* t0);
  int iterate(const ClFluidRefs& f, const FluidParams& p, bool density, float dt, double tol,
              int min_iterations, float warm, int which);
  void sources(const ClFluidRefs& f, bool density, float dt, bool gated);
  // The density solve pushes with wp*_ (the walls' gradient at x + dt u), the divergence solve with wg*_.
  void applyVelocityChange(const ClFluidRefs& f, bool density, const DeviceBuffer& k, float scale,
                           bool gated);

  ClKernel factor_, factor_lanes_, rate_, rate_lanes_, kappa_, kappa_lanes_;
  ClKernel source_, check_, warm_, increment_, apply_, predict_, finish_, reorder_;
  DeviceBuffer alpha_, wgx_, wgy_, wgz_, bulk_;
  DeviceBuffer vax_, vay_, vaz_, q_;        // the fluid's parts of the factor (ff_dfsph_factor_at)
  DeviceBuffer wall_;                       // the walls' density shares S(x_i) of the density phase
  DeviceBuffer wpx_, wpy_, wpz_, alpha_p_;  // the density solve's wall gradient and factor at x + dt u
  DeviceBuffer k_[2][2];                    // [double buffer for the reorder][kd, kv]
  int kcur_ = 0;
  DeviceBuffer inc_, b_, rate_buf_, dux_, duy_, duz_, ux_, uy_, uz_, partial_, state_;
  size_t n_ = 0;  // particles the buffers hold (k restarts from 0 when it changes)
  bool sized_ = false;
  float vol_ = 0.0f, vol_spacing_ = 0.0f, vol_h_ = 0.0f;
  float last_dt_ = 0.0f, rho0_ = 1.0f;
  FfDfsphArgs args_{};
  long iterations_ = 0, capped_ = 0;
  int last_div_ = 0, last_dens_ = 0;
  bool profiling_ = false;
  std::vector<StageTime> stages_;
};

}  // namespace ff
