#include "experiments/common/task_overrides.h"

#include <yaml-cpp/yaml.h>

#include <stdexcept>

#include "experiments/common/json_text.h"

namespace cmt {

namespace {

// A number as the shortest text that reads back as the same double (nlohmann's round-trip formatting), so
// the edited task holds exactly the value the sweep drew.
YAML::Node number_node(double v) { return YAML::Node(json_text(nlohmann::json(v))); }

YAML::Node vector_node(const std::vector<double>& v) {
  YAML::Node seq(YAML::NodeType::Sequence);
  seq.SetStyle(YAML::EmitterStyle::Flow);
  for (const double x : v) seq.push_back(number_node(x));
  return seq;
}

}  // namespace

std::string ParamTarget::param_key() const {
  switch (kind) {
    case Kind::kFriction:
      return "friction";
    case Kind::kUncertainty:
      return name;
    case Kind::kMotion:
      return "motions." + name;
  }
  return "";
}

std::string ParamTarget::task_path() const {
  switch (kind) {
    case Kind::kFriction:
      return "friction";
    case Kind::kUncertainty:
      return "uncertainty." + name;
    case Kind::kMotion:
      return "motions." + name;
  }
  return "";
}

const std::vector<std::string>& uncertainty_override_keys() {
  static const std::vector<std::string> keys = {"eps_s", "eps_p", "theta_v", "theta_f", "step"};
  return keys;
}

nlohmann::json ParamValue::json() const {
  if (target.kind != ParamTarget::Kind::kMotion) return value.at(0);
  return value;
}

std::string apply_overrides(const std::string& base_yaml, const Task& base, const ParamSet& params) {
  YAML::Node root = YAML::Load(base_yaml);
  for (const ParamValue& p : params) {
    switch (p.target.kind) {
      case ParamTarget::Kind::kFriction:
        root["friction"] = number_node(p.value.at(0));
        break;
      case ParamTarget::Kind::kUncertainty:
        root["uncertainty"][p.target.name] = number_node(p.value.at(0));
        break;
      case ParamTarget::Kind::kMotion: {
        const Motion* m = base.find_motion(p.target.name);
        if (m == nullptr) throw std::logic_error("override of unknown motion '" + p.target.name + "'");
        YAML::Node motion = root["motions"][p.target.name];
        motion[m->kind == Motion::Kind::kSpring ? "spring" : "damper"] = vector_node(p.value);
        break;
      }
    }
  }
  YAML::Emitter out;
  out << root;
  return std::string(out.c_str()) + "\n";
}

nlohmann::json params_json(const ParamSet& params) {
  nlohmann::json j = nlohmann::json::object();
  for (const ParamValue& p : params) j[p.target.param_key()] = p.json();
  return j;
}

}  // namespace cmt
