// The real executor of a sweep unit: load the unit's task text, run the validation
// (experiments/validation/validation.h) and turn its result into the rows of the results store.
#pragma once

#include "experiments/results/results_store.h"
#include "experiments/sweep/sweep_runner.h"
#include "experiments/validation/validation.h"

namespace cmt {

// predictions, rollouts (one row per motion of every rollout) and metrics rows of a validation.
UnitRecord unit_record(const LoadedTask& task, const ValidationResult& result);

// Loads each unit's task (reusing the last one: consecutive units of a sweep share their task text) and
// validates the unit's strategy with its n, seed, mode, controller form, sticking trials and counterexample
// budget.
UnitExecutor make_validation_executor();

}  // namespace cmt
