#include "experiments/common/task_motions.h"

#include <yaml-cpp/yaml.h>

#include "models/input_error.h"

namespace cmt {
namespace {

YAML::Node point_yaml(const Vec3& p, const Task& task) {
  YAML::Node v(YAML::NodeType::Sequence);
  v.SetStyle(YAML::EmitterStyle::Flow);
  v.push_back(p.x());
  if (task.dimension == 3) v.push_back(p.y());
  v.push_back(p.z());
  return v;
}

// A list of `{box: {min, max}}` items (docs/task-format.md, "Termination sets").
YAML::Node boxes_yaml(const std::vector<AxisBox>& boxes, const Task& task) {
  YAML::Node list(YAML::NodeType::Sequence);
  for (const AxisBox& b : boxes) {
    YAML::Node item;
    item.SetStyle(YAML::EmitterStyle::Flow);
    item["box"]["min"] = point_yaml(b.min, task);
    item["box"]["max"] = point_yaml(b.max, task);
    list.push_back(item);
  }
  return list;
}

// A list of `{direction, angle}` cones (docs/task-format.md, "Termination sets").
YAML::Node cones_yaml(const std::vector<ForceCone>& cones, const Task& task) {
  YAML::Node list(YAML::NodeType::Sequence);
  for (const ForceCone& f : cones) {
    YAML::Node item;
    item.SetStyle(YAML::EmitterStyle::Flow);
    item["direction"] = point_yaml(f.direction, task);
    item["angle"] = f.angle;
    list.push_back(item);
  }
  return list;
}

}  // namespace

std::string task_yaml_with_motions(const std::string& task_yaml, const Task& task,
                                   const std::vector<AddedMotion>& motions, const std::string& strategy_name,
                                   const std::string& who) {
  YAML::Node root = YAML::Load(task_yaml);
  YAML::Node list(YAML::NodeType::Sequence);
  list.SetStyle(YAML::EmitterStyle::Flow);
  for (const AddedMotion& m : motions) {
    if (task.find_motion(m.name))
      throw InputError(task.source_file, "motions." + m.name, who + " motion name is taken");
    const YAML::Node v = point_yaml(m.target, task);
    YAML::Node motion;
    motion.SetStyle(YAML::EmitterStyle::Flow);
    motion[m.kind == Motion::Kind::kSpring ? "spring" : "damper"] = v;
    if (m.edr) motion["edr"] = true;
    if (!m.sensed_positions.empty()) motion["terminate"]["position"] = boxes_yaml(m.sensed_positions, task);
    if (!m.sensed_forces.empty()) motion["terminate"]["force"] = cones_yaml(m.sensed_forces, task);
    root["motions"][m.name] = motion;
    list.push_back(m.name);
  }
  if (!strategy_name.empty()) {
    if (root["strategies"] && root["strategies"][strategy_name])
      throw InputError(task.source_file, "strategies." + strategy_name, who + " strategy name is taken");
    root["strategies"][strategy_name] = list;
  }
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << root;
  return std::string(out.c_str()) + "\n";
}

std::string free_strategy_name(const Task& task, const std::string& wanted) {
  std::string name = wanted;
  for (int k = 2; task.find_strategy(name); ++k) name = wanted + "_" + std::to_string(k);
  return name;
}

}  // namespace cmt
