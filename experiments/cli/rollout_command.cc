// cmt rollout: Monte Carlo rollouts of a strategy in MuJoCo (sim/rollout.h, docs/rollouts.md).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <thread>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/cli/rollout_cli.h"
#include "models/input_error.h"
#include "sim/error_vector.h"
#include "sim/rollout.h"

namespace cmt {

namespace {

std::string atom_kind_or_free(const CSpace& c, int atom) {
  return atom < 0 ? "free" : atom_kind_name(c.atom_kind(atom));
}

nlohmann::json motion_json(const LoadedTask& task, const MotionOutcome& m) {
  const int dim = task.task.dimension;
  return {{"motion", m.motion},
          {"end", point_json(m.end, dim)},
          {"atom", m.atom},
          {"atom_name", m.atom < 0 ? "free" : task.cspace.atom_name(m.atom)},
          {"kind", atom_kind_or_free(task.cspace, m.atom)},
          {"termination", termination_name(m.termination)},
          {"contact_force", {m.contact_force.x(), m.contact_force.y(), m.contact_force.z()}},
          {"sim_time", m.sim_time},
          {"steps", m.steps},
          {"max_penetration", m.max_penetration},
          {"velocity_switches", m.velocity_switches},
          {"replans", m.replans},
          {"node", m.node},
          {"branch", m.branch}};
}

nlohmann::json outcome_json(const LoadedTask& task, const RolloutOutcome& r) {
  const int dim = task.task.dimension;
  nlohmann::json motions = nlohmann::json::array();
  for (const MotionOutcome& m : r.motions) motions.push_back(motion_json(task, m));
  nlohmann::json j = {{"index", r.index},
                      {"start", point_json(r.start, dim)},
                      {"end", point_json(r.end, dim)},
                      {"atom", r.atom},
                      {"atom_name", r.atom < 0 ? "free" : task.cspace.atom_name(r.atom)},
                      {"kind", atom_kind_or_free(task.cspace, r.atom)},
                      {"termination", termination_name(r.termination)},
                      {"success", r.success},
                      {"unstable", r.unstable},
                      {"motions", motions}};
  if (r.unstable) j["unstable_reason"] = r.unstable_reason;
  if (r.no_branch) j["no_branch"] = true;  // a conditional test passed no branch (no 'else')
  return j;
}

void write_csv(const std::filesystem::path& file, const LoadedTask& task,
               const std::vector<RolloutOutcome>& rs) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write CSV file '" + file.string() + "'");
  out.precision(17);
  out << "rollout,success,unstable,start_x,start_y,start_z,motion_index,motion,end_x,end_y,end_z,atom,atom_"
         "name,"
         "kind,termination,contact_force_x,contact_force_y,contact_force_z,sim_time,steps,max_penetration\n";
  for (const RolloutOutcome& r : rs)
    for (std::size_t i = 0; i < r.motions.size(); ++i) {
      const MotionOutcome& m = r.motions[i];
      out << r.index << ',' << r.success << ',' << r.unstable << ',' << r.start.x() << ',' << r.start.y()
          << ',' << r.start.z() << ',' << i << ',' << m.motion << ',' << m.end.x() << ',' << m.end.y() << ','
          << m.end.z() << ',' << m.atom << ',' << (m.atom < 0 ? "free" : task.cspace.atom_name(m.atom)) << ','
          << atom_kind_or_free(task.cspace, m.atom) << ',' << termination_name(m.termination) << ','
          << m.contact_force.x() << ',' << m.contact_force.y() << ',' << m.contact_force.z() << ','
          << m.sim_time << ',' << m.steps << ',' << m.max_penetration << '\n';
    }
  if (!out) throw std::runtime_error("cannot write CSV file '" + file.string() + "': write failed");
}

void write_trajectories(const std::filesystem::path& file, const std::vector<RolloutOutcome>& rs) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write trajectory file '" + file.string() + "'");
  out.precision(10);
  out << "rollout,time,motion,x,y,z,sensed_x,sensed_y,sensed_z,contact\n";
  for (const RolloutOutcome& r : rs)
    for (const TrajectoryPoint& p : r.trajectory)
      out << r.index << ',' << p.time << ',' << p.motion << ',' << p.position.x() << ',' << p.position.y()
          << ',' << p.position.z() << ',' << p.sensed.x() << ',' << p.sensed.y() << ',' << p.sensed.z() << ','
          << p.contact << '\n';
  if (!out) throw std::runtime_error("cannot write trajectory file '" + file.string() + "': write failed");
}

