// `cmt validate --edr` (validate_edr.h).
#include "experiments/cli/validate_edr.h"

#include <chrono>
#include <iostream>

#include "experiments/cli/cli_output.h"
#include "experiments/edr/edr_check.h"
#include "experiments/edr/edr_verdict.h"
#include "models/loaded_task.h"

namespace cmt {
namespace {

void print_summary(const nlohmann::json& out) {
  const nlohmann::json& o = out["outcomes"];
  std::cout << out["task"].get<std::string>() << " / " << out["strategy"].get<std::string>() << ": "
            << (out["edr_reliable"].get<bool>() ? "EDR-reliable"
                                                : "not EDR-reliable: " + out["reason"].get<std::string>())
            << "\n  " << out["rollouts"].get<int>() << " rollouts in " << out["worlds"].size()
            << " worlds: " << o["success"].get<int>() << " success, " << o["failure_signalled"].get<int>()
            << " failure signalled, " << o["false_success"].get<int>() << " false success, "
            << o["false_failure"].get<int>() << " false failure, " << out["missed_success"].get<int>()
            << " missed success, " << o["timeout"].get<int>() << " timeout, " << out["unstable"].get<int>()
            << " unstable\n  soundness " << out["soundness"].get<double>() << " ("
            << out["outside"].get<int>() << " of " << out["ends"].get<int>()
            << " motion ends outside their world's prediction), coverage " << out["coverage"].get<double>()
            << "\n";
  for (const nlohmann::json& f : out["forbidden"])
    std::cout << "  " << f["outcome"].get<std::string>() << ": " << f["replay"].get<std::string>() << "\n";
  for (const nlohmann::json& f : out["outside_ends"])
    std::cout << "  outside: " << f["replay"].get<std::string>() << "\n";
}

}  // namespace

int validate_edr(const ValidateEdrOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const auto task = load_task_from_string(read_task_text(options.task), options.task);
  EdrVerdictRequest request;
  request.file = options.task;
  request.strategy = options.strategy;
  request.resolution = options.resolution;
  request.refine_depth = options.refine_depth;
  request.require_signal = true;
  const EdrResult verdict = edr_verdict(*task, request);
  EdrCheckOptions check_options;
  check_options.rollouts = options.rollouts;
  check_options.rollouts_per_world = options.per_world;
  check_options.seed = options.seed;
  check_options.threads = options.threads;
  check_options.mode = options.mode;
  const EdrCheck check = check_edr(task->task, options.strategy, verdict, check_options);
  nlohmann::json out = edr_check_json(task->task, check);
  const int forbidden = check.false_success + check.false_failure;
  out["task"] = task->task.name;
  out["strategy"] = options.strategy;
  out["edr"] = true;
  out["edr_reliable"] = out["reliable"] = verdict.edr_reliable;
  out["reason"] = verdict.reason;
  // As in `cmt validate`: the rollouts that ended in the goal, whatever the predicate reported.
  out["successes"] = check.success + check.missed_success + check.false_failure;
  out["soundness_bug"] = verdict.edr_reliable && forbidden > 0;
  out["seed"] = options.seed;
  out["mode"] = sample_mode_name(options.mode);
  out["per_world"] = options.per_world;
  out["verdict"] = edr_verdict_json(task->task, request, verdict);
  out["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (options.json)
    print_json(out);
  else
    print_summary(out);
  if (out["soundness_bug"].get<bool>())
    std::cerr << "\n*** SOUNDNESS BUG: '" << options.strategy << "' is verified EDR-reliable, but "
              << forbidden << " rollouts ended in a forbidden outcome (replays in `forbidden`)\n\n";
  return check.outside > 0 || out["soundness_bug"].get<bool>() ? kExitFailureFound : kExitSuccess;
}

}  // namespace cmt
