// The EDR verdict of a strategy as the CLI gives it (`cmt edr`, `cmt verify --edr`, `cmt validate --edr`):
// the task's slices at a resolution, the verifier's model in each slice and the JSON of the result
// (docs/contracts.md: edr_reliable, slices with params, goal_empty, distinguishable and the F/P/P~/H pieces).
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "models/loaded_task.h"
#include "verifier/edr/edr.h"

namespace cmt {

struct EdrVerdictRequest {
  std::string file;      // the task file, for messages
  std::string strategy;  // a decision-free strategy of the task
  int resolution = 5;    // evenly spaced values per model parameter (model_error.h slice_values)
  int refine_depth = 3;  // slicing-gap refinement (verifier/edr/edr.h EdrOptions::refine_depth)
  // The verifier's model in each slice: Buckley's first order (VerifyOptions{}), or the rollouts' model of
  // the slice's MuJoCo scene (verifier_model.h rollout_verify_options) with the contact lift, servo coast
  // and stop rule replaced where set here (>= 0).
  bool first_order = false;
  double contact_lift = -1, servo_coast = -1, stop_relative_speed = -1;
  // Require the strategy's last motion to carry the EDR termination predicate (`edr: true`).
  bool require_signal = false;
};

// The strategy's verdict over the task's slices. Bad input (a conditional strategy, too many slices, a last
// motion without `edr: true` when required, a slice the loader rejects) throws InputError naming the key.
EdrResult edr_verdict(const LoadedTask& task, const EdrVerdictRequest& request);

// The verdict's JSON: task, strategy, motions, resolution, model, parameters (with critical and slice
// values), slices, terminates, reaches_goal, distinguishable, confusions, confusion_count, edr_reliable,
// reason.
nlohmann::json edr_verdict_json(const Task& task, const EdrVerdictRequest& request, const EdrResult& result);

}  // namespace cmt
