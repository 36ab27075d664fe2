#include "experiments/edr/edr_plan_task.h"

#include "experiments/common/task_motions.h"
#include "verifier/edr/edr_plan.h"

namespace cmt {

std::string task_yaml_with_dampers(const std::string& task_yaml, const Task& task,
                                   const std::vector<Vec3>& directions, const std::string& strategy_name) {
  std::vector<AddedMotion> motions;
  for (std::size_t i = 0; i < directions.size(); ++i)
    motions.push_back({edr_plan_motion_name(static_cast<int>(i)),
                       Motion::Kind::kDamper,
                       directions[i],
                       i + 1 == directions.size(),
                       {},
                       {}});
  return task_yaml_with_motions(task_yaml, task, motions, strategy_name, "the EDR planner's");
}

}  // namespace cmt
