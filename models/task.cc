#include "models/task.h"

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

}  // namespace cmt
