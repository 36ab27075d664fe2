// The units of work of a sweep (docs/sweeps.md): one validation of one strategy on one task (with its
// parameter overrides written in) for one seed. Each unit has a stable key, the hash of everything that
// determines its result, so a rerun into the same results database recognises finished work.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/sweep/spec/sweep_spec.h"

namespace cmt {

struct SweepUnit {
  int index = 0;  // position in the spec's expansion; shards partition by it
  std::string unit_key;
  std::string task;       // the task's name
  std::string task_file;  // resolved path of the task file
  std::string task_yaml;  // the task text after the overrides (what is validated)
  std::string strategy;
  nlohmann::json params = nlohmann::json::object();  // the overrides, {param_key: value}
  int n = 0;
  std::uint64_t seed = 0;
  SampleMode mode = SampleMode::kUniform;
  ControllerForm controller = ControllerForm::kImpedance;
  int sticking_trials = 0;
  int counterexample_budget = 0;
  double verify_budget_seconds = 0;  // 0 = no limit (experiments/common/verifier_budget.h)
  // The adversarial-rollout search after the validation (docs/falsify.md "In sweeps and the report"); all
  // three 0: none.
  int falsify_budget = 0;
  int falsify_coverage_budget = 0;
  int falsify_gap_budget = 0;
  int falsify_failure_budget = 0;  // the failure search (under an unreliable verdict only)
  std::string spec_key;            // tasks[i], for messages
};

// Hash of the task text after overrides, strategy, n, seed, mode, controller form, sticking trials,
// counterexample budget and verifier time budget (a format-version tag first; fnv1a128_hex, 32 hex digits).
// The time budget is in it because a unit's result can depend on it (a timed-out verifier). The falsify
// budgets are added only when their sum is > 0, and the gap and failure budgets only when each is > 0, so
// units without a search keep the keys they had before it existed (existing databases resume).
std::string make_unit_key(const std::string& task_yaml, const std::string& strategy, int n,
                          std::uint64_t seed, SampleMode mode, ControllerForm controller, int sticking_trials,
                          int counterexample_budget, double verify_budget_seconds = 0, int falsify_budget = 0,
                          int falsify_coverage_budget = 0, int falsify_gap_budget = 0,
                          int falsify_failure_budget = 0);

// Every unit of the spec: tasks in spec order, then parameter sets (grid, then random draws), strategies and
// seeds (innermost). A unit whose key repeats an earlier one (the same values listed twice) is dropped and
// counted in `duplicates`. Throws InputError naming the spec key of an override that makes the task invalid.
std::vector<SweepUnit> expand_units(const SweepSpec& spec, int* duplicates = nullptr);

// --shard i/N: unit k belongs to shard (k mod N).
struct Shard {
  int index = 0;
  int count = 1;
  bool contains(int unit_index) const { return unit_index % count == index; }
  std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
};
// Parses "i/N" with 0 <= i < N; throws InputError(option, "--shard", reason) otherwise.
Shard parse_shard(const std::string& text);

}  // namespace cmt