// The `cmt rollout --json` object (docs/contracts.md): the run's settings, counts and totals, every outcome.
struct RolloutRun {
  const LoadedTask& task;
  const RolloutScene& scene;
  const Strategy& strategy;
  SimOptions options;
  std::uint64_t seed = 0;
  int threads = 1;
  double seconds = 0;
};

nlohmann::json rollouts_json(const RolloutRun& run, const std::vector<RolloutOutcome>& results) {
  int successes = 0, unstable = 0;
  long steps = 0;
  double max_penetration = 0, sim_time = 0;
  std::map<std::string, int> terminations, end_atoms;
  nlohmann::json outcomes = nlohmann::json::array();
  for (const RolloutOutcome& r : results) {
    successes += r.success;
    unstable += r.unstable;
    ++terminations[termination_name(r.termination)];
    ++end_atoms[r.atom < 0 ? "free" : run.task.cspace.atom_name(r.atom)];
    for (const MotionOutcome& m : r.motions) {
      steps += m.steps;
      sim_time += m.sim_time;
      max_penetration = std::max(max_penetration, m.max_penetration);
    }
    outcomes.push_back(outcome_json(run.task, r));
  }
  const int n = static_cast<int>(results.size());
  return {
      {"task", run.task.task.name},
      {"strategy", run.strategy.name},
      {"controller", controller_form_name(run.options.form)},
      {"mode", sample_mode_name(run.options.mode)},
      {"seed", run.seed},
      {"threads", run.threads},
      {"rollouts", n},
      {"successes", successes},
      {"failures", n - successes - unstable},
      {"unstable", unstable},
      {"success_rate", static_cast<double>(successes) / n},
      {"terminations", terminations},
      {"end_atoms", end_atoms},
      {"max_penetration", max_penetration},
      {"max_penetration_m", max_penetration * run.scene.meters_per_unit()},
      {"atom_tolerance", run.scene.atom_tolerance()},
      {"timestep", run.scene.timestep()},
      {"sim_time", sim_time},
      {"steps", steps},
      {"seconds", run.seconds},
      {"steps_per_second", run.seconds > 0 ? steps / run.seconds : 0.0},
      {"outcomes", outcomes},
  };
}

// A one-line progress bar, redrawn in place (only when stderr is a terminal).
void draw_progress(int done, int total, std::chrono::steady_clock::time_point start) {
  const int width = 40;
  const int filled = total > 0 ? width * done / total : width;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "\r[%s%s] %d/%d rollouts, %.1f s", std::string(filled, '#').c_str(),
               std::string(width - filled, ' ').c_str(), done, total, seconds);
  std::fflush(stderr);
}

// One rollout under an error vector (sim/error_vector.h); a bad vector is an input error (exit status 2).
RolloutOutcome run_error_vector(std::shared_ptr<const RolloutScene> scene, const Strategy& strategy,
                                const std::string& text) {
  const Task& task = scene->task().task;
  const bool position = scene->options().form == ControllerForm::kPosition;
  std::vector<double> vector;
  std::optional<ErrorVectorLayout> layout;
  try {
    vector = parse_error_vector(text);
    layout.emplace(task, strategy,
                   shape_of_vector(task, strategy, static_cast<int>(vector.size()), position,
                                   scene->options().damper_speed_per_scale));
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("--errors", e.what());
  }
  ScriptedErrors errors(task, *layout, std::move(vector));
  RolloutRunner runner(std::move(scene));
  return runner.run(strategy, errors, 0);
}

struct RolloutCli {
  std::string task, strategy, mode = "uniform", controller = "admittance", csv, trajectories, errors;
  std::vector<std::string> world;
  int n = 100;
  std::uint64_t seed = 1;
  int threads = 0;
};

