// controller.h - the separable fluid controller: control particles (eq. 4-6)
// driven by cluster shape matching (eq. 7-9), with fluid feedback.
//
// It knows nothing of SPH: it reads spans of fluid positions and velocities
// and returns accelerations, so any particle fluid can embed it (the paper's
// "easy to embed" claim). The OpenMP backend uses it for its control phases.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "control/control_set.h"
#include "control/recapture_field.h"
#include "core/params.h"
#include "core/state_io.h"
#include "ff_rotation.h"
#include "grid/uniform_grid.h"

namespace ff {

struct FluidView {
  size_t n = 0;
  const float *x = nullptr, *y = nullptr, *z = nullptr;
  const float *vx = nullptr, *vy = nullptr, *vz = nullptr;
  float volume = 0.0f;  // V_e of eq. 5: the rest volume of one particle
  // Optional: a grid whose ranges index these arrays directly (the arrays are
  // sorted by it, cells of any size) and groups of up to 8 consecutive
  // particles in one row of its cells (UniformGrid::rowGroups). Without it
  // the controller sorts a copy of the fluid itself.
  const UniformGrid* grid = nullptr;
  const std::vector<uint32_t>* groups = nullptr;
  const float* rho = nullptr;  // per-particle density; only read with ControlForceUnits::ForceDensity
  float rest_density = 1.0f;   // used instead of rho when rho is null
  float mass = 1.0f;           // particle mass; only read with ControlForceUnits::Force
  float gravity[3] = {0.0f, 0.0f, 0.0f};  // the host solver's gravity (for gravity compensation)
  // Optional: the fluid the control shapes, as a flag per particle identity
  // (id[i] for particle i); only that fluid is recaptured. Null: all of it.
  const uint32_t* id = nullptr;
  const uint8_t* controlled_by_id = nullptr;
};

class Controller {
 public:
  void setParams(const ControlParams& cp, const ShapeMatchParams& sm) {
    cp_ = cp, sm_ = sm, pairs_ready_ = false, control_sorted_ = false;
  }
  // The host's gravity: the anchor (sm.anchor) holds the set against it (none while it is 0).
  void setGravity(const float g[3]) { g_[0] = g[0], g_[1] = g[1], g_[2] = g[2]; }
  // Control particles are kept inside this box (the container), if set.
  void setBounds(const float lo[3], const float hi[3]);
  // New control particles (a new target or region). Restarts the shape-matching clock.
  void reset(ControlSet set);
  void clear() { reset(ControlSet()); }
  bool active() const { return set_.size() > 0; }

  // Phase "control scale": s_i (eq. 5) and the fluid velocity around each
  // control particle, for the feedback. False if a value is not finite.
  bool computeScale(const FluidView& f);
  // Phase "control forces": adds the accelerations of eq. 4 and eq. 6 to a*.
  // Called right after computeScale on the same view, with nothing moved in
  // between (as the phases run), it reuses the pairs of fluid and control
  // particles within reach that computeScale found.
  // Eq. 6 is integrated implicitly over dt (see ff_velocity_force_implicit).
  // False if a value is not finite.
  bool addForces(const FluidView& f, float dt, float* ax, float* ay, float* az);
  // Phase "shape matching": advances the control particles' own clock by dt and
  // runs the shape-matching steps that fall due. Returns how many ran.
  int advance(float dt);
  // One shape-matching step of sm.time_step: feedback, eq. 7-9, integration.
  // False if a value is not finite.
  bool shapeMatchStep();
  // True when no shape-matching step since the last call wrote a NaN or Inf.
  bool takeFinite() {
    const bool ok = sm_finite_;
    sm_finite_ = true;
    return ok;
  }

  // All three phases for one fluid step; for embedding in another solver.
  void step(const FluidView& f, float dt, float* ax, float* ay, float* az);

  // Checkpoints: the control particles, their fields, the cluster rotations
  // (warm starts) and the shape-matching clock.
  void saveState(StateWriter& w) const;
  void loadState(StateReader& r);

