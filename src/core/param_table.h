// param_table.h - the single table of run parameters: every key of the scene's
// "params" object with its type, its sane range and what it means. The scene
// reader, the viewer script reader and validateParams all go through it, so a
// range is written once (here, in param_table.cpp).
#pragma once
#include <string>
#include <vector>

#include "core/params.h"

namespace ff {

struct ParamInfo {
  enum class Type {
    Real,     // one float
    Integer,  // one int
    Vector,   // three floats (a JSON array of 3 numbers)
    Units,    // ControlForceUnits, written as a string
    Solver,   // PressureSolverKind, written as its name (solverName)
  };
  const char* group;  // "fluid", "control" or "shape_matching"
  const char* key;    // the key inside the group, e.g. "time_step"
  Type type;
  // Allowed range (every component for Vector). min_open excludes min itself.
  double min, max;
  bool min_open;
  const char* doc;  // one line: what the parameter means, with its unit
  // The field in a Params (a float, an int, a float[3], a ControlForceUnits or a PressureSolverKind).
  void* (*field)(Params&);
  // An integer that picks one of the modes min..max (control.normalise,
  // control.adaptive, shape_matching.anchor), not a count or an amount: a
  // sweep runs it in each mode instead of scaling it (bench --stability).
  bool mode = false;

  std::string name() const;  // "params.GROUP.KEY"
  // The value of a Real or Integer parameter in `p`.
  double number(const Params& p) const;
  // "in [MIN, MAX]" or "in (MIN, MAX]"
  std::string rangeText() const;
  bool inRange(double v) const;
};

// Every parameter, group by group, in the order the docs list them.
const std::vector<ParamInfo>& paramTable();
// The names of the groups ("fluid", "control", "shape_matching").
const std::vector<std::string>& paramGroups();

// Writes the Real parameter `info` of `p`. A step in seconds (fluid.time_step,
// shape_matching.time_step) goes through its group's setTimeStep, which turns
// the group's *_fall off: a step given in seconds is the step taken. The
// scene/params overlay and bench --stability write through this. A *_fall
// written after its step (the table lists it later) turns it on again.
void setRealParam(const ParamInfo& info, Params& p, float v);
// One rule of which parameter overrides which: params.GROUP.KEY has no
// effect while params.GROUP.BY meets `when`. With `sets`, BY sets KEY's
// value at run time (a step from its fall time, the radius from
// radius_spacings), so the value a Params holds there is derived, not given;
// otherwise BY's mode leaves KEY unused (its value stays the user's). Every
// reader of "is this key overridden" goes through this one table: the scene
// reader's warning (and so a script's params and Python's set_params), the
// scene writer, the viewer's panel and bench --stability.
struct OverrideRule {
  // When BY overrides KEY: BY's value is above 0 (a number that is off at 0),
  // is the mode 1, or the mode 0.
  enum class When { Positive, One, Zero };
  const char* group;  // "control"
  const char* key;    // "attraction"
  const char* by;     // the key of the same group that overrides it: "normalise"
  bool sets;          // whether `by` sets key's value (else its mode leaves key unused)
  When when;
  const char* note;  // what acts instead: "attraction_g and velocity_rate act instead"

  // `when` in words: "> 0", "is 1", "is 0".
  const char* condition() const;
  // Whether params.GROUP.BY meets `when` in `p`.
  bool holds(const Params& p) const;
};
const std::vector<OverrideRule>& overrideRules();
// The rule under which another parameter overrides `info` in `p`, or nullptr.
const OverrideRule* overriddenBy(const ParamInfo& info, const Params& p);
// Whether the value of `info` acts on a run with parameters `p` (no rule
// overrides it). The viewer's panel shows the sliders that act;
// bench --stability sweeps them.
bool paramActs(const ParamInfo& info, const Params& p);
// Why `info` does not act ("while params.control.normalise is 1 (...)"), or
// "" where it does: a scene's or script's params that give it are warned.
std::string whyNoEffect(const ParamInfo& info, const Params& p);
// Whether another parameter sets `info`'s value at run time (a rule with
// `sets`): the scene writer leaves it out, so the scene keeps following it.
bool setByAnother(const ParamInfo& info, const Params& p);

// The most shape-matching steps one fluid step may make
// (params.fluid.time_step / params.shape_matching.time_step).
constexpr double kMaxShapeStepsPerStep = 1000.0;

}  // namespace ff
