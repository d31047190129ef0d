// viewer_session.h - the viewer's simulation, window-free: the running
// Simulation, the user's edits (target, region, parameters) and what a reset
// keeps. The viewer plays the scene's target schedule itself, so that a target
// the user picks is not replaced by the next scheduled one.
#pragma once
#include <memory>
#include <string>

#include "scene/scene.h"
#include "sim/simulation.h"

namespace ff::viewer {

struct BackendChoice {
  std::string kind = "auto";  // auto | cpu | opencl
  int device = -1;
  int threads = 0;
};

class ViewerSession {
 public:
  // Builds the backend and the Simulation and applies the schedule's entries
  // at time 0. Throws ff::Error (backend, scene or target problems).
  ViewerSession(const SceneDesc& scene, const BackendChoice& backend);

  Simulation& sim() { return *sim_; }
  const Simulation& sim() const { return *sim_; }
  const SceneDesc& scene() const { return scene_; }  // as loaded
  const std::string& backendNote() const { return note_; }

  // A target picked by the user: applied now, and the scene's schedule stops.
  // Throws ff::Error (e.g. an unreadable mesh); the previous target then stays.
  void chooseTarget(const TargetSpec& spec);
  void chooseNoTarget();
  bool followsSchedule() const { return follow_schedule_; }
  std::string targetLabel() const;  // "none" without control

  // The current target is rebuilt from all the fluid inside the region.
  // Throws ff::Error, keeping the previous region, when the region holds no fluid.
  void setRegion(const RegionDesc& region);
  const RegionDesc& region() const { return sim_->scene().region; }

  // Throws ff::Error naming the field (validateParams); the previous ones stay.
  // A new cluster size or coarse level re-places the control particles of the
  // current target.
  void setParams(const Params& params);
  const Params& params() const { return sim_->scene().params; }

  // The scene as it stands now, to save: the container and fluid as loaded,
  // the current parameters and region, and the picked target (or the scene's
  // schedule while it is followed; nothing after "No control"). No camera.
  SceneDesc currentScene() const;

  // The schedule entries that fall due (when it is followed), then one step.
  void step();

  // Rebuilds the Simulation at time 0 with a fresh backend.
  // keep_edits = true: the current parameters and region stay, and so does the
  // picked target (or "No control"); when none was picked the scene's schedule
  // plays again from its start. keep_edits = false: the scene as loaded.
  // Returns a warning when the kept target could not be applied at time 0 (for
  // instance: the kept region holds no fluid then); the run is then uncontrolled.
  // Throws ff::Error if the new Simulation cannot be built; the old one stays.
  std::string reset(bool keep_edits);

 private:
  void applyDueSchedule();

  SceneDesc scene_;
  BackendChoice backend_;
  std::string note_;
  std::unique_ptr<Simulation> sim_;
  bool follow_schedule_ = true;
  bool chose_none_ = false;
  TargetSpec chosen_;  // the user's pick (when !follow_schedule_ && !chose_none_)
  TargetSpec active_;  // the spec of the target the Simulation holds now
  size_t next_schedule_ = 0;
};

}  // namespace ff::viewer
