// Sweep parameter overrides (docs/sweeps.md): a value for the task's friction, one of its uncertainty bounds,
// or a motion's commanded velocity/position, written into the task's YAML tree. The edited text is loaded
// again by the task loader, so every check of the task format (e.g. theta_v < pi/2) applies to the
// overridden task exactly as to a hand-written file.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "models/task.h"

namespace cmt {

struct ParamTarget {
  enum class Kind { kFriction, kUncertainty, kMotion };
  Kind kind = Kind::kFriction;
  std::string name;  // the uncertainty key (eps_s, eps_p, theta_v, theta_f, step) or the motion name

  // The key in a configuration's params object (results store): friction, theta_v, ..., motions.NAME.
  std::string param_key() const;
  // The key path in the task file: friction, uncertainty.theta_v, motions.NAME.
  std::string task_path() const;
};

// The uncertainty keys a sweep may set.
const std::vector<std::string>& uncertainty_override_keys();

struct ParamValue {
  ParamTarget target;
  std::vector<double> value;  // one number, or the motion's 2- or 3-vector
  std::string spec_key;       // where in the spec file the value comes from, for messages

  nlohmann::json json() const;  // a number or a list of numbers
};

using ParamSet = std::vector<ParamValue>;

// The task text with the values written in (a motion keeps its kind: spring or damper). `base` is the parsed
// task, for the motions' kinds. The result is the re-emitted YAML tree (comments dropped), also for an empty
// set, so that the same task always gives the same text.
std::string apply_overrides(const std::string& base_yaml, const Task& base, const ParamSet& params);

// The params object of a configuration: {param_key: value}.
nlohmann::json params_json(const ParamSet& params);

}  // namespace cmt
