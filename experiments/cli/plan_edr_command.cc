// `cmt plan-edr TASK [--coarse K] [--fine K] [--max-motions M] [--min-motions M] [--angle-step A]
// [--angle-steps N] [--guaranteed] [--first-order] [-o OUT.yaml] --json` (docs/contracts.md): LIMITED's
// generate-and-test search for an EDR strategy of one or two damper motions (verifier/edr/edr_plan.h,
// docs/edr.md "Planning"). `found`, `strategy` (the planned motions' names), `motions` (name, commanded),
// `verdicts` (coarse verdicts computed), `guaranteed` (success guaranteed in every slice with a goal),
// `verdict` (the fine slices' `cmt edr` object) or `reason`; -o writes the task with the plan added as a
// strategy. Exit 0 found, 1 not, 2 bad input.
#include <chrono>
#include <fstream>
#include <iostream>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/common/point_json.h"
#include "experiments/common/task_motions.h"
#include "experiments/edr/edr_plan_task.h"
#include "experiments/edr/edr_verdict.h"
#include "experiments/validation/verifier_model.h"
#include "models/input_error.h"
#include "models/model_error.h"
#include "models/task_loader.h"
#include "verifier/edr/edr_plan.h"

namespace cmt {
namespace {

struct PlanEdrCli {
  std::string task, out;
  EdrPlanOptions options;
  bool first_order = false;
};

nlohmann::json plan_json(const PlanEdrCli& cli, const Task& task, const std::string& text,
                         const EdrPlan& plan, double seconds) {
  nlohmann::json out = {{"task", task.name}, {"found", plan.found}, {"verdicts", plan.verdicts}};
  if (!plan.found) {
    out["reason"] = plan.reason;
    out["strategy"] = nullptr;
    out["seconds"] = seconds;
    return out;
  }
  const std::string name = free_strategy_name(task, "plan_edr");
  const std::string planned = task_yaml_with_dampers(text, task, plan.directions, name);
  const Task planned_task = parse_task_string(planned, cli.task);
  nlohmann::json motions = nlohmann::json::array();
  for (std::size_t i = 0; i < plan.directions.size(); ++i)
    motions.push_back({{"name", edr_plan_motion_name(static_cast<int>(i))},
                       {"commanded", point_json(plan.directions[i], task.dimension)}});
  EdrVerdictRequest request;
  request.file = cli.task;
  request.strategy = name;
  request.resolution = cli.options.fine_resolution;
  request.first_order = cli.first_order;
  out["strategy"] = planned_task.strategy_named(name).motions;
  out["strategy_name"] = name;
  out["motions"] = motions;
  out["guaranteed"] = guaranteed_where_goal_exists(plan.verdict);
  out["verdict"] = edr_verdict_json(planned_task, request, plan.verdict);
  if (!cli.out.empty()) {
    std::ofstream file(cli.out);
    if (!(file << planned)) throw InputError(cli.out, "-o", "cannot write the planned task");
    out["written"] = cli.out;
  }
  out["seconds"] = seconds;
  return out;
}

void run_plan_edr(const PlanEdrCli& cli, CommandState& state) {
  const auto start = std::chrono::steady_clock::now();
  const std::string text = read_task_text(cli.task);
  const auto task = load_task_from_string(text, cli.task);
  EdrPlanOptions options = cli.options;
  if (!cli.first_order) {
    options.edr.verify = [](const LoadedTask& slice) { return rollout_verify_options(slice); };
    options.edr.backprojection_margin = [](const LoadedTask& slice) { return rollout_contact_lift(slice); };
  }
  const TaskWithDampers with_dampers = [&](const std::vector<Vec3>& directions) {
    return parse_task_string(task_yaml_with_dampers(text, task->task, directions), cli.task);
  };
  for (const auto& [resolution, option] :
       {std::pair{options.coarse_resolution, "--coarse"}, std::pair{options.fine_resolution, "--fine"}}) {
    try {
      model_slices(task->task, resolution);
    } catch (const std::invalid_argument& e) {  // too many slices
      throw InputError(cli.task, option, e.what());
    }
  }
  const EdrPlan plan = plan_edr(task->task, with_dampers, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::json out = plan_json(cli, task->task, text, plan, seconds);
  if (state.json) {
    print_json(out);
  } else if (plan.found) {
    std::cout << "found: " << out["strategy"].dump() << " " << out["motions"].dump() << "\n";
  } else {
    std::cout << "not found: " << plan.reason << "\n";
  }
  state.exit_status = plan.found ? kExitSuccess : 1;
}

}  // namespace

void add_plan_edr_command(CLI::App& app, CommandState& state) {
  auto cli = std::make_shared<PlanEdrCli>();
  auto* cmd = app.add_subcommand(
      "plan-edr", "search for an EDR strategy of one or two damper motions under model error (Donald 1987)");
  cmd->add_option("TASK", cli->task, "task YAML file (with model_error)")->required();
  cmd->add_option("--coarse", cli->options.coarse_resolution, "slice resolution of the search (default 2)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--fine", cli->options.fine_resolution,
                  "slice resolution a candidate is re-verified at (default 5)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--min-motions", cli->options.min_motions, "1 or 2 (default 1)")->check(CLI::Range(1, 2));
  cmd->add_option("--max-motions", cli->options.max_motions, "1 or 2 (default 2)")->check(CLI::Range(1, 2));
  cmd->add_option("--angle-step", cli->options.angle_step,
                  "radians between candidate directions (default 0.2618, 15 degrees)")
      ->check(CLI::Range(0.01, 1.6));
  cmd->add_option("--angle-steps", cli->options.angle_steps, "candidates on each side (default 6)")
      ->check(CLI::Range(0, 50));
  cmd->add_option("--budget", cli->options.max_verdicts,
                  "coarse verdicts before giving up (default 400; the fine re-verifications are not counted)")
      ->check(CLI::Range(1, 100000));
  cmd->add_flag("--guaranteed", cli->options.guaranteed,
                "accept only plans guaranteed to succeed in every slice where the goal exists");
  cmd->add_flag("--first-order", cli->first_order, "Buckley's first-order model instead of the rollouts'");
  cmd->add_option("-o", cli->out, "write the task with the plan added as a strategy");
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([cli, &state] {
    if (cli->options.min_motions > cli->options.max_motions)
      throw CLI::ValidationError("--min-motions", "must be <= --max-motions");
    if (cli->options.angle_steps * cli->options.angle_step > 3.1416)
      throw CLI::ValidationError("--angle-steps", "--angle-steps x --angle-step must be at most pi");
    run_plan_edr(*cli, state);
  });
}

}  // namespace cmt
