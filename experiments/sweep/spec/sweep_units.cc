#include "experiments/sweep/spec/sweep_units.h"

#include <regex>
#include <set>

#include "experiments/common/json_text.h"
#include "experiments/sweep/spec/stable_hash.h"
#include "models/input_error.h"
#include "models/task_loader.h"

namespace cmt {

namespace {

// Bumped whenever the meaning of a unit's fields changes, so old databases never match new units.
// 2: the controller form is a field (validate's default changed from admittance to impedance).
constexpr const char* kUnitKeyVersion = "cmt-sweep-unit/2";

// The spec key of the override that the task loader's complaint is about (its key path starts with the
// override's task path), else the task entry.
std::string culprit_key(const InputError& e, const ParamSet& params, const std::string& entry_key) {
  for (const ParamValue& p : params) {
    const std::string path = p.target.task_path();
    if (e.key() == path || e.key().rfind(path + ".", 0) == 0) return p.spec_key;
  }
  return entry_key;
}

}  // namespace

std::string make_unit_key(const std::string& task_yaml, const std::string& strategy, int n,
                          std::uint64_t seed, SampleMode mode, ControllerForm controller, int sticking_trials,
                          int counterexample_budget, double verify_budget_seconds, int falsify_budget,
                          int falsify_coverage_budget, int falsify_gap_budget, int falsify_failure_budget) {
  HashInput in;
  in.add(kUnitKeyVersion)
      .add(task_yaml)
      .add(strategy)
      .add(n)
      .add(std::to_string(seed))
      .add(sample_mode_name(mode))
      .add(controller_form_name(controller))
      .add(sticking_trials)
      .add(counterexample_budget)
      .add(json_text(nlohmann::json(verify_budget_seconds)));  // shortest round-trip text
  // Only with a search: the keys of units without one stay what they were before the search existed.
  if (falsify_budget + falsify_coverage_budget + falsify_gap_budget + falsify_failure_budget > 0)
    in.add("falsify").add(falsify_budget).add(falsify_coverage_budget);
  // Only with a gap or failure search: the keys of searches without one stay what they were before it
  // existed.
  if (falsify_gap_budget > 0) in.add("gap").add(falsify_gap_budget);
  if (falsify_failure_budget > 0) in.add("failure").add(falsify_failure_budget);
  return fnv1a128_hex(in.text());
}

std::vector<SweepUnit> expand_units(const SweepSpec& spec, int* duplicates) {
  std::vector<SweepUnit> units;
  std::set<std::string> keys;
  int dropped = 0;
  for (const SweepTaskEntry& entry : spec.tasks)
    for (const ParamSet& params : entry.param_sets) {
      const std::string yaml = apply_overrides(entry.base_yaml, entry.base, params);
      std::string name;
      try {
        name = parse_task_string(yaml, entry.file.string()).name;
      } catch (const InputError& e) {
        throw InputError(spec.path, culprit_key(e, params, entry.spec_key),
                         "these overrides " + json_text(params_json(params)) +
                             " make the task invalid: " + e.key() + ": " + e.reason());
      }
      for (const std::string& strategy : entry.strategies)
        for (const std::uint64_t seed : spec.seeds) {
          SweepUnit u;
          u.unit_key = make_unit_key(
              yaml, strategy, entry.n, seed, spec.mode, spec.controller, spec.sticking_trials,
              spec.counterexample_budget, spec.verify_budget_seconds, entry.falsify.budget,
              entry.falsify.coverage_budget, entry.falsify.gap_budget, entry.falsify.failure_budget);
          if (!keys.insert(u.unit_key).second) {
            ++dropped;
            continue;
          }
          u.index = static_cast<int>(units.size());
          u.task = name;
          u.task_file = entry.file.string();
          u.task_yaml = yaml;
          u.strategy = strategy;
          u.params = params_json(params);
          u.n = entry.n;
          u.seed = seed;
          u.mode = spec.mode;
          u.controller = spec.controller;
          u.sticking_trials = spec.sticking_trials;
          u.counterexample_budget = spec.counterexample_budget;
          u.verify_budget_seconds = spec.verify_budget_seconds;
          u.falsify_budget = entry.falsify.budget;
          u.falsify_coverage_budget = entry.falsify.coverage_budget;
          u.falsify_gap_budget = entry.falsify.gap_budget;
          u.falsify_failure_budget = entry.falsify.failure_budget;
          u.spec_key = entry.spec_key;
          units.push_back(std::move(u));
        }
    }
  if (duplicates != nullptr) *duplicates = dropped;
  return units;
}

Shard parse_shard(const std::string& text) {
  std::smatch m;
  if (!std::regex_match(text, m, std::regex("([0-9]{1,9})/([0-9]{1,9})")))
    throw InputError("(command line)", "--shard", "expected i/N with 0 <= i < N, got '" + text + "'");
  Shard s{std::stoi(m[1]), std::stoi(m[2])};
  if (s.count < 1 || s.index >= s.count)
    throw InputError("(command line)", "--shard", "expected i/N with 0 <= i < N, got '" + text + "'");
  return s;
}

}  // namespace cmt
