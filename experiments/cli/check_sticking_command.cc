// `cmt check-sticking TASK -n N --seed S [--threads T] --json`: the physics check of the stick/slide
// classification (experiments/validation/sticking_check.h). Exit status 1 when any trial disagrees.
#include <algorithm>
#include <iostream>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/validation/sticking_check.h"
#include "models/task_error.h"

namespace cmt {

void add_check_sticking_command(CLI::App& app, CommandState& state) {
  struct Options {
    std::string task;
    int n = 2000;
    std::uint64_t seed = 1;
    int threads = 2;
    std::vector<std::string> kinds;
    std::string scene = "soft-layer";
  };
  auto options = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("check-sticking", "Check the damper stick/slide classes against MuJoCo");
  cmd->add_option("TASK", options->task, "task YAML file")->required();
  cmd->add_option("-n", options->n, "number of trials")->check(CLI::PositiveNumber);
  cmd->add_option("--seed", options->seed, "master seed");
  cmd->add_option("--threads", options->threads, "worker threads")->check(CLI::PositiveNumber);
  cmd->add_option("--kinds", options->kinds, "atom kinds to test (face, edge, vertex; default all)")
      ->check(CLI::IsMember({"face", "edge", "vertex"}));
  cmd->add_option("--scene", options->scene,
                  "MuJoCo scene: soft-layer (default: the rollouts' calibrated scene, Coulomb at concave "
                  "edges), rollout (the same scene) or stiff (sim/rollout.h stiff_scene: stiff contact, off "
                  "Coulomb in concave edges)")
      ->check(CLI::IsMember({"soft-layer", "rollout", "stiff"}));
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([options, &state] {
    const auto task = load_task(options->task);
    AtomKindFilter kinds;
    if (!options->kinds.empty()) {
      auto has = [&](const char* k) {
        return std::find(options->kinds.begin(), options->kinds.end(), k) != options->kinds.end();
      };
      kinds = {has("face"), has("edge"), has("vertex")};
    }
    SimOptions sim;  // the rollouts' Coulomb-calibrated scene
    if (options->scene == "stiff") sim.scene = stiff_scene();
    const StickingCheckResult r =
        check_sticking(task, options->n, options->seed, options->threads, kinds, sim);
    nlohmann::json j = sticking_check_json(*task, r);
    j["scene"] = options->scene;
    j.erase("records");  // per-trial records are for reports (sweeps); the CLI prints the summary
    if (state.json)
      print_json(j);
    else
      std::cout << task->task.name << ": " << r.trials << " trials, " << r.disagreements
                << " disagreements (must " << r.must << ", may " << r.may << " of which " << r.may_stuck
                << " stuck, never " << r.never << ")"
                << (r.unstable > 0 ? ", " + std::to_string(r.unstable) + " unstable (not classified)"
                                   : std::string())
                << "\n";
    state.exit_status = r.disagreements == 0 ? kExitSuccess : kExitFailureFound;
  });
}

}  // namespace cmt
