// `cmt plan TASK --states [--max-atoms K] [--friction MU] [--eps-s E] [--theta-f T] [--list] --json`: the
// primitive states of Buckley's planner (§6.4.1, Table 6.3; docs/planner.md). The planner's search is not
// built yet: without --states the command is a usage error (exit 2).
#include <chrono>
#include <iostream>
#include <optional>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/common/task_overrides.h"
#include "models/loaded_task.h"
#include "models/task_error.h"
#include "verifier/planner/primitive_states.h"

namespace cmt {
namespace {

struct PlanCli {
  std::string task;
  bool states = false, list = false;
  int max_atoms = 0;
  long long max_states = 1'000'000;
  std::optional<double> friction, eps_s, theta_f;
};

// The task with the given friction and sensing bounds written in (task_overrides.h: checked like a file).
std::shared_ptr<const LoadedTask> task_with_overrides(const PlanCli& cli) {
  const std::string text = read_task_text(cli.task);
  const auto base = load_task_from_string(text, cli.task);
  ParamSet params;
  const auto set = [&](ParamTarget::Kind kind, const std::string& name, const std::optional<double>& v,
                       const std::string& option) {
    if (v) params.push_back({{kind, name}, {*v}, option});
  };
  set(ParamTarget::Kind::kFriction, "", cli.friction, "--friction");
  set(ParamTarget::Kind::kUncertainty, "eps_s", cli.eps_s, "--eps-s");
  set(ParamTarget::Kind::kUncertainty, "theta_f", cli.theta_f, "--theta-f");
  if (params.empty()) return base;
  return load_task_from_string(apply_overrides(text, base->task, params), cli.task);
}

void run_plan(const PlanCli& cli, CommandState& state) {
  if (!cli.states)
    throw CLI::ValidationError("plan",
                               "give --states (the planner's search is not built yet; docs/planner.md)");
  const auto start = std::chrono::steady_clock::now();
  const auto task = task_with_overrides(cli);
  const CSpace& c = task->cspace;
  const Uncertainty& u = task->task.uncertainty;
  const planner::PrimitiveStates p = planner::primitive_states(c, u.eps_s, u.theta_f, cli.max_atoms,
                                                               static_cast<std::size_t>(cli.max_states));
  nlohmann::json by_size = nlohmann::json::object();
  for (std::size_t k = 1; k < p.by_size.size(); ++k) by_size[std::to_string(k)] = p.by_size[k];
  nlohmann::json out = {{"task", task->task.name},
                        {"faces", c.faces().size()},
                        {"edges", c.edges().size()},
                        {"vertices", c.vertices().size()},
                        {"atoms", p.atoms},
                        {"friction", task->task.friction},
                        {"eps_s", u.eps_s},
                        {"theta_f", u.theta_f},
                        {"max_atoms", cli.max_atoms},
                        {"primitive_states", p.states.size()},
                        {"by_size", by_size},
                        {"truncated", p.truncated},
                        {"max_states", cli.max_states}};
  if (cli.list) {
    nlohmann::json states = nlohmann::json::array();
    for (const std::vector<int>& s : p.states) {
      nlohmann::json names = nlohmann::json::array();
      for (int a : s) names.push_back(c.atom_name(a));
      states.push_back(names);
    }
    out["states"] = states;
  }
  out["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (state.json) {
    print_json(out);
  } else {
    std::cout << task->task.name << ": " << p.atoms << " atoms, " << p.states.size() << " primitive states"
              << (cli.max_atoms > 0 ? " of at most " + std::to_string(cli.max_atoms) + " atoms" : "")
              << (p.truncated ? " (truncated)" : "") << "; by size:";
    for (std::size_t k = 1; k < p.by_size.size(); ++k) std::cout << " " << k << ": " << p.by_size[k];
    std::cout << "\n";
  }
  state.exit_status = kExitSuccess;
}

}  // namespace

void add_plan_command(CLI::App& app, CommandState& state) {
  auto cli = std::make_shared<PlanCli>();
  auto* cmd = app.add_subcommand("plan", "Buckley's planner (ch. 6): its primitive states (--states)");
  cmd->add_option("TASK", cli->task, "task YAML file")->required();
  cmd->add_flag(
      "--states", cli->states,
      "count the primitive states: sets of atoms no two of which sensing can tell apart (Sec 6.4.1)");
  cmd->add_option("--max-atoms", cli->max_atoms, "only states of at most K atoms (default 0: any number)")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--max-states", cli->max_states,
                  "stop after this many states (default 10^6); truncated: true says the counts are partial")
      ->check(CLI::Range(1LL, 100'000'000LL));
  cmd->add_flag("--list", cli->list, "also list every state's atoms");
  cmd->add_option("--friction", cli->friction, "use this friction coefficient instead of the task's");
  cmd->add_option("--eps-s", cli->eps_s, "use this position-sensing error instead of the task's");
  cmd->add_option("--theta-f", cli->theta_f, "use this force-sensing error instead of the task's");
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([cli, &state] { run_plan(*cli, state); });
}

}  // namespace cmt
