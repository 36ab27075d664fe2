#include "experiments/common/task_motions.h"

#include <yaml-cpp/yaml.h>

#include "models/task_error.h"

namespace cmt {

std::string task_yaml_with_motions(const std::string& task_yaml, const Task& task,
                                   const std::vector<AddedMotion>& motions, const std::string& strategy_name,
                                   const std::string& who) {
  YAML::Node root = YAML::Load(task_yaml);
  YAML::Node list(YAML::NodeType::Sequence);
  list.SetStyle(YAML::EmitterStyle::Flow);
  for (const AddedMotion& m : motions) {
    if (task.find_motion(m.name))
      throw TaskError(task.source_file, "motions." + m.name, who + " motion name is taken");
    YAML::Node v(YAML::NodeType::Sequence);
    v.SetStyle(YAML::EmitterStyle::Flow);
    v.push_back(m.target.x());
    if (task.dimension == 3) v.push_back(m.target.y());
    v.push_back(m.target.z());
    YAML::Node motion;
    motion.SetStyle(YAML::EmitterStyle::Flow);
    motion[m.kind == Motion::Kind::kSpring ? "spring" : "damper"] = v;
    if (m.edr) motion["edr"] = true;
    root["motions"][m.name] = motion;
    list.push_back(m.name);
  }
  if (!strategy_name.empty()) {
    if (root["strategies"] && root["strategies"][strategy_name])
      throw TaskError(task.source_file, "strategies." + strategy_name, who + " strategy name is taken");
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
