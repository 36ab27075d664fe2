// Reading teaching session files (session_file.h).
#include "experiments/teach/session_file.h"

#include <fstream>
#include <sstream>

#include "models/input_error.h"
#include "models/task_ranges.h"
#include "models/yaml_document.h"
#include "models/yaml_node.h"

namespace cmt {
namespace {

Vec3 parse_vector(const YamlNode& n, int dimension) {
  const std::vector<double> v = n.numbers();
  if (static_cast<int>(v.size()) != dimension)
    n.fail("expected " + std::to_string(dimension) + " numbers, got " + std::to_string(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i)
    if (std::abs(v[i]) > kMaxCoordinate)
      n.item(i).fail(
          "magnitude exceeds the largest accepted coordinate (docs/task-format.md \"Accepted ranges "
          "and sizes\")");
  return dimension == 2 ? Vec3(v[0], 0, v[1]) : Vec3(v[0], v[1], v[2]);
}

SessionStep parse_step(const YamlNode& item, const Task& task) {
  SessionStep step;
  if (!item.is_map()) {
    step.motion = item.string();
    if (!task.find_motion(step.motion))
      item.fail("no motion named '" + step.motion + "' in the task" +
                (task.motions.empty() ? "" : " (it has: " + [&] {
                  std::string names;
                  for (const Motion& m : task.motions) names += (names.empty() ? "" : ", ") + m.name;
                  return names;
                }() + ")"));
    return step;
  }
  item.require_map({"spring", "damper", "name"});
  if (item.has("spring") == item.has("damper"))
    item.fail("an inline motion is exactly one of spring, damper");
  Motion m;
  if (item.has("name")) {
    m.name = item.at("name").string();
    if (m.name.empty()) item.at("name").fail("the name is empty");
    if (task.find_motion(m.name))
      item.at("name").fail("the task already has a motion named '" + m.name + "'");
    if (m.name.rfind("taught_", 0) == 0)
      item.at("name").fail("names taught_... are kept for the inline motions without a name");
  }
  if (item.has("spring")) {
    m.kind = Motion::Kind::kSpring;
    m.target = parse_vector(item.at("spring"), task.dimension);
  } else {
    m.kind = Motion::Kind::kDamper;
    const Vec3 d = parse_vector(item.at("damper"), task.dimension);
    if (!(d.norm() >= kMinDirectionLength))
      item.at("damper").fail("the commanded velocity direction is zero");
    m.target = d.normalized();
  }
  step.inline_motion = m;
  return step;
}

}  // namespace

std::vector<SessionStep> parse_session(const std::string& yaml_text, const std::string& label,
                                       const Task& task) {
  const YAML::Node root_node = load_yaml_document(yaml_text, label);
  const YamlNode root(root_node, "", &label);
  if (!root_node.IsDefined() || root_node.IsNull()) root.fail("the file is empty");
  if (!root.is_map()) root.fail("expected a map with the key 'steps'");
  root.require_map({"steps", "description"});
  if (!root.has("steps")) root.fail("missing key 'steps'");
  const YamlNode steps = root.at("steps").list();
  if (steps.size() > kMaxMotions) steps.fail("more than " + std::to_string(kMaxMotions) + " steps");
  std::vector<SessionStep> out;
  for (std::size_t i = 0; i < steps.size(); ++i) out.push_back(parse_step(steps.item(i), task));
  for (std::size_t i = 0; i < out.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (out[i].inline_motion && out[j].inline_motion && !out[i].inline_motion->name.empty() &&
          out[i].inline_motion->name == out[j].inline_motion->name)
        steps.item(i).at("name").fail("the name '" + out[i].inline_motion->name + "' is used by step " +
                                      std::to_string(j));
  return out;
}

std::vector<SessionStep> load_session(const std::filesystem::path& path, const Task& task) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), "", "cannot open the teaching session file");
  std::stringstream text;
  text << in.rdbuf();
  return parse_session(text.str(), path.string(), task);
}

std::string session_step_yaml(const SessionStep& step, int dimension) {
  if (!step.inline_motion) return step.motion;
  const Motion& m = *step.inline_motion;
  std::ostringstream out;
  out.precision(17);
  out << "{" << (m.kind == Motion::Kind::kSpring ? "spring" : "damper") << ": [" << m.target.x() << ", ";
  if (dimension == 3) out << m.target.y() << ", ";
  out << m.target.z() << "]";
  if (!m.name.empty()) out << ", name: " << m.name;
  out << "}";
  return out.str();
}

}  // namespace cmt
