#include "control/controller.h"

#include <cmath>

#include "control/shape_matching.h"
#include "ff_control.h"
#include "ff_sph.h"

namespace ff {

void Controller::setBounds(const float lo[3], const float hi[3]) {
  bounded_ = true;
  for (int d = 0; d < 3; ++d) lo_[d] = lo[d], hi_[d] = hi[d];
}

void Controller::reset(ControlSet set) {
  set_ = std::move(set);
  const size_t n = set_.size();
  fields_.s.assign(n, 1.0f);
  fields_.ux.assign(n, 0.0f), fields_.uy.assign(n, 0.0f), fields_.uz.assign(n, 0.0f);
  q_.assign(set_.clusters.count(), FF_Q(0.0f, 0.0f, 0.0f, 1.0f));
  gx_ = set_.x, gy_ = set_.y, gz_ = set_.z;
  clock_ = 0.0;
}

void Controller::computeScale(const FluidView& f) {
  const long n = long(set_.size());
  if (n == 0) return;
  const float r = cp_.radius, r2 = r * r, coef = ff_poly6_coef(r);
  fluid_grid_.build(f.n, f.x, f.y, f.z, r);
  const auto& order = fluid_grid_.order();
#pragma omp parallel for schedule(dynamic, 64)
  for (long i = 0; i < n; ++i) {
    const float px = set_.x[i], py = set_.y[i], pz = set_.z[i];
    float sum = 0.0f, ux = 0.0f, uy = 0.0f, uz = 0.0f;
    fluid_grid_.forEachRange(px, py, pz, [&](uint32_t b, uint32_t e) {
      for (uint32_t k = b; k < e; ++k) {
        const uint32_t j = order[k];
        const float dx = px - f.x[j], dy = py - f.y[j], dz = pz - f.z[j];
        const float w = ff_poly6(dx * dx + dy * dy + dz * dz, r2, coef);
        if (w <= 0.0f) continue;
        sum += w;
        ux += w * f.vx[j], uy += w * f.vy[j], uz += w * f.vz[j];
      }
    });
    const float rho_hat = f.volume * sum;
    fields_.s[i] = ff_control_scale(rho_hat);
    // Kernel-weighted mean fluid velocity; where the kernel is only partly
    // filled the missing part counts as still air (so it also damps).
    const float norm = sum > 0.0f ? f.volume / FF_FMAX(rho_hat, 1.0f) : 0.0f;
    fields_.ux[i] = ux * norm, fields_.uy[i] = uy * norm, fields_.uz[i] = uz * norm;
  }
}

void Controller::addForces(const FluidView& f, float dt, float* ax, float* ay, float* az) {
  const size_t n = set_.size();
  if (n == 0) return;
  const float r = cp_.radius, r2 = r * r, coef = ff_poly6_coef(r);
  // Control particles sorted by cell of their own grid, with s and velocity.
  cp_grid_.build(n, set_.x.data(), set_.y.data(), set_.z.data(), r);
  const auto& order = cp_grid_.order();
  for (auto* a : {&sx_, &sy_, &sz_, &ss_, &svx_, &svy_, &svz_}) a->resize(n);
  for (size_t k = 0; k < n; ++k) {
    const uint32_t i = order[k];
    sx_[k] = set_.x[i], sy_[k] = set_.y[i], sz_[k] = set_.z[i], ss_[k] = fields_.s[i];
    svx_[k] = set_.vx[i], svy_[k] = set_.vy[i], svz_[k] = set_.vz[i];
  }
  const bool per_density = cp_.units == ControlForceUnits::ForceDensity;
  const float unit_scale = cp_.units == ControlForceUnits::Force ? 1.0f / f.mass : 1.0f;
  const float wa = cp_.attraction, wv = cp_.velocity, gc = cp_.gravity_compensation;
  const float cp_volume = set_.particle_volume;
  const float full_at = ff_control_full_coverage(cp_volume, r, coef);
#pragma omp parallel for schedule(static)
  for (long e = 0; e < long(f.n); ++e) {
    const float xe = f.x[e], ye = f.y[e], ze = f.z[e];
    ff_float3 fa = FF_F3(0.0f, 0.0f, 0.0f);
    float wsum = 0.0f, vsx = 0.0f, vsy = 0.0f, vsz = 0.0f;
    cp_grid_.forEachRange(xe, ye, ze, [&](uint32_t b, uint32_t end) {
      for (uint32_t k = b; k < end; ++k) {
        const ff_float3 d = FF_F3(sx_[k] - xe, sy_[k] - ye, sz_[k] - ze);
        const float d2 = FF_DOT(d, d);
        const float w = ff_poly6(d2, r2, coef);
        if (w <= 0.0f) continue;
        fa += ff_attraction_term(d, FF_SQRT(d2), ss_[k], w);
        wsum += w;
        vsx += w * svx_[k], vsy += w * svy_[k], vsz += w * svz_[k];
      }
    });
    if (wsum <= 0.0f) continue;
    const float scale = per_density ? 1.0f / (f.rho ? f.rho[e] : f.rest_density) : unit_scale;
    const float k = wv * wsum * scale;
    fa = fa * (wa * scale);
    // Gravity carried by the control (all of it inside the shape).
    const float held = gc * ff_control_held(wsum, cp_volume, full_at);
    fa = fa - FF_F3(f.gravity[0], f.gravity[1], f.gravity[2]) * held;
    ax[e] += fa.x + ff_velocity_force_implicit(wv * vsx * scale, k, f.vx[e], dt);
    ay[e] += fa.y + ff_velocity_force_implicit(wv * vsy * scale, k, f.vy[e], dt);
    az[e] += fa.z + ff_velocity_force_implicit(wv * vsz * scale, k, f.vz[e], dt);
  }
}

int Controller::advance(float dt) {
  if (set_.size() == 0) return 0;
  clock_ += dt;
  int steps = 0;
  const double h = sm_.time_step;
  while (clock_ >= h * (1.0 - 1e-9)) {
    shapeMatchStep();
    clock_ -= h;
    ++steps;
  }
  return steps;
}

void Controller::shapeMatchStep() {
  const long n = long(set_.size());
  if (n == 0) return;
  clusterFrames(set_, q_, cx_, cy_, cz_, sm_.rotation_iterations);
  clusterGoals(set_, q_, cx_, cy_, cz_, gx_, gy_, gz_);
  clusterVelocities(set_, cvx_, cvy_, cvz_);
  const float h = sm_.time_step, alpha = sm_.stiffness, fb = cp_.feedback, damp = sm_.damping;
  const Clusters& cl = set_.clusters;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    ff_float3 v = FF_F3(set_.vx[i], set_.vy[i], set_.vz[i]);
    const ff_float3 x = FF_F3(set_.x[i], set_.y[i], set_.z[i]);
    ff_float3 vc = FF_F3(0.0f, 0.0f, 0.0f);
    for (uint32_t k = cl.of_start[i]; k < cl.of_start[i + 1]; ++k) {
      const uint32_t c = cl.of[k];
      vc += FF_F3(cvx_[c], cvy_[c], cvz_[c]);
    }
    vc = vc * (1.0f / float(cl.of_start[i + 1] - cl.of_start[i]));
    v = ff_feedback_velocity(v, vc, damp);  // the same relaxation, towards the clusters' motion
    v = ff_feedback_velocity(v, FF_F3(fields_.ux[i], fields_.uy[i], fields_.uz[i]), fb);
    v += ff_shape_match_dv(FF_F3(gx_[i], gy_[i], gz_[i]), x, alpha, h);
    ff_float3 nx = x + v * h;
    if (bounded_) {
      float* c[3] = {&nx.x, &nx.y, &nx.z};
      float* vv[3] = {&v.x, &v.y, &v.z};
      for (int d = 0; d < 3; ++d) {
        if (*c[d] < lo_[d]) *c[d] = lo_[d], *vv[d] = 0.0f;
        if (*c[d] > hi_[d]) *c[d] = hi_[d], *vv[d] = 0.0f;
      }
    }
    set_.x[i] = nx.x, set_.y[i] = nx.y, set_.z[i] = nx.z;
    set_.vx[i] = v.x, set_.vy[i] = v.y, set_.vz[i] = v.z;
  }
}

void Controller::step(const FluidView& f, float dt, float* ax, float* ay, float* az) {
  computeScale(f);
  addForces(f, dt, ax, ay, az);
  advance(dt);
}

}  // namespace ff
