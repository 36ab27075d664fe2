// `cmt validate TASK --strategy NAME -n N --seed S [--threads T] [--mode uniform|extreme]
// [--controller impedance|admittance|position] [--sticking-trials K] [--ends] [--time-limit T] --json`: the
// verifier's prediction against MuJoCo rollouts (experiments/validation/validation.h, docs/validation.md).
// Exit 0 when physics agrees with the prediction, 1 when it contradicts it (an end outside the predicted set,
// a failure of a strategy verified reliable, a stick/slide disagreement), 2 on bad input. The verifier runs
// under the wall-clock limit T, as in `cmt verify`: past it the rollouts run without a prediction
// (verifier_timed_out: true). With --edr: an EDR strategy in worlds drawn over the model parameters
// (validate_edr.h).
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/cli/rollout_cli.h"
#include "experiments/cli/validate_edr.h"
#include "experiments/cli/verify_command.h"
#include "experiments/common/json_text.h"
#include "experiments/validation/validation.h"
#include "models/input_error.h"

namespace cmt {
namespace {

std::string point(const Vec3& p) {
  std::ostringstream os;
  os << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return os.str();
}

void print_summary(std::ostream& os, const ValidationResult& r) {
  os << r.task << " / " << r.strategy << ": verifier says "
     << (r.prediction.reliable ? "reliable" : "NOT reliable") << "; " << r.successes << "/"
     << r.rollouts.size() << " rollouts succeeded (" << r.unstable << " unstable)\n"
     << "  soundness " << r.soundness << " (" << r.outside << " of " << r.ends.size()
     << " motion ends outside the predicted sets, tolerance " << r.contact_tolerance << ")\n"
     << "  coverage " << r.coverage << " (radius " << r.coverage_radius << ")\n"
     << "  verifier theta_v " << r.verifier.theta_v << ": " << r.verifier.reason << "\n";
  if (r.options.verifier_timed_out_after > 0) os << "  " << r.prediction.failure << "\n";
  for (const ObservedEnd& e : r.worst)
    os << "  outside: rollout " << e.rollout << " motion " << r.prediction.steps[e.motion].motion << " end "
       << point(e.end) << " at distance " << e.distance << "\n";
  if (!r.unexpected_timeouts.empty())
    os << "  " << r.unexpected_timeouts.size()
       << " motions timed out where the verifier predicted termination\n";
  if (r.search.ran) os << "  search: " << r.search.note << "\n";
  if (r.soundness_bug) os << "  SOUNDNESS BUG: verified reliable, yet a rollout failed\n";
  if (r.counterexample)
    os << "  counterexample (" << r.counterexample->how << "): " << r.counterexample->replay << "\n";
  if (r.sticking)
    os << "  sticking: " << r.sticking->trials << " trials, " << r.sticking->disagreements << " disagreements"
       << (r.sticking->unstable > 0 ? ", " + std::to_string(r.sticking->unstable) + " unstable"
                                    : std::string())
       << "\n";
}

// What the command prints and its exit status, made in the process that ran the validation.
struct ValidateOutput {
  std::string out, err;
  int exit_status = kExitSuccess;
};

ValidateOutput render(const LoadedTask& task, const ValidationResult& r, bool json, bool with_ends) {
  std::ostringstream out, err;
  if (r.soundness_bug)
    err << "\n*** SOUNDNESS BUG: the verifier says '" << r.strategy << "' is reliable, but rollout "
        << r.counterexample->index << " failed. Replay it with:\n***   " << r.counterexample->replay
        << "\n\n";
  if (r.outside > 0)
    err << "*** " << r.outside << " motion ends lie outside the predicted termination sets (farthest "
        << r.worst.front().distance << ")\n";
  if (json) {
    out << json_text(validation_json(task, r, with_ends), 2) << "\n";
  } else {
    print_summary(out, r);
  }
  return {out.str(), err.str(), contradicts_verifier(r) ? kExitFailureFound : kExitSuccess};
}

// The validation under the verifier's time limit (validate_with_verifier_budget), rendered where it ran. A
// InputError there comes back whole (file, key, reason, place), so bad input still names its key.
ValidateOutput validate_within_time_limit(const std::shared_ptr<const LoadedTask>& task,
                                          const std::string& strategy, const ValidateOptions& options,
                                          double time_limit, bool json, bool with_ends) {
  const nlohmann::json payload =
      nlohmann::json::parse(validate_with_verifier_budget(time_limit, options, [&](const ValidateOptions& o) {
        try {
          const ValidateOutput v = render(*task, run_validation(task, strategy, o), json, with_ends);
          return json_text({{"out", v.out}, {"err", v.err}, {"exit_status", v.exit_status}});
        } catch (const InputError& e) {
          return json_text({{"task_error",
                             {{"file", e.file()},
                              {"key", e.key()},
                              {"reason", e.reason()},
                              {"line", e.where().line},
                              {"column", e.where().column}}}});
        }
      }));
  if (payload.contains("task_error")) {
    const nlohmann::json& e = payload["task_error"];
    throw InputError(e["file"], e["key"], e["reason"], TextLocation{e["line"], e["column"]});
  }
  return {payload["out"], payload["err"], payload["exit_status"]};
}

}  // namespace

void add_validate_command(CLI::App& app, CommandState& state) {
  struct Options {
    std::string task, strategy, mode = "uniform", controller = "impedance";
    int n = 1000, threads = 0, sticking_trials = 0, budget = ValidateOptions{}.counterexample_budget;
    double time_limit = kDefaultVerifyTimeLimit;
    std::uint64_t seed = 1;
    bool ends = false, edr = false, spring_coast = true;
    int per_world = ValidateEdrOptions{}.per_world, resolution = ValidateEdrOptions{}.resolution;
    int refine_depth = ValidateEdrOptions{}.refine_depth;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("validate", "Compare the verifier's prediction with MuJoCo rollouts");
  cmd->add_option("TASK", o->task, "task YAML file")->required();
  cmd->add_option("--strategy", o->strategy, "strategy name (from the task file)")->required();
  add_rollout_sampling_options(cmd, o->n, o->seed, o->threads, o->mode);
  cmd->add_option("--controller", o->controller,
                  "controller form: impedance (default; the verifier's model), admittance (verified with "
                  "theta_v widened by the sensed-force error), or position (springs)")
      ->check(CLI::IsMember({"admittance", "impedance", "position"}))
      ->capture_default_str();
  cmd->add_option("--sticking-trials", o->sticking_trials,
                  "also run this many stick/slide trials (cmt check-sticking) and add the per-atom table")
      ->capture_default_str();
  cmd->add_option("--search-budget", o->budget,
                  "extra rollouts for the counterexample search when the verifier says unreliable and no "
                  "rollout failed")
      ->capture_default_str();
  cmd->add_flag("--ends", o->ends, "list every observed motion end in the JSON");
  cmd->add_flag(
      "--spring-coast,!--no-spring-coast", o->spring_coast,
      "bound spring flights for the servo coast (docs/verifier.md \"Servo coast of springs\"; the default); "
      "--no-spring-coast: their first-order flights");
  cmd->add_option("--time-limit", o->time_limit,
                  "wall-clock seconds the verifier may run (default " +
                      std::to_string(kDefaultVerifyTimeLimit) +
                      "); beyond, the rollouts run without a prediction (verifier_timed_out: true)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--edr", o->edr,
                "error detection and recovery under model error (docs/edr.md): rollouts in worlds drawn over "
                "the model parameters, each classified by the last motion's EDR termination predicate");
  cmd->add_option("--per-world", o->per_world, "with --edr: rollouts per drawn world")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--resolution", o->resolution,
                  "with --edr: the verifier's slices, evenly spaced values per model parameter (cmt edr)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--refine", o->refine_depth,
                  "with --edr: bisections between adjacent slices (cmt edr --refine, docs/edr.md \"Between "
                  "slices\"; 0: none)")
      ->check(CLI::Range(0, 10))
      ->capture_default_str();
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([o, &state] {
    check_rollout_sampling_options(o->n, o->threads);
    const int threads =
        o->threads > 0 ? o->threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    if (o->edr) {
      if (o->controller != "impedance")
        throw CLI::ValidationError("--controller", "--edr runs the impedance form (the verifier's model)");
      if (o->sticking_trials > 0 || o->ends)
        throw CLI::ValidationError("--edr", "--sticking-trials and --ends are for a task's nominal world");
      ValidateEdrOptions edr;
      edr.task = o->task;
      edr.strategy = o->strategy;
      edr.rollouts = o->n;
      edr.per_world = o->per_world;
      edr.resolution = o->resolution;
      edr.refine_depth = o->refine_depth;
      edr.threads = threads;
      edr.seed = o->seed;
      edr.mode = *parse_sample_mode(o->mode);
      edr.json = state.json;
      state.exit_status = validate_edr(edr);
      return;
    }
    if (o->sticking_trials < 0)
      throw CLI::ValidationError("--sticking-trials",
                                 "must be >= 0, got " + std::to_string(o->sticking_trials));
    if (o->budget < 0)
      throw CLI::ValidationError("--search-budget", "must be >= 0, got " + std::to_string(o->budget));
    const auto task = load_task_from_string(read_task_text(o->task), o->task);
    ValidateOptions options;
    options.n = o->n;
    options.seed = o->seed;
    options.threads = threads;
    options.mode = *parse_sample_mode(o->mode);
    options.form = *parse_controller_form(o->controller);
    options.sticking_trials = o->sticking_trials;
    options.counterexample_budget = o->budget;
    options.spring_coast = o->spring_coast;
    const ValidateOutput v =
        validate_within_time_limit(task, o->strategy, options, o->time_limit, state.json, o->ends);
    std::cerr << v.err;
    std::cout << v.out;
    state.exit_status = v.exit_status;
  });
}

}  // namespace cmt
