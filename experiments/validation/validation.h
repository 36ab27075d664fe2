// Predicted vs observed: the verifier's forward projections of a strategy beside N MuJoCo rollouts
// of the same strategy under sampled bounded errors. Soundness asks whether every observed motion end lies
// in the predicted termination set of that motion; coverage asks how much of the predicted set the rollouts
// actually reached. docs/validation.md defines both, the contact tolerance and the coverage radius.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "controllers/controller.h"
#include "controllers/error_model.h"
#include "experiments/validation/sticking_check.h"
#include "experiments/validation/verifier_model.h"
#include "models/loaded_task.h"
#include "sim/rollout.h"
#include "verifier/verify.h"

namespace cmt {

// An observed motion end counts as inside the predicted termination set when it is within this fraction of
// the scene scale of it. The same tolerance as the rollouts' atom attribution (sim/rollout.h
// kAtomRelativeTolerance, 1e-4 of the scene): MuJoCo ends are true C-space points that sit ~1e-7 m inside a
// face at rest and hop up to ~1.5e-6 m off it while sliding, so an end on the predicted set can be that far
// from it; 1e-4 of the scene is 30x the largest hop and small against every feature. Using the rollouts' own
// tolerance means an end the rollouts attribute to an atom is judged against that atom consistently.
inline constexpr double kContactRelativeTolerance = kAtomRelativeTolerance;
// Coverage radius r = sqrt(c A / (pi N)) for N ends of a motion whose predicted face regions have area A
// (docs/validation.md): were the N ends uniform over the area, a point of it would have no end within r
// with probability (1 - pi r^2 / A)^N ~ e^-c. c = 3: ~5 % of a set that the rollouts spread over uniformly
// would still count as uncovered, so coverage well below .95 means parts of the prediction were not reached.
// 1-D predictions (segments, edge intervals) use r = c L / (2 N) for their length L, by the same argument.
inline constexpr double kCoverageConstant = 3;
// Lattice points laid over a motion's predicted area (or along its length) to measure coverage: the
// estimate's sampling error is ~1/sqrt of this for smooth boundaries (< 1 %), at 20000 x N distance tests.
inline constexpr int kCoverageSamples = 20000;
// Outside ends listed in ValidationResult::worst.
inline constexpr int kMaxWorstEnds = 20;

struct ValidateOptions {
  int n = 1000;            // rollouts
  std::uint64_t seed = 1;  // master seed: rollout i uses rollout_stream(seed, i)
  int threads = 1;         // results are identical for every thread count
  SampleMode mode = SampleMode::kUniform;
  // Impedance by default: no sensed force enters its command, so its velocity error is exactly what the
  // verifier models (theta_v). The admittance form is verified with a widened theta_v (verifier_model.h).
  ControllerForm form = ControllerForm::kImpedance;
  // Counterexample search when the verifier says unreliable and no rollout failed: at most this many extra
  // rollouts (extreme-mode errors, start-region vertices, then a local search around the closest miss).
  int counterexample_budget = 400;
  // Per-atom stick/slide agreement table (experiments/validation/sticking_check.h): trials, 0 = skip.
  int sticking_trials = 0;
  // VerifyOptions::spring_coast for the prediction (docs/verifier.md "Servo coast of springs").
  bool spring_coast = true;
  // > 0: the verifier ran out of this wall-clock budget (s) elsewhere (experiments/common/verifier_budget.h):
  // it is not run; the prediction is empty and unreliable with failure "verifier: timed out after B s", every
  // end counts as unpredicted and no counterexample search runs.
  double verifier_timed_out_after = 0;
  // Called once the verifier has finished, before the rollouts (the verifier budget's phase signal).
  std::function<void()> after_verify;
};

// One observed motion end (every motion of every rollout, not only the last).
struct ObservedEnd {
  int rollout = 0;  // rollout index
  // motion_key: the prediction's step for this motion (VerifyResult::steps; = the motion's index in a
  // decision-free strategy), or steps.size() + its index in the rollout when nothing predicts it.
  int motion = 0;
  std::string motion_name;
  Vec3 end = Vec3::Zero();
  int atom = -1;  // nearest atom within the rollout atom tolerance, -1 = free space
  Termination termination = Termination::kNone;
  bool inside = false;     // within the contact tolerance of the motion's predicted termination set
  double distance = 0;     // distance to the predicted set (task units), 0 when inside the exact set
  std::uint64_t seed = 0;  // the rollout's master seed and error mode (replay_command)
  SampleMode mode = SampleMode::kUniform;
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

// Coverage of one motion's prediction (docs/validation.md "Coverage").
struct StepValidation {
  std::string motion;
  int ends = 0;                  // terminated ends of this motion (stable rollouts)
  int outside = 0;               // of which outside its predicted set
  std::string measure = "none";  // "area", "length", "points" or "none" (empty prediction or no ends)
  double predicted = 0;          // the predicted set's area, length or point count
  double covered = 0;            // the part of it within radius of an end (same unit)
  double coverage = 0;           // covered / predicted
  double radius = 0;             // task units
};

// The counterexample search (when the verifier says unreliable and no rollout failed).
struct SearchReport {
  bool ran = false;
  int rollouts = 0;                // extra rollouts run
  int outside = 0;                 // their ends outside the predicted sets (scored like the main ones)
  std::vector<ObservedEnd> worst;  // those ends, farthest first
  std::string note;                // what the search did, in words
};

struct ValidationResult {
  std::string task, strategy;
  ValidateOptions options;
  VerifierModel verifier;  // the bound the verifier used for options.form and why (its task may be widened)
  VerifyResult prediction;
  std::vector<RolloutOutcome> rollouts;
  std::vector<ObservedEnd> ends;  // every terminated motion end of every stable rollout, rollout-major
  int successes = 0, unstable = 0;
  int outside = 0;             // observed motion ends outside the predicted termination sets
  double soundness = 1;        // (ends - outside) / ends, over stable rollouts
  double coverage = 0;         // fraction of the predicted termination area within coverage_radius of an end
  double coverage_radius = 0;  // task units (docs/validation.md: from the sample size)
  double contact_tolerance = 0;    // task units
  std::vector<ObservedEnd> worst;  // the outside ends, farthest first (at most 20)
  // Verdict vs physics: unreliable and some rollout failed -> counterexample from the rollouts; unreliable
  // and none failed -> the search's result (empty if it found none); reliable and a rollout failed ->
  // soundness_bug with that rollout as the counterexample.
  std::optional<Counterexample> counterexample;
  bool soundness_bug = false;
  std::optional<StickingCheckResult> sticking;  // when options.sticking_trials > 0
  double verify_seconds = 0, rollout_seconds = 0;
  // Motions that timed out (Termination::kNone, not a termination point; not in `ends`), and those of them
  // where the verifier said may_not_terminate = false.
  std::vector<ObservedEnd> timeouts, unexpected_timeouts;
  int unpredicted = 0;  // terminated ends of motions after the verifier's failed step (no prediction)
  std::vector<StepValidation> steps;  // per verified motion
  SearchReport search;
  double search_seconds = 0, sticking_seconds = 0;
};

// The scoring parts of run_validation, exposed so tests can feed synthetic predictions and rollouts.
// Distance from p to a step's predicted termination set: the reached set and, for a spring with
// free_termination, the free-space rest ball.
double distance_to_prediction(const VerifyStep& step, const Vec3& p);
// The index of the step in `steps` that predicts a rollout's motion: the one that simulated its strategy
// node (conditional strategies, Buckley §4.2); motions and steps built without nodes pair by position. -1
// when the verifier simulated nothing for it.
int prediction_step(const std::vector<VerifyStep>& steps, const MotionOutcome& motion, int position);
// ObservedEnd::motion and the results store's rollouts.motion: prediction_step, or steps.size() + position
// when nothing predicts the motion (unique within a rollout, since a rollout runs each node at most once).
int motion_key(const std::vector<VerifyStep>& steps, const MotionOutcome& motion, int position);
// One rollout's motion ends against the prediction (prediction_step pairs them), with the contact tolerance:
// terminated ends of predicted motions go to `ends`, time-outs to `timeouts` (and to `unexpected_timeouts`
// when the step said may_not_terminate = false); terminated ends after the last step count in `unpredicted`.
// The rollout ran under (seed, mode).
void observe_rollout(const std::vector<VerifyStep>& steps, const RolloutOutcome& rollout, std::uint64_t seed,
                     SampleMode mode, double tolerance, std::vector<ObservedEnd>* ends,
                     std::vector<ObservedEnd>* timeouts, std::vector<ObservedEnd>* unexpected_timeouts,
                     int* unpredicted);
// From result->prediction, result->rollouts and result->options (seed, mode): successes, unstable, ends,
// timeouts, unexpected_timeouts, unpredicted, outside, soundness, worst, contact_tolerance.
void score_soundness(const LoadedTask& task, ValidationResult* result);
// From result->prediction and result->ends: steps, coverage, coverage_radius (docs/validation.md). With
// `radii` (the steps of an earlier scoring), step k is measured at radii[k].radius instead of the radius from
// its sample size, so that coverage of a superset of ends can be compared with it (it cannot decrease).
void score_coverage(const LoadedTask& task, ValidationResult* result,
                    const std::vector<StepValidation>& radii = {});
// The lattice a step's coverage is measured on: points of the highest-dimensional part of its prediction,
// each standing for an equal share of its measure (area-uniform on face regions, length-uniform on segments,
// the isolated points themselves); planar tasks are measured in the x-z plane.
struct CoverageLattice {
  std::string measure = "none";  // "area", "length", "points" or "none" (empty prediction)
  double predicted = 0;          // the area, length or point count
  std::vector<Vec3> points;
};
CoverageLattice coverage_lattice(const LoadedTask& task, const VerifyStep& step);
// Where coverage measures an end: the end itself, at y = 0 in planar tasks.
Vec3 coverage_position(const LoadedTask& task, Vec3 end);
// Does the result contradict the verifier (exit status 1): an outside end (main or search rollouts), a
// soundness bug, or a stick/slide disagreement in the sticking table.
bool contradicts_verifier(const ValidationResult& result);
// `cmt rollout TASK --strategy S -n (index+1) --seed SEED --mode MODE [--controller FORM]`.
std::string replay_command(const LoadedTask& task, const std::string& strategy, std::uint64_t seed, int index,
                           SampleMode mode, ControllerForm form);

// Runs the verifier and the rollouts (and the search and the sticking table). The verifier runs on
// make_verifier_model(task, options.form).task (theta_v widened for the admittance form), the rollouts on
// `task`. Throws InputError for an unknown strategy or a widened theta_v the task format refuses.
ValidationResult run_validation(std::shared_ptr<const LoadedTask> task, const std::string& strategy,
                                const ValidateOptions& options);

// Runs `work` (a validation with the options it is given, and whatever the caller makes of it, as text) in a
// forked child whose verifier phase has `budget` seconds (experiments/common/verifier_budget.h; the child's
// options.after_verify ends the phase). When the verifier overruns, the child is killed and `work` runs here
// with verifier_timed_out_after = budget: the rollouts without a prediction. Returns work's text either way.
std::string validate_with_verifier_budget(double budget, ValidateOptions options,
                                          const std::function<std::string(const ValidateOptions&)>& work);

// The `cmt validate --json` object: the docs/contracts.md fields (reliable, rollouts, successes, outside,
// soundness, coverage) and the rest of the result (prediction as verify_json, worst offenders, the
// counterexample, the sticking table). `with_ends` adds every observed end.
nlohmann::json validation_json(const LoadedTask& task, const ValidationResult& result,
                               bool with_ends = false);
nlohmann::json counterexample_json(const LoadedTask& task, const Counterexample& counterexample);

}  // namespace cmt
