// Predicted vs observed (issue 6): the verifier's forward projections of a strategy beside N MuJoCo rollouts
// of the same strategy under sampled bounded errors. Soundness asks whether every observed motion end lies
// in the predicted termination set of that motion; coverage asks how much of the predicted set the rollouts
// actually reached. docs/validation.md defines both, the contact tolerance and the coverage radius.
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "controllers/controller.h"
#include "controllers/error_model.h"
#include "experiments/sticking_check.h"
#include "models/loaded_task.h"
#include "sim/rollout.h"
#include "verifier/verify.h"

namespace cmt {

struct ValidateOptions {
  int n = 1000;            // rollouts
  std::uint64_t seed = 1;  // master seed: rollout i uses rollout_stream(seed, i)
  int threads = 1;         // results are identical for every thread count
  SampleMode mode = SampleMode::kUniform;
  ControllerForm form = ControllerForm::kAdmittance;
  // Counterexample search when the verifier says unreliable and no rollout failed: at most this many extra
  // rollouts (extreme-mode errors, start-region vertices, then a local search around the closest miss).
  int counterexample_budget = 400;
  // Per-atom stick/slide agreement table (experiments/sticking_check.h): trials, 0 = skip.
  int sticking_trials = 0;
};

// One observed motion end (every motion of every rollout, not only the last).
struct ObservedEnd {
  int rollout = 0;  // rollout index
  int motion = 0;   // index into the strategy's motions
  Vec3 end = Vec3::Zero();
  int atom = -1;  // nearest atom within the rollout atom tolerance, -1 = free space
  Termination termination = Termination::kNone;
  bool inside = false;  // within the contact tolerance of the motion's predicted termination set
  double distance = 0;  // distance to the predicted set (task units), 0 when inside the exact set
};

// A rollout that replays: `cmt rollout TASK --strategy S -n (index+1) --seed SEED --mode MODE` runs it as
// its last rollout.
struct Counterexample {
  std::uint64_t seed = 0;
  int index = 0;
  SampleMode mode = SampleMode::kUniform;
  std::string how;     // "rollouts", "extreme", "start-vertices", "local-search"
  std::string replay;  // the command line that replays it
  RolloutOutcome outcome;
};

struct ValidationResult {
  std::string task, strategy;
  ValidateOptions options;
  VerifyResult prediction;
  std::vector<RolloutOutcome> rollouts;
  std::vector<ObservedEnd> ends;  // every motion end of every rollout, rollout-major
  int successes = 0, unstable = 0;
  int outside = 0;         // observed motion ends outside the predicted termination sets
  double soundness = 1;    // (ends - outside) / ends, over stable rollouts
  double coverage = 0;     // fraction of the predicted termination area within coverage_radius of an end
  double coverage_radius = 0;      // task units (docs/validation.md: from the sample size)
  double contact_tolerance = 0;    // task units
  std::vector<ObservedEnd> worst;  // the outside ends, farthest first (at most 20)
  // Verdict vs physics: unreliable and some rollout failed -> counterexample from the rollouts; unreliable
  // and none failed -> the search's result (empty if it found none); reliable and a rollout failed ->
  // soundness_bug with that rollout as the counterexample.
  std::optional<Counterexample> counterexample;
  bool soundness_bug = false;
  std::optional<StickingCheckResult> sticking;  // when options.sticking_trials > 0
  double verify_seconds = 0, rollout_seconds = 0;
};

// Runs the verifier and the rollouts (and the search and the sticking table). Throws TaskError for an
// unknown strategy.
ValidationResult run_validation(std::shared_ptr<const LoadedTask> task, const std::string& strategy,
                                const ValidateOptions& options);

// The `cmt validate --json` object: the contracts.md fields (reliable, rollouts, successes, outside,
// soundness, coverage) and the rest of the result (prediction as verify_json, worst offenders, the
// counterexample, the sticking table). `with_ends` adds every observed end.
nlohmann::json validation_json(const LoadedTask& task, const ValidationResult& result, bool with_ends = false);
nlohmann::json counterexample_json(const LoadedTask& task, const Counterexample& counterexample);

}  // namespace cmt
