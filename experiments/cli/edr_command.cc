// `cmt edr TASK --strategy NAME [--resolution K] [--refine D] [--first-order] [--check N --per-world K --seed
// S --threads T --check-mode M] [--json]`: one-step error detection and recovery under model error (Donald
// 1987; docs/edr.md). Slices the task's model parameters (models/ model_error.h), runs the strategy in each
// slice under the rollouts' model and reports per slice the forward projection F, the strong and weak
// preimages P and P~ of the goal, the failure region H and whether the terminations in the goal are
// distinguishable from H across all slices; --check runs MuJoCo rollouts in N worlds drawn over the
// parameters' intervals (experiments/edr/edr_check.h). Exit 0: EDR-reliable (and the check, if run, found no
// forbidden outcome and no end outside a world's prediction); 1: not; 2: bad input.
#include <chrono>
#include <cstdint>
#include <iostream>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/edr/edr_check.h"
#include "experiments/edr/edr_verdict.h"
#include "models/loaded_task.h"

namespace cmt {
namespace {

constexpr std::int64_t kMaxCheckRollouts = 1000000;

struct EdrCli {
  std::string task, strategy;
  int resolution = 5;
  int refine_depth = EdrVerdictRequest{}.refine_depth;
  bool first_order = false;
  int check = 0, per_world = 10, threads = 1;
  std::uint64_t seed = 1;
  std::string check_mode = "extreme";
};

// --check: rollouts in worlds drawn over the parameters; true when no forbidden outcome occurred.
bool run_check(const EdrCli& cli, const Task& task, const EdrResult& r, nlohmann::json* out) {
  EdrCheckOptions o;
  o.rollouts = cli.check * cli.per_world;  // at most 10^6 (the options' check)
  o.rollouts_per_world = cli.per_world;
  o.seed = cli.seed;
  o.threads = cli.threads;
  o.mode = cli.check_mode == "uniform" ? SampleMode::kUniform : SampleMode::kExtreme;
  const EdrCheck check = check_edr(task, cli.strategy, r, o);
  (*out)["check"] = edr_check_json(task, check);
  (*out)["check"]["mode"] = cli.check_mode;
  (*out)["check"]["seed"] = cli.seed;
  return check.false_success == 0 && check.false_failure == 0 && check.outside == 0;
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
  if (static_cast<std::int64_t>(cli.check) * cli.per_world > kMaxCheckRollouts)
    throw CLI::ValidationError("--check", "--check x --per-world must be at most " +
                                              std::to_string(kMaxCheckRollouts) + " rollouts");
  const auto start_time = std::chrono::steady_clock::now();
  const auto task = load_task_from_string(read_task_text(cli.task), cli.task);
  EdrVerdictRequest request;
  request.file = cli.task;
  request.strategy = cli.strategy;
  request.resolution = cli.resolution;
  request.refine_depth = cli.refine_depth;
  request.first_order = cli.first_order;
  const EdrResult r = edr_verdict(*task, request);
  nlohmann::json out = edr_verdict_json(task->task, request, r);
  const bool check_ok = cli.check == 0 || run_check(cli, task->task, r, &out);
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
  cmd->add_option(
         "--refine", cli->refine_depth,
         "bisections of adjacent slices where one has a goal and the other not, or where the midpoint's "
         "terminations leave the pair's sweep (docs/edr.md \"Between slices\"; one continuous "
         "parameter; 0: none)")
      ->check(CLI::Range(0, 10))
      ->capture_default_str();
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
