#include "experiments/sweep/sweep_executor.h"

#include <map>
#include <memory>
#include <utility>

#include "experiments/common/json_text.h"
#include "experiments/falsify/falsify.h"
#include "experiments/results/unit_record_json.h"
#include "experiments/validation/verify_json.h"

namespace cmt {

namespace {

std::array<double, 3> xyz(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

std::string falsify_record(std::shared_ptr<const LoadedTask> task, const SweepUnit& unit,
                           const ValidationResult& v, int threads) {
  FalsifyOptions f;
  f.budget = unit.falsify_budget;
  f.coverage_budget = unit.falsify_coverage_budget;
  f.gap_budget = unit.falsify_gap_budget;
  f.failure_budget = unit.falsify_failure_budget;
  f.mode = unit.mode;  // the baseline's: the validation's rollouts
  f.seed = unit.seed;
  f.threads = threads;
  f.form = unit.controller;
  const Strategy& strategy = task->task.strategy_named(unit.strategy);
  nlohmann::json j = falsify_json(*task, run_falsify(task, strategy, v.prediction, f, v.rollouts));
  j.erase("threads");  // the result does not depend on it; the stored unit should not either
  return json_text(j);
}

UnitRecord unit_record(const LoadedTask& task, const ValidationResult& v) {
  UnitRecord r;
  r.reliable = v.prediction.reliable;
  r.failure = v.prediction.failure;
  r.verify_seconds = v.verify_seconds;
  r.verify_json = json_text(verify_json(task, v.prediction, v.verify_seconds));
  r.verifier_theta_v = v.verifier.theta_v;
  r.verifier_model = json_text(verifier_model_json(v.verifier));

  std::map<std::pair<int, int>, const ObservedEnd*> ends;
  for (const ObservedEnd& e : v.ends) ends[{e.rollout, e.motion}] = &e;
  for (const RolloutOutcome& ro : v.rollouts) {
    RolloutRow base;
    base.rollout = ro.index;
    base.success = ro.success;
    base.unstable = ro.unstable;
    if (ro.motions.empty()) {  // ended before any motion did: one row for the rollout itself
      RolloutRow row = base;
      row.motion = -1;
      row.start = xyz(ro.start);
      row.end = xyz(ro.end);
      row.atom = ro.atom;
      row.termination = termination_name(ro.termination);
      r.rollouts.push_back(row);
      continue;
    }
    for (std::size_t i = 0; i < ro.motions.size(); ++i) {
      const MotionOutcome& m = ro.motions[i];
      RolloutRow row = base;
      row.motion = motion_key(v.prediction.steps, m, static_cast<int>(i));
      row.start = xyz(i == 0 ? ro.start : ro.motions[i - 1].end);
      row.end = xyz(m.end);
      row.atom = m.atom;
      row.termination = termination_name(m.termination);
      if (const auto it = ends.find({ro.index, row.motion}); it != ends.end()) {
        row.inside = it->second->inside;
        row.distance = it->second->distance;
      }
      r.rollouts.push_back(row);
    }
  }

  r.rollout_count = static_cast<int>(v.rollouts.size());
  r.successes = v.successes;
  r.unstable = v.unstable;
  r.ends = static_cast<int>(v.ends.size());
  r.outside = v.outside;
  r.soundness = v.soundness;
  r.coverage = v.coverage;
  r.coverage_radius = v.coverage_radius;
  r.contact_tolerance = v.contact_tolerance;
  r.soundness_bug = v.soundness_bug;
  if (v.counterexample) r.counterexample = json_text(counterexample_json(task, *v.counterexample));
  if (v.sticking) r.sticking = json_text(sticking_check_json(task, *v.sticking));
  r.rollout_seconds = v.rollout_seconds;
  return r;
}

UnitExecutor make_validation_executor() {
  struct Cache {
    std::string yaml;
    std::shared_ptr<const LoadedTask> task;
  };
  auto cache = std::make_shared<Cache>();
  return [cache](const SweepUnit& unit, int threads) {
    if (!cache->task || cache->yaml != unit.task_yaml) {
      cache->task = load_task_from_string(unit.task_yaml, unit.task_file);
      cache->yaml = unit.task_yaml;
    }
    ValidateOptions options;
    options.n = unit.n;
    options.seed = unit.seed;
    options.threads = threads;
    options.mode = unit.mode;
    options.form = unit.controller;
    options.sticking_trials = unit.sticking_trials;
    options.counterexample_budget = unit.counterexample_budget;
    // The validation, then (with a falsify budget and a prediction) the adversarial search against that
    // prediction with the validation's rollouts as its baseline: both in the child under a verifier budget.
    const auto validate = [&](const ValidateOptions& o) {
      const ValidationResult v = run_validation(cache->task, unit.strategy, o);
      UnitRecord record = unit_record(*cache->task, v);
      if (unit.falsify_budget + unit.falsify_coverage_budget + unit.falsify_gap_budget +
                  unit.falsify_failure_budget >
              0 &&
          o.verifier_timed_out_after <= 0)
        record.falsify = falsify_record(cache->task, unit, v, threads);
      return record;
    };
    if (unit.verify_budget_seconds <= 0) return validate(options);
    // The record comes back from the child process as text, bit for bit.
    return unit_record_from_text(validate_with_verifier_budget(
        unit.verify_budget_seconds, options,
        [&](const ValidateOptions& o) { return unit_record_to_text(validate(o)); }));
  };
}

}  // namespace cmt
