// `cmt teach` output (teach_json.h).
#include "experiments/teach/teach_json.h"

#include <yaml-cpp/yaml.h>

#include "experiments/common/point_json.h"
#include "experiments/validation/verify_json.h"

namespace cmt {
namespace {

// Each cell's pieces (the start set it stands for), with the chain verified from it when it is solved.
nlohmann::json cells_json(const LoadedTask& task, const std::vector<teaching::StartCell>& cells) {
  nlohmann::json out = nlohmann::json::array();
  for (const teaching::StartCell& c : cells)
    for (nlohmann::json& piece : pieces_json(task, ReachedSet::from_region(task, c.region).pieces())) {
      piece["cell"] = c.path;
      if (!c.chain.nodes.empty()) piece["chain"] = strategy_json(c.chain, task.task.dimension);
      out.push_back(std::move(piece));
    }
  return out;
}

nlohmann::json motion_json(const Motion& m, int dimension) {
  return {{"name", m.name},
          {"kind", m.kind == Motion::Kind::kSpring ? "spring" : "damper"},
          {"commanded", point_json(m.target, dimension)}};
}

YAML::Node coordinates(const Vec3& v, int dimension) {
  YAML::Node out(YAML::NodeType::Sequence);
  out.SetStyle(YAML::EmitterStyle::Flow);
  out.push_back(v.x());
  if (dimension == 3) out.push_back(v.y());
  out.push_back(v.z());
  return out;
}

// The sensing test of a branch in the task format: `position` boxes, `force` cones.
template <typename Tree, typename Vector, typename Leaf, typename Sequence>
Tree test_tree(const MotionTermination& when, int dimension, Vector vector, Leaf leaf, Sequence sequence) {
  Tree test = leaf();
  if (!when.position.empty()) {
    Tree boxes = sequence(false);
    for (const AxisBox& b : when.position) {
      Tree box = leaf(), corners = leaf();
      corners["min"] = vector(b.min, dimension);
      corners["max"] = vector(b.max, dimension);
      box["box"] = corners;
      boxes.push_back(box);
    }
    test["position"] = boxes;
  }
  if (!when.force.empty()) {
    Tree cones = sequence(false);
    for (const ForceCone& f : when.force) {
      Tree cone = leaf();
      cone["direction"] = vector(f.direction, dimension);
      cone["angle"] = f.angle;
      cones.push_back(cone);
    }
    test["force"] = cones;
  }
  return test;
}

// The list of the strategy from node `node` on, in the task format (JSON or YAML); `sequence` makes an
// empty list (a branch that stops is `[]`).
template <typename Tree, typename Vector, typename Leaf, typename Sequence>
Tree strategy_list(const Strategy& s, int node, int dimension, Vector vector, Leaf leaf, Sequence sequence) {
  Tree list = sequence(true);
  for (; node >= 0; node = s.nodes[static_cast<std::size_t>(node)].next) {
    const StrategyNode& n = s.nodes[static_cast<std::size_t>(node)];
    list.push_back(n.motion);
    if (n.branches.empty()) continue;
    Tree branches = sequence(false);
    for (const StrategyBranch& b : n.branches) {
      Tree branch = leaf();
      Tree body = strategy_list<Tree>(s, b.first, dimension, vector, leaf, sequence);
      if (b.otherwise) {
        branch["else"] = body;
      } else {
        branch["when"] = test_tree<Tree>(b.when, dimension, vector, leaf, sequence);
        branch["then"] = body;
      }
      branches.push_back(branch);
    }
    Tree item = leaf();
    item["branch"] = branches;
    Tree block = sequence(false);  // a list that holds a branch is written in block style
    for (const auto& motion : list) block.push_back(motion);
    block.push_back(item);
    return block;
  }
  return list;
}

YAML::Node strategy_node(const Strategy& strategy, int dimension) {
  const auto leaf = [] { return YAML::Node(YAML::NodeType::Map); };
  const auto sequence = [](bool flow) {
    YAML::Node list(YAML::NodeType::Sequence);
    if (flow) list.SetStyle(YAML::EmitterStyle::Flow);
    return list;
  };
  return strategy_list<YAML::Node>(strategy, strategy.nodes.empty() ? -1 : 0, dimension, coordinates, leaf,
                                   sequence);
}

}  // namespace

nlohmann::json strategy_json(const Strategy& strategy, int dimension) {
  const auto leaf = [] { return nlohmann::json::object(); };
  const auto sequence = [](bool) { return nlohmann::json::array(); };
  return strategy_list<nlohmann::json>(strategy, strategy.nodes.empty() ? -1 : 0, dimension, point_json, leaf,
                                       sequence);
}

nlohmann::json teach_step_json(const teaching::Session& session, const teaching::TeachStep& step) {
  const LoadedTask& task = session.task();
  const Motion* m = task.task.find_motion(step.motion);
  nlohmann::json out = {{"motion", step.motion},
                        {"commanded", motion_json(*m, task.task.dimension)},
                        {"chain", strategy_json(step.chain, task.task.dimension)},
                        {"solved_regions", cells_json(task, step.solved)},
                        {"start_remaining", cells_json(task, step.remaining)},
                        {"solved_measure", step.solved_measure},
                        {"remaining_measure", step.remaining_measure},
                        {"verifications", step.verifications},
                        {"dispatches", step.dispatches},
                        {"seconds", step.seconds}};
  out["stops_from_solved"] = pieces_json(task, step.stops_from_solved);
  if (!step.remaining.empty()) {
    out["stops_from_remaining"] = pieces_json(task, step.stops_from_remaining);
    out["failure"] = step.failure;
    out["blocking"] = pieces_json(task, step.blocking);
    out["unchecked_reason_atoms"] = step.unchecked_reason_atoms;
  }
  return out;
}

nlohmann::json teach_json(const teaching::Session& session, double seconds) {
  nlohmann::json steps = nlohmann::json::array();
  for (const teaching::TeachStep& s : session.steps()) steps.push_back(teach_step_json(session, s));
  const auto strategy = session.strategy();
  return {{"task", session.task().task.name},
          {"solved", session.solved() && strategy.has_value()},
          {"start_solved", session.solved()},
          {"steps", steps},
          {"strategy",
           strategy ? strategy_json(*strategy, session.task().task.dimension) : nlohmann::json(nullptr)},
          {"seconds", seconds}};
}

namespace {

YAML::Node taught_task_node(const std::string& task_yaml, const teaching::Session& session,
                            const Strategy& strategy, const std::string& strategy_name) {
  YAML::Node root = YAML::Load(task_yaml);
  const int dimension = session.task().task.dimension;
  for (const Motion& m : session.inline_motions()) {
    YAML::Node motion;
    motion[m.kind == Motion::Kind::kSpring ? "spring" : "damper"] = coordinates(m.target, dimension);
    root["motions"][m.name] = motion;
  }
  root["strategies"][strategy_name] = strategy_node(strategy, dimension);
  return root;
}

std::string emit(const YAML::Node& root) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << root;
  return std::string(out.c_str()) + "\n";
}

}  // namespace

