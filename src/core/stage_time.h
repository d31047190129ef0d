// stage_time.h - the time of a named stage inside a step's phase (a pressure
// solver's divergence solve, its density solve, ...): what `run`'s profile,
// `flowform bench` and the viewer's panel list under the phase.
#pragma once
#include <string>
#include <vector>

namespace ff {

struct StageTime {
  std::string phase;  // the phase it runs in (phaseName), e.g. "pressure"
  std::string name;   // e.g. "divergence solve"
  double ms = 0.0;
};

// Adds `from` into `into` stage by stage (matched by phase and name; new
// stages go at the end, in their order).
inline void addStages(std::vector<StageTime>& into, const std::vector<StageTime>& from) {
  for (const StageTime& s : from) {
    bool found = false;
    for (StageTime& t : into)
      if (t.phase == s.phase && t.name == s.name) t.ms += s.ms, found = true;
    if (!found) into.push_back(s);
  }
}

}  // namespace ff