// The simulation options the flags ask for; --controller position takes springs only.
SimOptions rollout_sim_options(const RolloutCli& o, const LoadedTask& task, const Strategy& strategy) {
  SimOptions options;
  options.form = *parse_controller_form(o.controller);
  options.mode = *parse_sample_mode(o.mode);
  options.record_trajectory = !o.trajectories.empty();
  if (options.form == ControllerForm::kPosition)
    for (const std::string& name : strategy.motions) {
      const Motion* m = task.task.find_motion(name);
      if (m != nullptr && m->kind == Motion::Kind::kDamper)
        throw InputError(task.task.source_file, "motions." + name,
                         "--controller position implements generalized springs only (Buckley eq. 3.25); '" +
                             name + "' is a damper");
    }
  return options;
}

// The rollouts (sampled, or the one --errors vector), with a progress bar on a terminal.
std::vector<RolloutOutcome> run_rollout_batch(const RolloutCli& o,
                                              const std::shared_ptr<const RolloutScene>& scene,
                                              const Strategy& strategy, int threads) {
  const auto start = std::chrono::steady_clock::now();
  std::function<void(int)> progress;
  const bool bar = isatty(STDERR_FILENO);
  if (bar) progress = [&](int done) { draw_progress(done, o.n, start); };
  std::vector<RolloutOutcome> results =
      o.errors.empty() ? run_rollouts(scene, strategy, o.n, o.seed, threads, progress)
                       : std::vector<RolloutOutcome>{run_error_vector(scene, strategy, o.errors)};
  if (bar) std::fprintf(stderr, "\n");
  return results;
}

void run_rollout_command(RolloutCli o, CommandState& state) {
  if (!o.errors.empty()) o.n = 1;
  check_rollout_sampling_options(o.n, o.threads);
  const auto task = task_in_world(load_task(o.task), o.world);
  const Strategy& strategy = task->task.strategy_named(o.strategy);
  const SimOptions options = rollout_sim_options(o, *task, strategy);
  const int threads =
      o.threads > 0 ? o.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const auto start = std::chrono::steady_clock::now();
  const auto scene = RolloutScene::build(task, options);
  const std::vector<RolloutOutcome> results = run_rollout_batch(o, scene, strategy, threads);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (!o.csv.empty()) write_csv(o.csv, *task, results);
  if (!o.trajectories.empty()) write_trajectories(o.trajectories, results);
  nlohmann::json j = rollouts_json({*task, *scene, strategy, options, o.seed, threads, seconds}, results);
  if (!o.errors.empty()) j["errors"] = o.errors;
  const int successes = j["successes"], unstable = j["unstable"];
  if (state.json) {
    print_json(j);
  } else {
    std::cout << task->task.name << " / " << strategy.name << " (" << controller_form_name(options.form)
              << ", " << sample_mode_name(options.mode) << ", seed " << o.seed << "): " << successes << "/"
              << o.n << " succeeded, " << unstable << " unstable, " << seconds << " s\n";
  }
  state.exit_status = successes == o.n ? kExitSuccess : kExitFailureFound;
}

}  // namespace

void add_rollout_command(CLI::App& app, CommandState& state) {
  auto o = std::make_shared<RolloutCli>();
  auto* cmd = app.add_subcommand("rollout", "Monte Carlo MuJoCo rollouts of a strategy under sampled errors");
  cmd->add_option("TASK", o->task, "task YAML file")->required();
  cmd->add_option("--strategy", o->strategy, "strategy name (from the task file)")->required();
  add_rollout_sampling_options(cmd, o->n, o->seed, o->threads, o->mode);
  cmd->add_option(
         "--controller", o->controller,
         "controller form: admittance (Buckley eq. 3.23/3.24), impedance, or position (eq. 3.25, springs)")
      ->check(CLI::IsMember({"admittance", "impedance", "position"}))
      ->capture_default_str();
  cmd->add_option(
         "--world", o->world,
         "NAME=VALUE (repeatable): run in the world with these model-error values (docs/task-format.md "
         "\"model_error\"; others at their nominal values)")
      ->allow_extra_args(false);
  cmd->add_option("--csv", o->csv, "also write one CSV row per rollout and motion to this file");
  cmd->add_option("--trajectories", o->trajectories,
                  "also record trajectories (every 10 steps) to this CSV file");
  cmd->add_option("--errors", o->errors,
                  "run one rollout under this error vector (comma-separated numbers in [0, 1], as `cmt "
                  "falsify` prints them; docs/falsify.md) instead of sampled errors");
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([o, &state] { run_rollout_command(*o, state); });
}

}  // namespace cmt