std::string taught_task_yaml(const std::string& task_yaml, const teaching::Session& session,
                             const Strategy& strategy, const std::string& strategy_name) {
  return emit(taught_task_node(task_yaml, session, strategy, strategy_name));
}

namespace {
void set_start(YAML::Node& root, const Region& start, int dimension) {
  YAML::Node region;
  if (start.kind == Region::Kind::kPoint) {
    region["point"] = coordinates(start.points.front(), dimension);
  } else {
    YAML::Node points(YAML::NodeType::Sequence);
    for (const Vec3& p : start.points) points.push_back(coordinates(p, dimension));
    region[start.kind == Region::Kind::kSegment ? "segment" : "polygon"] = points;
  }
  root["start"] = region;
}
}  // namespace

std::string cell_task_yaml(const std::string& task_yaml, const teaching::Session& session,
                           const Strategy& strategy, const std::string& strategy_name, const Region& start) {
  YAML::Node root = taught_task_node(task_yaml, session, strategy, strategy_name);
  set_start(root, start, session.task().task.dimension);
  return emit(root);
}

std::string strategy_task_yaml(const std::string& task_yaml, int dimension,
                               const std::vector<std::string>& strategy, const std::string& strategy_name,
                               const Region& start) {
  YAML::Node root = YAML::Load(task_yaml);
  YAML::Node list(YAML::NodeType::Sequence);
  list.SetStyle(YAML::EmitterStyle::Flow);
  for (const std::string& name : strategy) list.push_back(name);
  root["strategies"][strategy_name] = list;
  set_start(root, start, dimension);
  return emit(root);
}

}  // namespace cmt
