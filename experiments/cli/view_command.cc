// `cmt view TASK [--strategy NAME] [--results DB --config K] [--rollouts N] -o DIR [--json]`: a
// self-contained 3-D page of a task (docs/viewer.md): its C-space, start and goal; with --strategy the
// verifier's predicted termination sets; with --results the prediction and the observed motion ends that a
// sweep recorded for configuration K; with --rollouts N also N rollouts' trajectories (impedance form,
// uniform errors, seeded). Writes DIR/index.html and its assets beside it.
#include "experiments/cli/view_command.h"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <thread>

#include "controllers/controller.h"
#include "controllers/error_model.h"
#include "controllers/termination.h"
#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/cli/sticking_command.h"
#include "experiments/cli/verify_command.h"
#include "experiments/report/predicted_sets.h"
#include "experiments/report/results_db.h"
#include "experiments/report/view_data.h"
#include "experiments/report/view_page.h"
#include "experiments/validation/verifier_model.h"
#include "models/input_error.h"
#include "sim/rollout.h"

namespace cmt {
namespace {

struct ViewOptions {
  std::string task, strategy, results, out_dir;
  long long config = -1;
  int rollouts = 0;
  unsigned long long seed = 1;
  double time_limit = kDefaultVerifyTimeLimit;
};

// The configuration's row of a results database; its task must be the one given (the page draws the
// configuration's own task text, with its parameter overrides).
report::ConfigRow config_row(const ViewOptions& o, const Task& task) {
  report::ResultsDb db = report::read_results_db(o.results);
  for (report::ConfigRow& c : db.configs) {
    if (c.config_id != o.config) continue;
    if (c.task != task.name)
      throw InputError(o.results, "--config",
                       "configuration " + std::to_string(o.config) + " is of task '" + c.task + "', not '" +
                           task.name + "'");
    return std::move(c);
  }
  throw InputError(o.results, "--config", "no configuration " + std::to_string(o.config));
}

// A recorded rollout as the page draws it: its sampled path, then its end.
report::ViewTrajectory view_trajectory(const RolloutOutcome& r) {
  report::ViewTrajectory t{r.index, r.success, {}};
  for (const TrajectoryPoint& p : r.trajectory) t.points.push_back(p.position);
  t.points.push_back(r.end);
  return t;
}

std::vector<report::ViewTrajectory> run_trajectories(std::shared_ptr<const LoadedTask> task,
                                                     const Strategy& strategy, const ViewOptions& o) {
  SimOptions sim;
  sim.form = ControllerForm::kImpedance;
  sim.record_trajectory = true;
  const auto outcomes = run_rollouts(RolloutScene::build(task, sim), strategy, o.rollouts, o.seed,
                                     static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  std::vector<report::ViewTrajectory> out;
  for (const RolloutOutcome& r : outcomes) {
    out.push_back(view_trajectory(r));
  }
  return out;
}

}  // namespace

std::vector<report::ViewTrajectory> replay_counterexample(std::shared_ptr<const LoadedTask> task,
                                                          const report::ConfigRow& row) {
  const Strategy* found = task->task.find_strategy(row.strategy);
  if (!found || !row.metrics || !row.metrics->counterexample.is_object()) return {};
  const Strategy& strategy = *found;
  const nlohmann::json& cx = row.metrics->counterexample;
  // A counterexample without its stream (seed, index) cannot be replayed; the report still shows its text.
  if (!cx.contains("seed") || !cx["seed"].is_number_unsigned() || !cx.contains("index") ||
      !cx["index"].is_number_integer())
    return {};
  SimOptions sim;
  sim.form = parse_controller_form(row.controller).value_or(ControllerForm::kImpedance);
  sim.mode = parse_sample_mode(cx.value("mode", std::string("uniform"))).value_or(SampleMode::kUniform);
  sim.record_trajectory = true;
  RolloutRunner runner(RolloutScene::build(task, sim));
  const RolloutOutcome r =
      runner.run(strategy, cx.at("seed").get<std::uint64_t>(), cx.at("index").get<int>());
  return {view_trajectory(r)};
}

namespace {

nlohmann::json run_view(const ViewOptions& o, bool* reliable) {
  const auto start = std::chrono::steady_clock::now();
  std::shared_ptr<const LoadedTask> task = load_task(o.task);
  std::optional<report::ConfigRow> row;
  if (!o.results.empty()) {
    row = config_row(o, task->task);
    task = load_task_from_string(
        row->task_yaml, o.results + " configs.task_yaml (config_id " + std::to_string(o.config) + ")");
  }
  const std::string strategy_name = row ? row->strategy : o.strategy;
  nlohmann::json verify;
  if (row && row->prediction) verify = row->prediction->verify_json;
  std::optional<Strategy> strategy;
  if (!strategy_name.empty()) strategy = task->task.strategy_named(strategy_name);
  if (strategy && verify.is_null()) {
    const VerifyOptions options = rollout_verify_options(*task);
    verify = verify_json_within_time_limit(*task, *strategy, options, o.time_limit, false, start);
    if (verify.contains("error")) throw InputError(o.task, "--strategy", verify["error"].get<std::string>());
  }
  std::optional<report::PredictedSets> prediction;
  if (!verify.is_null()) prediction = report::parse_predicted_sets(verify, task->task.dimension);
  *reliable = prediction && prediction->reliable;

  report::ViewInput input;
  input.task = task.get();
  input.title = task->task.name + (strategy_name.empty() ? "" : " / " + strategy_name);
  if (strategy) input.motions = strategy->motions;
  input.prediction = prediction ? &*prediction : nullptr;
  input.ends = row ? &row->rollouts : nullptr;
  input.stick_class = verifier_stick_classes();
  if (strategy && o.rollouts > 0) input.trajectories = run_trajectories(task, *strategy, o);
  if (row) input.counterexample = replay_counterexample(task, *row);
  const nlohmann::json data = report::view_data(input);
  report::write_view_assets(o.out_dir);
  report::write_view_page(data, std::filesystem::path(o.out_dir) / "index.html", ".");
  nlohmann::json summary = {{"page", (std::filesystem::path(o.out_dir) / "index.html").string()},
                            {"task", task->task.name},
                            {"layers", nlohmann::json::array()}};
  if (!strategy_name.empty()) summary["strategy"] = strategy_name;
  if (prediction) summary["reliable"] = prediction->reliable;
  for (const auto& layer : data["layers"]) {
    std::size_t items = 0;
    for (const char* k : {"polygons", "segments", "points", "polylines", "spheres"}) items += layer[k].size();
    summary["layers"].push_back({{"id", layer["id"]}, {"name", layer["name"]}, {"items", items}});
  }
  return summary;
}

}  // namespace

void add_view_command(CLI::App& app, CommandState& state) {
  auto o = std::make_shared<ViewOptions>();
  auto* cmd =
      app.add_subcommand("view", "Write an interactive 3-D page of a task, its prediction and outcomes");
  cmd->add_option("TASK", o->task, "task YAML file")->required();
  auto* strategy = cmd->add_option("--strategy", o->strategy, "verify this strategy and draw its prediction");
  auto* results = cmd->add_option("--results", o->results, "results database of cmt sweep");
  auto* config =
      cmd->add_option("--config", o->config, "configuration id in --results (cmt report lists them)");
  results->needs(config);
  config->needs(results);
  strategy->excludes(results);
  cmd->add_option("--rollouts", o->rollouts, "also run this many rollouts and draw their trajectories")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--seed", o->seed, "seed of those rollouts");
  cmd->add_option("--time-limit", o->time_limit, "wall-clock seconds the verifier may run")
      ->check(CLI::PositiveNumber);
  cmd->add_option("-o,--output", o->out_dir, "output directory (created if missing)")->required();
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([o, &state] {
    if (o->rollouts > 0 && o->strategy.empty() && o->results.empty())
      throw CLI::ValidationError("view", "--rollouts needs --strategy or --results");
    bool reliable = false;
    const nlohmann::json summary = run_view(*o, &reliable);
    if (state.json) {
      print_json(summary);
    } else {
      std::cout << "view: " << summary["page"].get<std::string>() << " (" << summary["layers"].size()
                << " layers)\n";
    }
    state.exit_status = kExitSuccess;
  });
}

}  // namespace cmt
