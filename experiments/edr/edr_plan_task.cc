#include "experiments/edr/edr_plan_task.h"

#include <yaml-cpp/yaml.h>

#include "models/task_error.h"
#include "verifier/edr/edr_plan.h"

namespace cmt {

std::string task_yaml_with_dampers(const std::string& task_yaml, const Task& task,
                                   const std::vector<Vec3>& directions, const std::string& strategy_name) {
  YAML::Node root = YAML::Load(task_yaml);
  YAML::Node list(YAML::NodeType::Sequence);
  list.SetStyle(YAML::EmitterStyle::Flow);
  for (std::size_t i = 0; i < directions.size(); ++i) {
    const std::string name = edr_plan_motion_name(static_cast<int>(i));
    if (task.find_motion(name))
      throw TaskError(task.source_file, "motions." + name, "the EDR planner's motion name is taken");
    YAML::Node v(YAML::NodeType::Sequence);
    v.SetStyle(YAML::EmitterStyle::Flow);
    v.push_back(directions[i].x());
    if (task.dimension == 3) v.push_back(directions[i].y());
    v.push_back(directions[i].z());
    YAML::Node motion;
    motion.SetStyle(YAML::EmitterStyle::Flow);
    motion["damper"] = v;
    if (i + 1 == directions.size()) motion["edr"] = true;
    root["motions"][name] = motion;
    list.push_back(name);
  }
  if (!strategy_name.empty()) root["strategies"][strategy_name] = list;
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << root;
  return std::string(out.c_str()) + "\n";
}

}  // namespace cmt
