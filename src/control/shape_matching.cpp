#include "control/shape_matching.h"

#include "ff_cluster_sums.h"
#include "ff_shape_match.h"
#include "parallel/parallel_grain.h"

namespace ff {

void clusterFrames(const ControlSet& set, std::vector<ff_quat>& q, std::vector<float>& cx,
                   std::vector<float>& cy, std::vector<float>& cz, int iterations) {
  const Clusters& cl = set.clusters;
  const long nc = long(cl.count());
  // The rest positions at the blend weight of this step (ff_blend_rest_at).
  const float w = set.blendWeight();
  q.resize(size_t(nc), FF_Q(0.0f, 0.0f, 0.0f, 1.0f));
  cx.resize(size_t(nc)), cy.resize(size_t(nc)), cz.resize(size_t(nc));
#pragma omp parallel for schedule(dynamic, 16)
  for (long c = 0; c < nc; ++c) {
    const ff_float3 com =
        ff_sm_frame(set.x.data(), set.y.data(), set.z.data(), set.x0.data(), set.y0.data(), set.z0.data(),
                    set.bx0.data(), set.by0.data(), set.bz0.data(), cl.rest_cx.data(), cl.rest_cy.data(),
                    cl.rest_cz.data(), cl.from_cx.data(), cl.from_cy.data(), cl.from_cz.data(),
                    cl.start.data(), cl.members.data(), uint32_t(c), w, iterations, &q[size_t(c)]);
    cx[c] = com.x, cy[c] = com.y, cz[c] = com.z;
  }
}

void clusterVelocities(const ControlSet& set, std::vector<float>& vx, std::vector<float>& vy,
                       std::vector<float>& vz) {
  const Clusters& cl = set.clusters;
  const long nc = long(cl.count());
  vx.resize(size_t(nc)), vy.resize(size_t(nc)), vz.resize(size_t(nc));
#pragma omp parallel for schedule(static) if (nc > kParallelLightLoop)
  for (long c = 0; c < nc; ++c) {
    const ff_float3 v = ff_cluster_mean3_of(set.vx.data(), set.vy.data(), set.vz.data(), cl.members.data(),
                                            cl.start[c], cl.start[c + 1]);
    vx[c] = v.x, vy[c] = v.y, vz[c] = v.z;
  }
}

void clusterGoals(const ControlSet& set, const std::vector<ff_quat>& q, const std::vector<float>& cx,
                  const std::vector<float>& cy, const std::vector<float>& cz, std::vector<float>& gx,
                  std::vector<float>& gy, std::vector<float>& gz) {
  const Clusters& cl = set.clusters;
  const long n = long(set.size()), nc = long(cl.count());
  gx.resize(size_t(n)), gy.resize(size_t(n)), gz.resize(size_t(n));
  const float w = set.blendWeight();
  // ff_sm_goal's per-cluster terms, once per cluster instead of once per
  // member: the rotation matrix of q[c] and the rest centre at blend weight w
  // (pure functions of the cluster, so ff_sm_goal_framed gives the same bits).
  static thread_local std::vector<ff_mat3> rot;
  static thread_local std::vector<ff_float3> rest;
  rot.resize(size_t(nc)), rest.resize(size_t(nc));
  ff_mat3* const R = rot.data();  // (the caller's thread's scratch, shared with the loops' threads)
  ff_float3* const RC = rest.data();
#pragma omp parallel for schedule(static) if (nc > kParallelLightLoop)
  for (long c = 0; c < nc; ++c) {
    R[c] = ff_quat_to_mat3(q[size_t(c)]);
    RC[c] = ff_blend_rest_at(cl.from_cx.data(), cl.from_cy.data(), cl.from_cz.data(), cl.rest_cx.data(),
                             cl.rest_cy.data(), cl.rest_cz.data(), uint32_t(c), w);
  }
#pragma omp parallel for schedule(static) if (n > kParallelLightLoop)
  for (long p = 0; p < n; ++p) {
    const ff_float3 g = ff_sm_goal_framed(set.x0.data(), set.y0.data(), set.z0.data(), set.bx0.data(),
                                          set.by0.data(), set.bz0.data(), cl.of_start.data(), cl.of.data(), R,
                                          RC, cx.data(), cy.data(), cz.data(), uint32_t(p), w);
    gx[size_t(p)] = g.x, gy[size_t(p)] = g.y, gz[size_t(p)] = g.z;
  }
}

void bestFitFrame(const ControlSet& set, ff_quat& q, float c[3], int iterations) {
  const size_t n = set.size();
  double mx = 0, my = 0, mz = 0;
  for (size_t p = 0; p < n; ++p) mx += set.x[p], my += set.y[p], mz += set.z[p];
  if (n) mx /= double(n), my /= double(n), mz /= double(n);
  ff_float3 com = FF_F3(float(mx), float(my), float(mz));
  ff_float3 rc = FF_F3(set.rest_cx, set.rest_cy, set.rest_cz);
  ff_mat3 apq = ff_mat3_zero();
  for (size_t p = 0; p < n; ++p)
    apq = ff_mat3_add_outer(apq, FF_F3(set.x[p], set.y[p], set.z[p]) - com,
                            FF_F3(set.x0[p], set.y0[p], set.z0[p]) - rc);
  q = ff_extract_rotation(apq, q, iterations);
  c[0] = com.x, c[1] = com.y, c[2] = com.z;
}

}  // namespace ff
