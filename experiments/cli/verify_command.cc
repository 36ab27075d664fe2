#include "experiments/cli/verify_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>

#include "controllers/termination.h"
#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/common/json_text.h"
#include "experiments/common/verifier_budget.h"
#include "experiments/edr/edr_verdict.h"
#include "experiments/validation/verifier_model.h"
#include "experiments/validation/verify_json.h"
#include "models/input_error.h"
#include "verifier/reached_set.h"

namespace cmt {
// The verification in a forked child under the wall-clock limit (experiments/common/verifier_budget.h: the
// verifier has no cancellation points, so only a separate process can be stopped). Returns verify_json, the
// time-out answer, or {"error": message} for a motion the verifier does not support (bad input).
nlohmann::json verify_json_within_time_limit(const LoadedTask& task, const Strategy& strategy,
                                             const VerifyOptions& options, double time_limit,
                                             bool with_reached, std::chrono::steady_clock::time_point start) {
  const ForkedRun run = run_forked_with_budget(time_limit, [&](const std::function<void()>& phase_done) {
    nlohmann::json out;
    try {
      const VerifyResult result = verify_strategy(task, strategy, options);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      out = verify_json(task, result, seconds, with_reached);
      out["timed_out"] = false;
    } catch (const UnsupportedMotion& e) {
      out = {{"error", e.what()}};
    }
    phase_done();
    return json_text(out);
  });
  if (!run.timed_out) return nlohmann::json::parse(run.payload);
  std::ostringstream failure;
  failure << kVerifierTimedOut << " after " << time_limit << " s (--time-limit)";
  return {{"task", task.task.name},
          {"reliable", false},
          {"timed_out", true},
          {"time_limit", time_limit},
          {"failure", failure.str()},
          {"failed_step", -1},
          {"steps", nlohmann::json::array()},
          {"outside_goal", nlohmann::json::array()},
          {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()},
          {"spring_model", spring_model_name(options.spring_model)},
          {"stop_relative_speed", options.stop_relative_speed},
          {"contact_lift", options.contact_lift},
          {"servo_coast", options.servo_coast}};
}

namespace {

// Units in the last place of the task's world coordinates that one cell of the region grid must span for the
// verifier to resolve positions as it does near the origin (docs/verifier.md "Invariance": precision far from
// the origin). Below it the sets stay sound (every rounding is outward) but may be looser.
constexpr double kRegionCellMinUlps = 16;

// A note on stderr when the task lies so far from the world origin that its coordinates' resolution nears
// the region grid's cell.
void note_far_from_origin(const LoadedTask& task) {
  double reach = 0;
  for (const Vertex& v : task.cspace.vertices()) reach = std::max(reach, v.point.cwiseAbs().maxCoeff());
  const double ulp = std::nextafter(reach, std::numeric_limits<double>::infinity()) - reach;
  const double cell = region_cell(task.cspace.scale());
  if (reach > 0 && cell < kRegionCellMinUlps * ulp)
    std::cerr << "note: " << task.task.name << " lies " << reach / task.cspace.scale()
              << " scene scales from the world origin, where a region cell (" << cell << ") spans "
              << cell / ulp << " units in the last place of its coordinates (fewer than "
              << kRegionCellMinUlps << "): the verdict is sound but may be looser than near the origin; "
              << "translate the task nearer the origin for the tightest sets\n";
}

// The EDR verdict's JSON (edr_verdict.h) computed in a forked child under the wall-clock limit, with
// `reliable` and `timed_out`; bad input found there (a slice the loader rejects) comes back as InputError.
nlohmann::json edr_verdict_within_time_limit(const LoadedTask& task, const EdrVerdictRequest& request,
                                             double time_limit, std::chrono::steady_clock::time_point start) {
  const ForkedRun run = run_forked_with_budget(time_limit, [&](const std::function<void()>& phase_done) {
    nlohmann::json out;
    try {
      const EdrResult r = edr_verdict(task, request);
      out = edr_verdict_json(task.task, request, r);
      out["reliable"] = r.edr_reliable;
      out["timed_out"] = false;
    } catch (const InputError& e) {
      out = {{"task_error", {{"file", e.file()}, {"key", e.key()}, {"reason", e.reason()}}}};
    }
    phase_done();
    return json_text(out);
  });
  nlohmann::json out;
  if (run.timed_out) {
    std::ostringstream reason;
    reason << kVerifierTimedOut << " after " << time_limit << " s (--time-limit)";
    out = {{"task", task.task.name}, {"strategy", request.strategy},
           {"reliable", false},      {"edr_reliable", false},
           {"timed_out", true},      {"time_limit", time_limit},
           {"reason", reason.str()}, {"slices", nlohmann::json::array()}};
  } else {
    out = nlohmann::json::parse(run.payload);
  }
  if (out.contains("task_error")) {
    const nlohmann::json& e = out["task_error"];
    throw InputError(e["file"], e["key"], e["reason"]);
  }
  out["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

// `cmt verify --edr`: the verdict's JSON or a summary; exit 0 when EDR-reliable, else 1.
int print_edr_verdict(const EdrVerdictRequest& request, double time_limit, bool json) {
  const auto start = std::chrono::steady_clock::now();
  const auto task = load_task_from_string(read_task_text(request.file), request.file);
  const nlohmann::json out = edr_verdict_within_time_limit(*task, request, time_limit, start);
  const bool reliable = out["edr_reliable"].get<bool>();
  if (json)
    print_json(out);
  else
    std::cout << task->task.name << ": "
              << (reliable ? "EDR-reliable" : "NOT EDR-reliable: " + out["reason"].get<std::string>()) << " ("
              << out["slices"].size() << " slices)\n";
  return reliable ? kExitSuccess : kExitFailureFound;
}

struct VerifyCli {
  std::string task, strategy, motion;
  bool reached = false;
  SpringModel spring_model = SpringModel::kVelocity;
  double stop_relative_speed = kStopRelativeSpeed;
  double contact_lift = -1;  // < 0: the rollouts' scene (rollout_contact_lift)
  double servo_coast = -1;   // < 0: the rollouts' scene (rollout_servo_coast)
  bool spring_coast = true;  // VerifyOptions::spring_coast
  double time_limit = kDefaultVerifyTimeLimit;
  bool edr = false;
  int resolution = EdrVerdictRequest{}.resolution;
  int refine_depth = EdrVerdictRequest{}.refine_depth;
};

// `cmt verify --edr`: the EDR verdict under model error (as `cmt edr`).
void run_verify_edr(const VerifyCli& cli, CommandState& state) {
  if (cli.strategy.empty()) throw CLI::ValidationError("--edr", "give --strategy NAME");
  if (cli.reached) throw CLI::ValidationError("--reached", "not with --edr (the slices list their pieces)");
  EdrVerdictRequest request;
  request.file = cli.task;
  request.strategy = cli.strategy;
  request.resolution = cli.resolution;
  request.refine_depth = cli.refine_depth;
  request.contact_lift = cli.contact_lift;
  request.servo_coast = cli.servo_coast;
  request.stop_relative_speed = cli.stop_relative_speed;
  request.require_signal = true;
  state.exit_status = print_edr_verdict(request, cli.time_limit, state.json);
}

// The verdict in words: per step (and branch) where its motion may terminate, and the failure if any.
void print_verify_text(const std::string& task_name, const nlohmann::json& j) {
  const bool reliable = j["reliable"].get<bool>();
  std::cout << task_name << ": " << (reliable ? "reliable" : "NOT reliable") << "\n";
  for (const auto& s : j["steps"]) {
    std::cout << "  "
              << (s.contains("branch") ? "[branch " + std::to_string(s["branch"].get<int>()) + "] " : "")
              << s["motion"].get<std::string>() << " terminates on:";
    for (const auto& p : s["termination"]) std::cout << " " << p["name"].get<std::string>();
    std::cout << "\n";
  }
  if (!reliable) std::cout << "  " << j["failure"].get<std::string>() << "\n";
}

void run_verify(const VerifyCli& cli, CommandState& state) {
  if (cli.edr) return run_verify_edr(cli, state);
  const auto start = std::chrono::steady_clock::now();
  const auto task = load_task(cli.task);
  Strategy strategy;
  if (!cli.strategy.empty()) {
    strategy = task->task.strategy_named(cli.strategy);
  } else if (!cli.motion.empty()) {
    strategy = Strategy::sequence(cli.motion, {cli.motion});  // unknown: InputError (verify.h)
  } else {
    throw CLI::ValidationError("verify", "give --strategy NAME or --motion NAME");
  }
  note_far_from_origin(*task);
  const VerifyOptions verify_options{cli.spring_model,
                                     cli.stop_relative_speed,
                                     cli.contact_lift >= 0 ? cli.contact_lift : rollout_contact_lift(*task),
                                     cli.servo_coast >= 0 ? cli.servo_coast : rollout_servo_coast(*task),
                                     rollout_spring_lag(),
                                     cli.spring_coast};
  const nlohmann::json j =
      verify_json_within_time_limit(*task, strategy, verify_options, cli.time_limit, cli.reached, start);
  if (j.contains("error")) {
    state.exit_status = report_bad_input(j["error"].get<std::string>(), state.json);
    return;
  }
  const bool reliable = j["reliable"].get<bool>();
  if (state.json)
    print_json(j);
  else
    print_verify_text(task->task.name, j);
  state.exit_status = reliable ? kExitSuccess : kExitFailureFound;
}

}  // namespace

void add_verify_command(CLI::App& app, CommandState& state) {
  auto options = std::make_shared<VerifyCli>();
  auto* cmd = app.add_subcommand("verify", "Verify a strategy of damper and spring motions (Buckley ch. 4)");
  cmd->add_option("TASK", options->task, "task YAML file")->required();
  auto* strategy =
      cmd->add_option("--strategy", options->strategy, "strategy name (from the task's strategies)");
  auto* motion = cmd->add_option("--motion", options->motion, "a single motion from the task's start");
  strategy->excludes(motion);
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->add_flag("--reached", options->reached, "also list every reached contact point per motion");
  cmd->add_option("--spring-model", options->spring_model,
                  "spring trajectory model: velocity (the impedance/admittance forms: sensing offset fixed "
                  "during a motion; default) or via-point (Buckley App. B, the position form)")
      ->transform(
          CLI::CheckedTransformer(std::map<std::string, SpringModel>{{"velocity", SpringModel::kVelocity},
                                                                     {"via-point", SpringModel::kViaPoint}},
                                  CLI::ignore_case));
  cmd->add_option(
         "--stop-relative-speed", options->stop_relative_speed,
         "kappa of the stop rule: a slide slower than kappa x the motion's reference speed counts as "
         "a stop, as in the rollouts (default " +
             std::to_string(kStopRelativeSpeed) + "); 0 = Coulomb sticking only (the thesis)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--contact-lift", options->contact_lift,
                  "how far (task units) a sliding robot may rise off a face (a slide into a concave edge may "
                  "meet the other face that high); default: the rollouts' MuJoCo scene, (m/b) mu_max V "
                  "(docs/verifier.md \"Contact lift\"); 0 = Buckley's first-order contact")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--servo-coast", options->servo_coast,
                  "how far (task units) the servo's lag may carry a damper on at an impact or past a rim it "
                  "slides over; default: the rollouts' MuJoCo scene, (m/b) V (docs/verifier.md \"Servo "
                  "coast\"); 0 = Buckley's first-order model")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--spring-coast,!--no-spring-coast", options->spring_coast,
                "bound velocity-model spring flights for the servo coast past convex rims and vertices "
                "(docs/verifier.md \"Servo coast of springs\"; the default); --no-spring-coast: their "
                "first-order flights");
  cmd->add_option("--time-limit", options->time_limit,
                  "wall-clock seconds the verifier may run (default " +
                      std::to_string(kDefaultVerifyTimeLimit) +
                      "); beyond, the answer is not reliable with timed_out: true (exit 1)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--edr", options->edr,
                "the EDR verdict under model error (docs/edr.md; as cmt edr): the strategy's last motion "
                "carries the EDR termination predicate (edr: true)");
  cmd->add_option(
         "--resolution", options->resolution,
         "with --edr: evenly spaced values per model parameter (critical values and midpoints added)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option(
         "--refine", options->refine_depth,
         "with --edr: bisections of adjacent slices where the goal appears or the terminations leave "
         "their sweep (as cmt edr)")
      ->check(CLI::Range(0, 10))
      ->capture_default_str();
  cmd->callback([options, &state] { run_verify(*options, state); });
}

}  // namespace cmt
