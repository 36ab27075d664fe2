// A sweep specification (docs/sweeps.md "Spec format"): which tasks, strategies, parameter values (a grid,
// random draws from ranges, or both), rollout count, seeds and sampling mode to validate. Parsing checks the
// spec as strictly as the task loader checks a task: unknown, missing and mistyped keys, out-of-range
// values, unknown strategies and motions, and every override value against the task format; each failure
// throws InputError naming the spec file, the key path and the reason (cmt exits with status 2).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "controllers/controller.h"
#include "controllers/error_model.h"
#include "experiments/common/task_overrides.h"
#include "models/task.h"

namespace cmt {

// Upper limits that catch typos (an extra zero) before hours of work start; raise them if a real study
// needs more.
inline constexpr long long kMaxSweepRollouts = 10'000'000;        // n per unit
inline constexpr long long kMaxSweepRandomDraws = 1'000'000;      // random.count per task
inline constexpr long long kMaxSweepStickingTrials = 10'000'000;  // sticking_trials per unit
inline constexpr long long kMaxSweepCounterexampleBudget = 10'000'000;
inline constexpr long long kMaxSweepFalsifyBudget = 10'000'000;          // each of falsify's budgets
inline constexpr double kMaxSweepVerifyBudgetSeconds = 7 * 24 * 3600.0;  // a week: beyond it, no limit at all
// Seeds are stored in SQLite INTEGER columns (signed 64-bit), so they must stay below 2^63.
inline constexpr long long kMaxSweepSeed = 0x7fffffffffffffffLL;

// The adversarial-rollout search after a unit's validation (docs/falsify.md "In sweeps and the report"):
// search rollouts of the falsification, the coverage and the gap phase, and of the failure search (run only
// under an unreliable verdict). All 0: no search.
struct SweepFalsify {
  int budget = 0;
  int coverage_budget = 0;
  int gap_budget = 0;      // optional in the spec
  int failure_budget = 0;  // optional in the spec
  bool enabled() const { return budget + coverage_budget + gap_budget + failure_budget > 0; }
};

struct SweepTaskEntry {
  std::string spec_key;        // tasks[i]
  std::filesystem::path file;  // resolved against the spec file's folder
  std::string base_yaml;       // the task file's text
  Task base;                   // ... parsed
  std::vector<std::string> strategies;
  int n = 0;                         // rollouts per unit of this entry: its `n`, else the spec's
  SweepFalsify falsify;              // this entry's `falsify`, else the spec's
  std::vector<ParamSet> param_sets;  // grid points x random draws; one empty set without either
};

struct SweepSpec {
  std::string path;  // as given
  std::string text;  // the spec file's text (stored with each run)
  std::string description;
  int n = 0;
  std::vector<std::uint64_t> seeds;
  SampleMode mode = SampleMode::kUniform;
  // cmt validate --controller; impedance by default, as there (the verifier's own model; the admittance
  // form is verified with a widened theta_v, experiments/validation/verifier_model.h).
  ControllerForm controller = ControllerForm::kImpedance;
  int sticking_trials = 0;
  int counterexample_budget = 400;  // ValidateOptions' default
  // Wall-clock seconds a unit's verifier may take, 0 = no limit (experiments/common/verifier_budget.h):
  // beyond it the unit records "verifier: timed out after B s" and its rollouts run without a prediction.
  double verify_budget_seconds = 0;
  SweepFalsify
      falsify;  // `falsify: {budget, coverage_budget[, gap_budget][, failure_budget]}`; missing: none
  std::vector<SweepTaskEntry> tasks;
};

SweepSpec load_sweep_spec(const std::filesystem::path& path);
// `label` names the file in messages; task files are resolved against `base_dir`.
SweepSpec parse_sweep_spec(const std::string& text, const std::string& label,
                           const std::filesystem::path& base_dir);

}  // namespace cmt
