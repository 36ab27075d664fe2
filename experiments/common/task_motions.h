// A task's text with planned motions added (the EDR planner's dampers, Buckley's planner's springs): the YAML
// tree gains the motions and, when a strategy name is given, a decision-free strategy of them; the text is
// meant to be read again by the task loader, which checks it like a hand-written file.
#pragma once

#include <string>
#include <vector>

#include "models/task.h"

namespace cmt {

struct AddedMotion {
  std::string name;
  Motion::Kind kind = Motion::Kind::kSpring;
  Vec3 target = Vec3::Zero();             // damper: direction; spring: commanded position (task units)
  bool edr = false;                       // marks the motion whose termination the EDR report reads
  std::vector<AxisBox> sensed_positions;  // `terminate: {position: ...}` when not empty (type 2)
  std::vector<ForceCone> sensed_forces;   // `terminate: {force: ...}` when not empty (type 3)
};

// The text (comments dropped). Throws InputError naming `motions.NAME` when a motion name is taken, or
// `strategies.NAME` when the strategy name is; `who` names the program that chose the names.
std::string task_yaml_with_motions(const std::string& task_yaml, const Task& task,
                                   const std::vector<AddedMotion>& motions, const std::string& strategy_name,
                                   const std::string& who);

// `wanted`, or wanted_2, wanted_3, ...: the first name no strategy of the task has.
std::string free_strategy_name(const Task& task, const std::string& wanted);

}  // namespace cmt
