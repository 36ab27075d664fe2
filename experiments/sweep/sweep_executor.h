// The real executor of a sweep unit: load the unit's task text, run the validation
// (experiments/validation/validation.h) and turn its result into the rows of the results store.
#pragma once

#include <memory>
#include <string>

#include "experiments/results/results_store.h"
#include "experiments/sweep/sweep_runner.h"
#include "experiments/validation/validation.h"

namespace cmt {

// predictions, rollouts (one row per motion of every rollout) and metrics rows of a validation.
UnitRecord unit_record(const LoadedTask& task, const ValidationResult& result);

// The adversarial-rollout search of a unit (docs/falsify.md "In sweeps and the report") against the
// validation's prediction, with the validation's rollouts as its baseline: the `cmt falsify --json` object
// without `threads`, as text (UnitRecord::falsify).
std::string falsify_record(std::shared_ptr<const LoadedTask> task, const SweepUnit& unit,
                           const ValidationResult& validation, int threads);

// Loads each unit's task (reusing the last one: consecutive units of a sweep share their task text) and
// validates the unit's strategy with its n, seed, mode, controller form, sticking trials and counterexample
// budget; with a falsify budget and a verifier that did not time out, then runs falsify_record.
UnitExecutor make_validation_executor();

}  // namespace cmt
