// Adversarial rollouts (docs/falsify.md): instead of sampling the bounded errors at random, search them.
// A rollout's errors are a vector in [0, 1]^n (sim/error_vector.h); the cross-entropy method
// (cross_entropy.h) chooses vectors
//   - to falsify: maximize the signed distance of a motion end from its predicted termination set
//     (robustness.h); an end farther out than the contact tolerance is a soundness bug, reported with the
//     `cmt rollout --errors` command that replays it; under a "reliable" verdict a failed rollout is one too;
//   - to cover: for each predicted termination piece that no random or falsification rollout ended in,
//     minimize the distance of that motion's end from the piece; the pieces still unreached after the budget
//     are listed (verifier looseness or a gap in the search, docs/falsify.md "Coverage");
//   - to fail (under an unreliable verdict): minimize the distance of the final end from the predicted
//     places where the strategy fails (the termination pieces outside the goal, a spring's free rest ball)
//     until a rollout fails; none failing in any phase marks the verdict a false alarm candidate;
//   - to fill coverage gaps: the coverage lattice point (validation.h coverage_lattice) farthest from every
//     end of its motion is the target of a search that minimizes its motion's end's distance from it, until
//     an end covers it (within the baseline's coverage radius) or its rollouts run out; then the next
//     farthest, skipping points near a target no search reached (docs/falsify.md "Gap search").
// Coverage is scored as `cmt validate` scores it (validation_coverage.cc), before (random rollouts only) and
// after (every rollout). Every draw comes from the seed; results are the same for any thread count.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "experiments/falsify/cross_entropy.h"
#include "experiments/validation/validation.h"
#include "sim/error_vector.h"

