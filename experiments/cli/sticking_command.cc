#include "experiments/cli/sticking_command.h"

#include <chrono>
#include <iostream>
#include <map>
#include <memory>
#include <utility>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "models/input_error.h"
#include "verifier/atom_cone.h"
#include "verifier/damper.h"
#include "verifier/spring.h"

namespace cmt {
namespace {

nlohmann::json polygon_json(const std::vector<Vec3>& pts, int dimension) {
  nlohmann::json out = nlohmann::json::array();
  for (const Vec3& p : pts) out.push_back(point_json(p, dimension));
  return out;
}

}  // namespace

nlohmann::json sticking_json(const LoadedTask& task, const Motion& motion) {
  const auto start = std::chrono::steady_clock::now();
  const CSpace& c = task.cspace;
  const Uncertainty& u = task.task.uncertainty;
  const int dim = task.task.dimension;
  const bool spring = motion.kind == Motion::Kind::kSpring;
  nlohmann::json atoms = nlohmann::json::array();
  nlohmann::json faces = nlohmann::json::array();
  int counts[3] = {0, 0, 0};
  const AtomCones cones(c);
  for (int id = 0; id < c.atom_count(); ++id) {
    StickClass cls;
    if (spring)
      cls = classify_spring(spring_sticking_regions(c, id, u), motion.target);
    else
      cls = classify_damper(cones, id, motion.target, u.theta_v);
    ++counts[static_cast<int>(cls)];
    atoms.push_back({{"atom", id},
                     {"name", c.atom_name(id)},
                     {"kind", atom_kind_name(c.atom_kind(id))},
                     {"class", stick_class_name(cls)}});
  }
  for (const Face& f : c.faces()) {
    nlohmann::json entry = {{"atom", f.id}};
    if (spring) {
      const auto conf = face_sticking_configurations(f, motion.target, u);
      entry["weak"] = polygon_json(conf.weak, dim);
      entry["strong"] = polygon_json(conf.strong, dim);
    } else {
      const SlidingCone s = sliding_cone(f.normal, f.friction, motion.target, u.theta_v);
      entry["sliding"] = {{"possible", s.possible}, {"all", s.all}, {"half_angle", s.half_angle}};
      if (s.possible && !s.all) entry["sliding"]["axis"] = point_json(s.axis, dim);
    }
    faces.push_back(entry);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {{"task", task.task.name},
          {"motion", motion.name},
          {"model", spring ? "spring" : "damper"},
          {"eps_t", eps_t(u)},
          {"counts", {{"must", counts[0]}, {"may", counts[1]}, {"never", counts[2]}}},
          {"atoms", atoms},
          {"faces", faces},
          {"seconds", seconds}};
}

report::StickClassOf verifier_stick_classes() {
  // Keyed by the task's address and the motion: the classes of all atoms are computed once per pair.
  auto cache =
      std::make_shared<std::map<std::pair<const LoadedTask*, std::string>, std::map<int, std::string>>>();
  return [cache](const LoadedTask& task, const std::string& motion, int atom) -> std::string {
    auto [it, fresh] = cache->try_emplace({&task, motion});
    const Motion* m = task.task.find_motion(motion);
    if (fresh && m) {
      const nlohmann::json classes = sticking_json(task, *m);
      for (const auto& a : classes["atoms"]) it->second[a["atom"].get<int>()] = a["class"].get<std::string>();
    }
    const auto cls = it->second.find(atom);
    return cls == it->second.end() ? "unknown" : cls->second;
  };
}

void add_sticking_command(CLI::App& app, CommandState& state) {
  struct Options {
    std::string task, motion;
  };
  auto options = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("sticking", "Stick/slide classification of every atom under one motion");
  cmd->add_option("TASK", options->task, "task YAML file")->required();
  cmd->add_option("--motion", options->motion, "motion name (from the task's motions)")->required();
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([options, &state] {
    const auto task = load_task(options->task);
    const Motion* motion = task->task.find_motion(options->motion);
    if (!motion)
      throw InputError(task->task.source_file, "motions", "no motion named '" + options->motion + "'");
    const nlohmann::json j = sticking_json(*task, *motion);
    if (state.json) {
      print_json(j);
    } else {
      std::cout << task->task.name << " / " << motion->name << " (" << j["model"].get<std::string>()
                << "): must " << j["counts"]["must"] << ", may " << j["counts"]["may"] << ", never "
                << j["counts"]["never"] << "\n";
      for (const auto& a : j["atoms"])
        std::cout << "  " << a["name"].get<std::string>() << " " << a["kind"].get<std::string>() << " "
                  << a["class"].get<std::string>() << "\n";
    }
    state.exit_status = kExitSuccess;
  });
}

}  // namespace cmt
