// `cmt edr TASK --strategy NAME [--resolution K] [--first-order] [--check N --per-world K --seed S --threads
// T
// --check-mode M] [--json]`: one-step error detection and
// recovery under model error (Donald 1987; docs/edr.md). Slices the task's model parameters (models/
// model_error.h), runs the strategy in each slice under the rollouts' model and reports per slice the
// forward projection F, the strong and weak preimages P and P~ of the goal, the failure region H and whether
// the terminations in the goal are distinguishable from H across all slices; --check runs MuJoCo rollouts in
// N worlds drawn over the parameters' intervals (experiments/edr/edr_check.h). Exit 0: EDR-reliable (and the
// check, if run, found no forbidden outcome); 1: not; 2: bad input.
#include <chrono>
#include <iostream>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/edr/edr_check.h"
#include "experiments/validation/verifier_model.h"
#include "experiments/validation/verify_json.h"
#include "models/loaded_task.h"
#include "models/model_error.h"
#include "models/task_error.h"
#include "verifier/edr/edr.h"

namespace cmt {
namespace {

struct EdrCli {
  std::string task, strategy;
  int resolution = 5;
  bool first_order = false;
  int check = 0, per_world = 10, threads = 1;
  std::uint64_t seed = 1;
  std::string check_mode = "extreme";
};

nlohmann::json parameters_json(const Task& task, int resolution) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t p = 0; p < task.model_error.size(); ++p) {
    const ModelParameter& m = task.model_error[p];
    out.push_back({{"name", m.name},
                   {"min", m.min},
                   {"max", m.max},
                   {"nominal", m.nominal},
                   {"critical", critical_values(task, p)},
                   {"values", slice_values(task, p, resolution)}});
  }
  return out;
}

nlohmann::json slice_json(const Task& task, const EdrSlice& s) {
  nlohmann::json params = nlohmann::json::object();
  for (std::size_t p = 0; p < task.model_error.size(); ++p) params[task.model_error[p].name] = s.values[p];
  const LoadedTask& lt = *s.task;
  nlohmann::json out = {{"params", params},
                        {"goal_empty", s.goal_empty},
                        {"terminates", s.terminates},
                        {"reliable", s.reliable},
                        {"distinguishable", s.distinguishable},
                        {"contact_lift", s.options.contact_lift},
                        {"servo_coast", s.options.servo_coast}};
  if (!s.terminates) {
    out["termination_problem"] = s.termination_problem;
    return out;
  }
  out["forward"] = pieces_json(lt, s.reached->pieces());
  out["forward_area"] = s.reached->area();
  out["termination_area"] = s.termination->area();
  out["success"] = pieces_json(lt, s.success->pieces());
  out["success_area"] = s.success->area();
  out["failure"] = pieces_json(lt, s.failure_pieces);
  out["failure_area"] = s.failure_area;
  if (s.strong) {
    out["strong_preimage_area"] = s.strong->area();
    out["weak_preimage_area"] = s.weak->area();
    out["failure_sticking_area"] = s.failure_sticking_area;
  }
  return out;
}

nlohmann::json confusion_json(const EdrResult& r, const EdrConfusion& c) {
  return {{"success_slice", c.success_slice},
          {"failure_slice", c.failure_slice},
          {"success_piece", pieces_json(*r.slices[c.success_slice].task, {c.success_piece})[0]},
          {"failure_piece", pieces_json(*r.slices[c.failure_slice].task, {c.failure_piece})[0]},
          {"distance", c.distance},
          {"force_angle", c.force_angle}};
}

// The strategy's slices, checked: decision-free, a slice count within the limit.
std::vector<std::vector<double>> slices_of(const LoadedTask& task, const EdrCli& cli,
                                           const Strategy& strategy) {
  if (strategy.conditional())
    throw TaskError(cli.task, "strategies." + cli.strategy,
                    "a conditional strategy: cmt edr runs decision-free sequences (the EDR test follows the "
                    "last motion)");
  try {
    return model_slices(task.task, cli.resolution);
  } catch (const std::invalid_argument& e) {
    throw TaskError(cli.task, "--resolution", e.what());
  }
}

nlohmann::json result_json(const EdrCli& cli, const Task& task, const Strategy& strategy,
                           const EdrResult& r) {
  nlohmann::json slices = nlohmann::json::array(), confusions = nlohmann::json::array();
  for (const EdrSlice& s : r.slices) slices.push_back(slice_json(task, s));
  for (const EdrConfusion& c : r.confusions) confusions.push_back(confusion_json(r, c));
  return {{"task", task.name},
          {"strategy", cli.strategy},
          {"motions", strategy.motions},
          {"resolution", cli.resolution},
          {"model", cli.first_order ? "first-order" : "rollouts"},
          {"parameters", parameters_json(task, cli.resolution)},
          {"slices", slices},
          {"terminates", r.terminates},
          {"reaches_goal", r.reaches_goal},
          {"distinguishable", r.distinguishable},
          {"confusions", confusions},
          {"confusion_count", r.confusion_count},
          {"edr_reliable", r.edr_reliable},
          {"reason", r.reason}};
}