namespace cmt {

// Pieces targeted by the coverage search, largest first; the rest are listed as not searched.
inline constexpr int kMaxCoverageTargets = 12;

struct FalsifyOptions {
  int budget = 400;           // falsification search rollouts
  int coverage_budget = 400;  // coverage search rollouts, shared among the unreached pieces
  int random = 100;           // random rollouts first (the baseline coverage), sampled in `mode`
  int gap_budget = 0;         // gap search rollouts (0: none)
  int gap_rollouts = 96;      // at most this many per gap
  // Failure search rollouts, run only under an unreliable verdict (0: none): a search for a rollout that
  // fails, toward the predicted places where the strategy fails (docs/falsify.md "False alarms").
  int failure_budget = 0;
  SampleMode mode = SampleMode::kExtreme;
  std::uint64_t seed = 1;
  int threads = 1;
  ControllerForm form = ControllerForm::kImpedance;  // as `cmt validate` (verifier_model.h)
  int switches = 3;                                  // K velocity-error switches per motion
  CrossEntropyOptions search;
};

// One end found outside (or a failed rollout under a reliable verdict).
struct FalsifyFinding {
  std::string how;     // "falsify", "coverage", "failure", "gap" or "random"
  std::string motion;  // the motion whose end is outside ("" for a failure at the goal)
  int step = -1;       // its prediction step
  Vec3 end = Vec3::Zero();
  double distance = 0;         // outside its predicted set (task units)
  std::vector<double> errors;  // the error vector (empty for a random rollout: replay by seed)
  std::string replay;
};

// A predicted termination piece and whether some rollout ended in it.
struct PieceCoverage {
  int step = 0;
  std::string motion;
  ReachedPiece piece;
  double measure = 0;      // area, length or 0 for a point
  std::string reached_by;  // "random", "falsify", "coverage", "gap" or "" (unreached)
  bool searched = false;   // the coverage search targeted it
  double closest = 0;      // the nearest end's distance from it (task units)
  int rollouts = 0;        // coverage-search rollouts spent on it
};

// A coverage gap the gap search targeted: a point of a motion's coverage lattice that no end covered.
struct CoverageGap {
  int step = 0;
  std::string motion;
  Vec3 point = Vec3::Zero();
  double gap = 0;        // its distance from the nearest end of its motion when it was chosen
  double closest = 0;    // the nearest end after its search
  bool reached = false;  // an end of its search came within `radius`
  int rollouts = 0;
  double radius = 0;  // its motion's coverage radius (validation.h StepValidation::radius)
};

// A search rollout's end of a predicted motion (every phase but the random one): the report draws them per
// motion beside the random ends (docs/falsify.md "In sweeps and the report").
struct SearchEnd {
  std::string how;  // "falsify", "coverage", "failure" or "gap"
  int step = 0;     // the prediction step
  Vec3 end = Vec3::Zero();
  bool inside = false;  // within the contact tolerance of the step's predicted set
};

struct FalsifyResult {
  std::string task, strategy;
  FalsifyOptions options;
  VerifyResult prediction;
  ErrorVectorShape shape;
  int dimension = 0;  // error vector length
  int searches = 0;   // cross-entropy searches (restarts included), every phase
  int rollouts = 0;   // search rollouts, every phase (the random ones not included)
  int unstable = 0;   // search rollouts that became unstable (scored as nothing)
  // Per prediction step: the largest signed distance any falsification rollout reached (> 0: outside).
  std::vector<double> best_signed_distance;
  std::vector<double> best_errors;       // the falsification search's best vector
  std::vector<FalsifyFinding> findings;  // soundness bugs, farthest first (at most kMaxWorstEnds)
  int outside = 0;                       // ends outside, all phases
  double coverage_before = 0, coverage_after = 0;
  double coverage_radius = 0;  // the random baseline's (both are measured at it)
  std::vector<PieceCoverage> pieces;
  std::vector<CoverageGap> gaps;       // in the order searched
  std::vector<SearchEnd> search_ends;  // in the order run (unstable rollouts have none)
  // Stable rollouts that failed (did not end in the goal), every phase, the random or baseline ones
  // included; the first found (phases in order: random, falsify, coverage, failure, gap) with its replay.
  int failures = 0;
  std::optional<FalsifyFinding> first_failure;
  int failure_rollouts = 0;  // of the failure search
  // The failure search's closest approach of a final end to the predicted places of failure (task units;
  // infinite when the verifier named none, or the search did not run), and whether it ran.
  double failure_closest = std::numeric_limits<double>::infinity();
  bool failure_searched = false;
  double verify_seconds = 0, random_seconds = 0, search_seconds = 0, coverage_seconds = 0, gap_seconds = 0;
  double failure_seconds = 0;
  // Buckley's verdict against every rollout here: unreliable, yet no rollout failed (the failure search
  // included when it ran).
  bool false_alarm() const { return !prediction.reliable && failures == 0; }
};

// The verifier runs on the task's model for the controller form (make_verifier_model, as in run_validation).
FalsifyResult run_falsify(std::shared_ptr<const LoadedTask> task, const std::string& strategy,
                          const FalsifyOptions& options);
// The same against a given prediction (tests: a deliberately shrunk one).
FalsifyResult run_falsify(std::shared_ptr<const LoadedTask> task, const Strategy& strategy,
                          const VerifyResult& prediction, const FalsifyOptions& options);
// The same with rollouts the caller already ran as the baseline, in place of options.random new ones (a
// sweep unit: the validation's N rollouts, run_validation with options.seed, options.mode and options.form).
// They play the random rollouts' part: coverage_before is theirs, the pieces they reach count as reached by
// "random" and coverage_radius is theirs; their ends outside are NOT findings (nor counted in `outside`):
// the validation scores them already. result.options.random is the baseline's size, random_seconds 0.
FalsifyResult run_falsify(std::shared_ptr<const LoadedTask> task, const Strategy& strategy,
                          const VerifyResult& prediction, const FalsifyOptions& options,
                          const std::vector<RolloutOutcome>& baseline);

// `cmt rollout TASK --strategy S --errors V [--controller F]`.
std::string error_replay_command(const LoadedTask& task, const std::string& strategy,
                                 const std::vector<double>& errors, ControllerForm form);

// The `cmt falsify --json` object (docs/falsify.md).
nlohmann::json falsify_json(const LoadedTask& task, const FalsifyResult& result);

}  // namespace cmt
