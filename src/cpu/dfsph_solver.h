// dfsph_solver.h - DFSPH (Bender & Koschier 2015, 2017) on the OpenMP
// backend. Phase "density": rho with the cubic spline and the analytic wall,
// and each particle's factor alpha. Phase "pressure", per substep: a
// divergence-free solve on the velocities, then, with every other
// acceleration of the substep applied, a constant-density solve. Both
// iterate Jacobi increments alpha_i b_i >= 0 that change the velocities at
// once (b is recomputed from the new velocities before the next one), and
// both are warm-started from half of the last substep's k, scaled by the
// change of dt. The formulas and per-particle bodies are ff_dfsph.h's.
#pragma once
#include <vector>

#include "cpu/neighbour_cache.h"
#include "cpu/pressure_solver.h"

namespace ff {

class DfsphSolver : public PressureSolver {
 public:
  std::string name() const override { return "dfsph"; }
  bool computeDensity(CpuFluid& f, const FluidParams& p, const ContainerDesc& box) override;
  bool solve(CpuFluid& f, const FluidParams& p, const ContainerDesc& box, float dt) override;
  void reorder(const std::vector<uint32_t>& order) override;
  size_t memoryBytes() const override;
  const NeighbourCache* neighbours() const override { return cache_current_ ? &cache_ : nullptr; }
  void saveState(StateWriter& w) const override;
  void loadState(StateReader& r, size_t n) override;

  // For tests: the last substep's iterations of each solve.
  int lastDivergenceIterations() const { return last_div_; }
  int lastDensityIterations() const { return last_dens_; }
  // For tests: the solves (density, divergence) whose warm start was 0 for
  // every particle, so that its walks were skipped.
  long coldStarts(bool density) const { return cold_starts_[density ? 0 : 1]; }

 private:
  // One solve on the velocities u_ (density: the constant-density solve over
  // dt, else the divergence-free solve): warm-started from `warm` times k
  // where the particle compresses, then Jacobi increments until the mean
  // remaining compression (b_) is at most tol. k ends as the total. Returns
  // the iterations.
  int iterate(const CpuFluid& f, const FluidParams& p, bool density, float dt, double tol, int min_iterations,
              float warm, std::vector<float>& k);
  // b_ = each particle's compression (rate) that the velocities u_ still
  // cause, and inc_ its Jacobi increment; returns the mean of b_. rs: the
  // neighbour sums of the rate where known (rs_), else they are walked.
  // With `warm_k`, also its warm start in the same pass: warm_k[i] becomes
  // ff_dfsph_warm_start(warm_k[i], b_i, warm), and *warmed whether any of
  // them is not 0.
  // fill_parts_: `threads` parts of `groups` for the density phase.
  void fillParts(const std::vector<uint32_t>& groups, int threads);
  double sources(const CpuFluid& f, bool density, float dt, const float* rs = nullptr,
                 float* warm_k = nullptr, float warm = 0.0f, bool* warmed = nullptr);
  // u_ += the velocity change of k, over `scale`; and total += k if given
  // (one pass over the neighbour cache).
  // The density solve pushes with the walls' gradient at the predicted
  // position (wp*_, set by sources()), the divergence solve with grad S(x).
  void applyVelocityChange(const CpuFluid& f, bool density, const std::vector<float>& k, float scale,
                           std::vector<float>* total);

  float vol_ = 0.0f;                            // the lattice volume V (ff_dfsph_lattice_volume)
  float vol_spacing_ = 0.0f, vol_h_ = 0.0f;     // what vol_ was computed for
  std::vector<float> alpha_, wgx_, wgy_, wgz_;  // this substep's factors and wall gradients
  std::vector<float> wall_;                     // and the walls' density shares S(x_i)
  std::vector<float> vax_, vay_, vaz_, q_;      // the fluid's parts of the factor (ff_dfsph_factor_at)
  std::vector<float> wpx_, wpy_, wpz_;          // the density solve's wall gradient at x + dt u
  std::vector<uint8_t> bulk_;                   // support filled enough for the divergence solve
  NeighbourCache cache_;                        // this substep's neighbours and gradient factors
  bool cache_current_ = false;                  // from the density phase until the grid phase reorders
  // The divergence sources' neighbour sums on the velocities of the density
  // phase (factorSums), for the next divergence solve's first sources: the
  // velocities do not change between the two phases.
  std::vector<float> rs_;
  bool rs_current_ = false;
  std::vector<float> kd_, kv_;  // warm-start state: the last solves' k
  std::vector<float> inc_, b_, ux_, uy_, uz_, scratch_;
  std::vector<double> group_b_;  // sources(): the sum of b in each lane group
  // The density phase's parts (fillParts) and the first particle of each of
  // the last split's parts.
  std::vector<size_t> fill_parts_;
  std::vector<uint32_t> split_at_;
  int last_div_ = 0, last_dens_ = 0;
  long cold_starts_[2] = {0, 0};
  float last_dt_ = 0.0f, rho0_ = 1.0f;
  float lo_[3] = {0, 0, 0}, hi_[3] = {0, 0, 0};  // the container of this substep
};

}  // namespace ff
