#include "experiments/verify_command.h"

#include <chrono>
#include <iostream>
#include <map>
#include <sstream>

#include "controllers/termination.h"
#include "experiments/cli_output.h"
#include "experiments/command.h"
#include "experiments/json_text.h"
#include "experiments/verifier_budget.h"
#include "experiments/verifier_model.h"
#include "models/task_error.h"

namespace cmt {
namespace {

nlohmann::json pieces_json(const LoadedTask& lt, const std::vector<ReachedPiece>& pieces) {
  const int dim = lt.task.dimension;
  nlohmann::json out = nlohmann::json::array();
  for (const ReachedPiece& p : pieces) {
    nlohmann::json poly = nlohmann::json::array();
    for (const Vec3& q : p.polygon) poly.push_back(point_json(q, dim));
    nlohmann::json entry = {{"atom", p.atom},
                            {"name", lt.cspace.atom_name(p.atom)},
                            {"kind", atom_kind_name(p.kind)},
                            {"polygon", poly}};
    if (!p.holes.empty()) {
      nlohmann::json holes = nlohmann::json::array();
      for (const auto& h : p.holes) {
        nlohmann::json hole = nlohmann::json::array();
        for (const Vec3& q : h) hole.push_back(point_json(q, dim));
        holes.push_back(hole);
      }
      entry["holes"] = holes;
    }
    if (p.kind == AtomKind::kFace && p.polygon.size() >= 3) entry["area"] = p.area;
    out.push_back(entry);
  }
  return out;
}

// A spring motion's free-space rest ball (not an atom).
nlohmann::json free_piece_json(const LoadedTask& lt, const VerifyStep& s) {
  return {{"atom", -1},
          {"name", "free"},
          {"kind", "free"},
          {"center", point_json(s.free_center, lt.task.dimension)},
          {"radius", s.free_radius}};
}

// The verification in a forked child under the wall-clock limit (experiments/verifier_budget.h: the verifier
// has no cancellation points, so only a separate process can be stopped). Returns verify_json, the time-out
// answer, or {"error": message} for a motion the verifier does not support (bad input).
nlohmann::json verify_within_time_limit(const LoadedTask& task, const Strategy& strategy,
                                        const VerifyOptions& options, double time_limit, bool with_reached,
                                        std::chrono::steady_clock::time_point start) {
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
          {"contact_lift", options.contact_lift}};
}

}  // namespace

nlohmann::json verify_json(const LoadedTask& lt, const VerifyResult& r, double seconds, bool with_reached) {
  nlohmann::json steps = nlohmann::json::array();
  for (const VerifyStep& s : r.steps) {
    nlohmann::json termination = pieces_json(lt, s.termination.pieces());
    if (s.free_termination) termination.push_back(free_piece_json(lt, s));
    steps.push_back({{"motion", s.motion},
                     {"termination", termination},
                     {"may_not_terminate", s.may_not_terminate},
                     {"fallback", s.fallback},
                     {"fixpoint_steps", s.fixpoint_steps},
                     {"widened_atoms", s.widened_atoms},
                     {"reached_area", s.reached_area}});
    if (with_reached && s.reached) steps.back()["reached"] = pieces_json(lt, s.reached->pieces());
    // The part of `termination` due to the motion's termination sets (Buckley §4.5), when it has any.
    if (s.sensing) steps.back()["sensing_termination"] = pieces_json(lt, s.sensing->pieces());
    // Conditional strategies (Buckley §4.2): where the step sits in the strategy tree and the test after it.
    nlohmann::json& j = steps.back();
    j["node"] = s.node;
    j["parent"] = s.parent;
    if (s.branch >= 0) j["branch"] = s.branch;
    if (!s.branches.empty()) {
      nlohmann::json branches = nlohmann::json::array();
      for (std::size_t i = 0; i < s.branches.size(); ++i)
        branches.push_back({{"branch", i},
                            {"reachable", !s.branches[i].start->empty()},
                            {"step", s.branches[i].step},
                            {"start", pieces_json(lt, s.branches[i].start->pieces())}});
      j["branches"] = branches;
    }
    if (s.unmatched) j["unmatched"] = pieces_json(lt, s.unmatched->pieces());
  }
  nlohmann::json out = {{"task", lt.task.name},
                        {"reliable", r.reliable},
                        {"steps", steps},
                        {"seconds", seconds},
                        {"spring_model", spring_model_name(r.spring_model)},
                        {"stop_relative_speed", r.stop_relative_speed},
                        {"contact_lift", r.contact_lift}};
  if (!r.reliable) {
    out["failed_step"] = r.failed_step;
    out["failure"] = r.failure;
    out["outside_goal"] = pieces_json(lt, r.outside_goal);
    if (r.failed_step >= 0 && r.steps[r.failed_step].free_termination)
      out["outside_goal"].push_back(free_piece_json(lt, r.steps[r.failed_step]));
  }
  return out;
}

void add_verify_command(CLI::App& app, CommandState& state) {
  struct Options {
    std::string task, strategy, motion;
    bool reached = false;
    SpringModel spring_model = SpringModel::kVelocity;
    double stop_relative_speed = kStopRelativeSpeed;
    double contact_lift = -1;  // < 0: the rollouts' scene (rollout_contact_lift)
    double time_limit = kDefaultVerifyTimeLimit;
  };
  auto options = std::make_shared<Options>();
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
  cmd->add_option("--time-limit", options->time_limit,
                  "wall-clock seconds the verifier may run (default " +
                      std::to_string(kDefaultVerifyTimeLimit) +
                      "); beyond, the answer is not reliable with timed_out: true (exit 1)")
      ->check(CLI::PositiveNumber);
  cmd->callback([options, &state] {
    const auto start = std::chrono::steady_clock::now();
    const auto task = load_task(options->task);
    Strategy strategy;
    if (!options->strategy.empty()) {
      const Strategy* s = task->task.find_strategy(options->strategy);
      if (!s)
        throw TaskError(task->task.source_file, "strategies",
                        "no strategy named '" + options->strategy + "'");
      strategy = *s;
    } else if (!options->motion.empty()) {
      strategy = Strategy::sequence(options->motion, {options->motion});  // unknown: TaskError (verify.h)
    } else {
      throw CLI::ValidationError("verify", "give --strategy NAME or --motion NAME");
    }
    const VerifyOptions verify_options{
        options->spring_model, options->stop_relative_speed,
        options->contact_lift >= 0 ? options->contact_lift : rollout_contact_lift(*task)};
    const nlohmann::json j = verify_within_time_limit(*task, strategy, verify_options, options->time_limit,
                                                      options->reached, start);
    if (j.contains("error")) {
      state.exit_status = report_bad_input(j["error"].get<std::string>(), state.json);
      return;
    }
    const bool reliable = j["reliable"].get<bool>();
    if (state.json) {
      print_json(j);
    } else {
      std::cout << task->task.name << ": " << (reliable ? "reliable" : "NOT reliable") << "\n";
      for (const auto& s : j["steps"]) {
        std::cout << "  "
                  << (s.contains("branch") ? "[branch " + std::to_string(s["branch"].get<int>()) + "] " : "")
                  << s["motion"].get<std::string>() << " terminates on:";
        for (const auto& p : s["termination"]) std::cout << " " << p["name"].get<std::string>();
        std::cout << "\n";
      }
      if (!reliable) std::cout << "  " << j["failure"].get<std::string>() << "\n";
    }
    state.exit_status = reliable ? kExitSuccess : kExitFailureFound;
  });
}

}  // namespace cmt
