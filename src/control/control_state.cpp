// control_state.cpp - the controller's part of a checkpoint.
#include "control/controller.h"

namespace ff {

void Controller::saveState(StateWriter& w) const {
  w.tag("CTRL");
  for (const auto* a : {&set_.x, &set_.y, &set_.z, &set_.vx, &set_.vy, &set_.vz, &set_.x0, &set_.y0, &set_.z0,
                        &set_.radius_scale})
    w.vec(*a);
  const Clusters& c = set_.clusters;
  w.vec(c.start), w.vec(c.members), w.vec(c.rest_cx), w.vec(c.rest_cy), w.vec(c.rest_cz);
  w.vec(c.of_start), w.vec(c.of);
  w.pod(set_.rest_cx), w.pod(set_.rest_cy), w.pod(set_.rest_cz), w.pod(set_.particle_volume);
  w.pod(set_.anchor_x), w.pod(set_.anchor_y), w.pod(set_.anchor_z);
  w.vec(set_.bx0), w.vec(set_.by0), w.vec(set_.bz0), w.vec(c.from_cx), w.vec(c.from_cy), w.vec(c.from_cz);
  w.pod(set_.blend_time), w.pod(set_.blend_elapsed);
  w.vec(fields_.s), w.vec(fields_.ux), w.vec(fields_.uy), w.vec(fields_.uz);
  w.vec(q_);
  w.pod(clock_);
}

void Controller::loadState(StateReader& r) {
  r.tag("CTRL");
  ControlSet set;
  for (auto* a :
       {&set.x, &set.y, &set.z, &set.vx, &set.vy, &set.vz, &set.x0, &set.y0, &set.z0, &set.radius_scale})
    r.vec(*a);
  Clusters& c = set.clusters;
  r.vec(c.start), r.vec(c.members), r.vec(c.rest_cx), r.vec(c.rest_cy), r.vec(c.rest_cz);
  r.vec(c.of_start), r.vec(c.of);
  r.pod(set.rest_cx), r.pod(set.rest_cy), r.pod(set.rest_cz), r.pod(set.particle_volume);
  r.pod(set.anchor_x), r.pod(set.anchor_y), r.pod(set.anchor_z);
  r.vec(set.bx0), r.vec(set.by0), r.vec(set.bz0), r.vec(c.from_cx), r.vec(c.from_cy), r.vec(c.from_cz);
  r.pod(set.blend_time), r.pod(set.blend_elapsed);
  // Every index must point inside its array: a corrupted file must not make
  // the shape-matching loops read out of bounds.
  const size_t n = set.x.size();
  bool ok = true;
  for (const auto* a :
       {&set.y, &set.z, &set.vx, &set.vy, &set.vz, &set.x0, &set.y0, &set.z0, &set.radius_scale})
    ok = ok && a->size() == n;
  // A radius scale must lie in (0, 1] (NaN fails too): the radius bounds every query.
  for (float s : set.radius_scale) ok = ok && s > 0.0f && s <= 1.0f;
  const size_t nc = c.count();
  ok = ok && c.rest_cx.size() == nc && c.rest_cy.size() == nc && c.rest_cz.size() == nc;
  // The blend's start configuration: none, or one per particle and cluster.
  const bool blend = !set.bx0.empty();
  ok = ok && set.by0.size() == set.bx0.size() && set.bz0.size() == set.bx0.size() &&
       (!blend || set.bx0.size() == n);
  ok = ok && c.from_cx.size() == (blend ? nc : 0) && c.from_cy.size() == c.from_cx.size() &&
       c.from_cz.size() == c.from_cx.size();
  ok = ok && (c.start.empty() || (c.start.front() == 0 && c.start.back() == c.members.size()));
  for (size_t i = 1; ok && i < c.start.size(); ++i) ok = c.start[i - 1] <= c.start[i];
  for (uint32_t m : c.members) ok = ok && m < n;
  ok = ok && (c.of_start.empty() ? n == 0 || c.of.empty() : c.of_start.size() == n + 1);
  ok = ok && (c.of_start.empty() || (c.of_start.front() == 0 && c.of_start.back() == c.of.size()));
  for (size_t i = 1; ok && i < c.of_start.size(); ++i) ok = c.of_start[i - 1] <= c.of_start[i];
  for (uint32_t k : c.of) ok = ok && k < nc;
  r.check(ok, "the control particles' arrays and clusters do not fit together");
  ControlFields f;
  r.vec(f.s), r.vec(f.ux), r.vec(f.uy), r.vec(f.uz);
  std::vector<ff_quat> q;
  r.vec(q);
  r.check(f.s.size() == n && f.ux.size() == n && f.uy.size() == n && f.uz.size() == n && q.size() == nc,
          "the control fields or cluster rotations do not match the control particles");
  const double clock = r.pod<double>();
  reset(std::move(set));
  fields_ = std::move(f);
  q_ = std::move(q);
  clock_ = clock;
}

}  // namespace ff
