#include "models/task.h"

#include "models/task_error.h"

namespace cmt {

double meters_per_unit(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kInch:
      return 0.0254;
    case LengthUnit::kMillimeter:
      return 0.001;
    case LengthUnit::kMeter:
      return 1.0;
  }
  return 1.0;
}

const char* unit_name(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kInch:
      return "in";
    case LengthUnit::kMillimeter:
      return "mm";
    case LengthUnit::kMeter:
      return "m";
  }
  return "m";
}

bool Strategy::conditional() const {
  for (const StrategyNode& n : nodes)
    if (!n.branches.empty()) return true;
  return false;
}

Strategy Strategy::sequence(std::string name, std::vector<std::string> motions) {
  Strategy s;
  s.name = std::move(name);
  for (std::size_t i = 0; i < motions.size(); ++i) {
    StrategyNode n;
    n.motion = motions[i];
    n.parent = static_cast<int>(i) - 1;
    n.next = i + 1 < motions.size() ? static_cast<int>(i) + 1 : -1;
    s.nodes.push_back(n);
  }
  s.motions = std::move(motions);
  return s;
}

const Motion* Task::find_motion(const std::string& motion_name) const {
  for (const Motion& m : motions)
    if (m.name == motion_name) return &m;
  return nullptr;
}

const Strategy* Task::find_strategy(const std::string& strategy_name) const {
  for (const Strategy& s : strategies)
    if (s.name == strategy_name) return &s;
  return nullptr;
}

const Strategy& Task::strategy_named(const std::string& strategy_name) const {
  if (const Strategy* s = find_strategy(strategy_name)) return *s;
  throw TaskError(source_file, "strategies",
                  "unknown strategy '" + strategy_name + "' (the task has: " + strategy_names() + ")");
}

std::string Task::strategy_names() const {
  std::string names;
  for (const Strategy& s : strategies) names += (names.empty() ? "" : ", ") + s.name;
  return names;
}

}  // namespace cmt
