// `cmt view` (docs/viewer.md) and what `cmt report` shares with it.
#pragma once

#include <memory>
#include <vector>

#include "experiments/report/results_db.h"
#include "experiments/report/view_data.h"
#include "models/loaded_task.h"

namespace cmt {

// A configuration's counterexample (a failing rollout its validation recorded), replayed from its seed, index
// and mode under the unit's controller form with the trajectory recorded; empty when there is none or the
// task has no such strategy.
std::vector<report::ViewTrajectory> replay_counterexample(std::shared_ptr<const LoadedTask> task,
                                                          const report::ConfigRow& row);

}  // namespace cmt
