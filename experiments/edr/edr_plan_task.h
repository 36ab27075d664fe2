// The task text with the EDR planner's damper motions added (verifier/edr/edr_plan.h TaskWithDampers): the
// YAML tree gains motions edr_plan_1, ... (the last with `edr: true`) and, when a strategy name is given,
// that strategy of them; re-read by the task loader, so every slice reads them too (Task::model_source).
#pragma once
#include <string>
#include <vector>

#include "models/task.h"

namespace cmt {

// The text (comments dropped). Throws InputError naming `motions` when a planner motion name is taken.
std::string task_yaml_with_dampers(const std::string& task_yaml, const Task& task,
                                   const std::vector<Vec3>& directions,
                                   const std::string& strategy_name = "");

}  // namespace cmt
