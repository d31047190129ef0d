// run_checkpoints.h - checkpoints of `flowform run`: every T simulated
// seconds, and a last one when SIGINT or SIGTERM asks the run to stop.
#pragma once
#include <string>

#include "sim/simulation.h"

namespace ff::app {

// While alive, SIGINT and SIGTERM only set a flag (the run stops after the
// step in progress); the previous handlers come back on destruction.
class StopSignals {
 public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  // The signal that asked to stop, or 0.
  int caught() const;
};

class Checkpoints {
 public:
  // Into `dir` (created when the first one is written), every `every`
  // simulated seconds after `now` (0: only on request).
  Checkpoints(std::string dir, double every, double now);
  // After a step: writes a checkpoint if one is due; returns its path or "".
  std::string due(const Simulation& sim);
  // Writes one now; returns its path (DIR/checkpoint_STEP.ffck).
  std::string write(const Simulation& sim);

 private:
  std::string dir_;
  double every_, next_;
};

}  // namespace ff::app