  const ControlSet& set() const { return set_; }
  const ControlFields& fields() const { return fields_; }
  const std::vector<ff_quat>& clusterRotations() const { return q_; }
  const std::vector<float>& goalX() const { return gx_; }
  const std::vector<float>& goalY() const { return gy_; }
  const std::vector<float>& goalZ() const { return gz_; }
  double clock() const { return clock_; }
  // Per fluid particle (in the view's order) of the last addForces: 1 if a
  // control particle was within the control radius, else 0 (the metric `stray`).
  const std::vector<uint8_t>& reached() const { return reached_; }
  // The control particles' grid of the last addForces (cells of radius / FF_CONTROL_GRID_DIVISIONS).
  const UniformGrid& controlGrid() const { return cp_grid_; }
  // The recapture's field of targets of the last addForces that recaptured
  // (sorted positions in controlGrid()'s order; kernels/common/ff_recapture_field.h).
  const RecaptureField& recaptureField() const { return rfield_; }
  size_t memoryBytes() const;

 private:
  ControlParams cp_;
  ShapeMatchParams sm_;
  ControlSet set_;
  ControlFields fields_;
  bool bounded_ = false;
  float g_[3] = {0, 0, 0};
  float lo_[3] = {0, 0, 0}, hi_[3] = {0, 0, 0};
  // The fluid sorted by a grid: the view's own when it has one, else a copy.
  struct SortedFluid {
    const UniformGrid* grid = nullptr;
    const std::vector<uint32_t>* groups = nullptr;
    const float *x = nullptr, *y = nullptr, *z = nullptr, *vx = nullptr, *vy = nullptr, *vz = nullptr;
    const uint32_t* order = nullptr;  // sorted position -> view index (null: the same)
  };
  SortedFluid sorted(const FluidView& f);
  // The control particles sorted by cp_grid_ (sx_ .. svz_, sr2_, scoef_).
  void sortControl();
  // For each group of the sorted fluid, the control particles (sorted
  // positions) that some particle of it reaches: hit_at_, hit_bufs_.
  void findPairs(const SortedFluid& sf);

  double clock_ = 0.0;  // time not yet consumed by shape-matching steps
  bool sm_finite_ = true;
  UniformGrid cp_grid_, fluid_grid_;
  RecaptureField rfield_;  // the recapture's targets over cp_grid_ (built while it acts)
  std::vector<uint32_t> fluid_groups_;
  std::vector<uint8_t> reached_;
  std::vector<float> fx_, fy_, fz_, fvx_, fvy_, fvz_;       // the fluid in fluid_grid_ order (no view grid)
  std::vector<float> sx_, sy_, sz_, ss_, svx_, svy_, svz_;  // control particles in cp_grid_ order
  std::vector<float> sr2_, scoef_;  // and their own radius squared and its poly6 coefficient (eq. 5)
  // The pairs within reach, per fluid group (thread's buffer, offset, count
  // in hit_bufs_): the sorted control positions, ascending. pairs_ready_:
  // computeScale found them on the view at pairs_x_ (pairs_n_ particles).
  std::vector<uint32_t> hit_at_;
  std::vector<std::vector<uint32_t>> hit_bufs_;
  std::vector<const uint32_t*> hit_ptr_;  // group g's first pair in hit_bufs_
  // Per group, chunks_ + 1 cuts: its pairs with control particles of chunk c
  // (sorted positions c n / chunks_ .. (c + 1) n / chunks_ - 1) are c's cut .. c+1's.
  std::vector<uint32_t> hit_cut_;
  size_t chunks_ = 1;
  bool pairs_ready_ = false;
  // sx_ .. scoef_ and cp_grid_ hold the control particles as they are: no
  // shape-matching step, reset, new bounds or parameters since sortControl.
  bool control_sorted_ = false;
  const float* pairs_x_ = nullptr;
  size_t pairs_n_ = 0;
  std::vector<float> acc_;  // the scale sums' lanes: per sorted control position 4 x 8 floats
  std::vector<ff_quat> q_;
  std::vector<float> cx_, cy_, cz_, gx_, gy_, gz_, cvx_, cvy_, cvz_;
};

}  // namespace ff