// --check: rollouts in worlds drawn over the parameters; true when no forbidden outcome occurred.
bool run_check(const EdrCli& cli, const Task& task, const Strategy& strategy, const EdrResult& r,
               nlohmann::json* out) {
  EdrCheckOptions o;
  o.worlds = cli.check;
  o.rollouts_per_world = cli.per_world;
  o.seed = cli.seed;
  o.threads = cli.threads;
  o.mode = cli.check_mode == "uniform" ? SampleMode::kUniform : SampleMode::kExtreme;
  const EdrCheck check = check_edr(task, strategy.motions, r, o);
  (*out)["check"] = edr_check_json(task, check);
  (*out)["check"]["mode"] = cli.check_mode;
  (*out)["check"]["seed"] = cli.seed;
  return check.false_success == 0 && check.false_failure == 0;
}

void print_text(const nlohmann::json& out) {
  for (const nlohmann::json& s : out["slices"])
    std::cout << s["params"].dump() << ": " << (s["goal_empty"].get<bool>() ? "no goal" : "goal")
              << (s["terminates"].get<bool>()
                      ? ", success area " + std::to_string(s["success_area"].get<double>()) + ", H area " +
                            std::to_string(s["failure_area"].get<double>())
                      : ", may not terminate")
              << "\n";
  std::cout << (out["edr_reliable"].get<bool>() ? "EDR-reliable"
                                                : "not EDR-reliable: " + out["reason"].get<std::string>())
            << "\n";
  if (out.contains("check")) std::cout << "check: " << out["check"]["outcomes"].dump() << "\n";
}

void run_edr(const EdrCli& cli, CommandState& state) {
  const auto start_time = std::chrono::steady_clock::now();
  const auto task = load_task_from_string(read_task_text(cli.task), cli.task);
  const Strategy& strategy = task->task.strategy_named(cli.strategy);
  const std::vector<std::vector<double>> slices = slices_of(*task, cli, strategy);
  EdrOptions options;
  if (!cli.first_order) {
    options.verify = [](const LoadedTask& slice) { return rollout_verify_options(slice); };
    options.backprojection_margin = [](const LoadedTask& slice) { return rollout_contact_lift(slice); };
  }
  const EdrResult r = verify_edr(task->task, strategy.motions, slices, options);
  nlohmann::json out = result_json(cli, task->task, strategy, r);
  const bool check_ok = cli.check == 0 || run_check(cli, task->task, strategy, r, &out);
  out["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  if (state.json)
    print_json(out);
  else
    print_text(out);
  state.exit_status = r.edr_reliable && check_ok ? kExitSuccess : 1;
}

}  // namespace

void add_edr_command(CLI::App& app, CommandState& state) {
  auto cli = std::make_shared<EdrCli>();
  auto* cmd = app.add_subcommand(
      "edr",
      "error detection and recovery under model error: is the goal recognizably reached or failure "
      "recognizably signalled in every slice? (Donald 1987)");
  cmd->add_option("TASK", cli->task, "task YAML file (with model_error)")->required();
  cmd->add_option("--strategy", cli->strategy, "a decision-free strategy of the task")->required();
  cmd->add_option("--resolution", cli->resolution,
                  "evenly spaced values per model parameter, ends included (default 5; critical values and "
                  "the midpoints between them are added)")
      ->check(CLI::Range(1, 1000));
  cmd->add_flag("--first-order", cli->first_order,
                "Buckley's first-order model (no contact lift, servo coast or slow stops) instead of the "
                "rollouts'");
  cmd->add_option("--check", cli->check,
                  "rollouts in this many worlds drawn uniformly over the model parameters (0: none)")
      ->check(CLI::Range(0, 100000));
  cmd->add_option("--per-world", cli->per_world, "rollouts per world of the check (default 10)")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--seed", cli->seed,
                  "seed of the check's worlds, rollouts and sensor readings (default 1)");
  cmd->add_option("--threads", cli->threads, "rollout threads (default 1)")->check(CLI::Range(1, 256));
  cmd->add_option("--check-mode", cli->check_mode,
                  "error sampling of the check: extreme (default) or uniform")
      ->check(CLI::IsMember({"uniform", "extreme"}));
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([cli, &state] { run_edr(*cli, state); });
}

}  // namespace cmt
