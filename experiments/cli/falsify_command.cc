// `cmt falsify TASK --strategy NAME [--budget N] [--coverage-budget N] [--gap-budget N] [--random N] [--seed
// S] [--threads T]
// [--mode uniform|extreme] [--controller FORM] [--switches K] --json`: adversarial rollouts, a search over
// the bounded errors for motion ends outside the verifier's prediction and for the predicted pieces random
// errors never reach (experiments/falsify/falsify.h, docs/falsify.md). Exit 0 when nothing is outside, 1 when
// the search (or the random baseline) found a soundness bug, 2 on bad input.
#include <iostream>
#include <thread>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/common/json_text.h"
#include "experiments/falsify/falsify.h"

namespace cmt {
namespace {

void print_summary(std::ostream& os, const FalsifyResult& r) {
  os << r.task << " / " << r.strategy << ": verifier says "
     << (r.prediction.reliable ? "reliable" : "NOT reliable") << "; " << r.rollouts << " search rollouts in "
     << r.searches << " searches (error vector of " << r.dimension << "), " << r.options.random
     << " random\n";
  for (std::size_t k = 0; k < r.best_signed_distance.size(); ++k)
    os << "  " << r.prediction.steps[k].motion << ": best signed distance " << r.best_signed_distance[k]
       << "\n";
  os << "  coverage " << r.coverage_before << " (random) -> " << r.coverage_after << " (all rollouts)\n";
  int unreached = 0;
  for (const PieceCoverage& pc : r.pieces) unreached += pc.reached_by.empty();
  os << "  " << r.pieces.size() - unreached << " of " << r.pieces.size() << " predicted pieces reached\n";
  int gaps_reached = 0;
  for (const CoverageGap& g : r.gaps) gaps_reached += g.reached;
  if (!r.gaps.empty())
    os << "  gap search: " << gaps_reached << " of " << r.gaps.size() << " targeted gaps reached\n";
  if (!r.prediction.reliable) {
    os << "  " << r.failures << " failed rollouts";
    if (r.first_failure)
      os << ", first (" << r.first_failure->how << ") "
         << "at goal distance " << r.first_failure->distance << "\n    " << r.first_failure->replay << "\n";
    else
      os << (r.failure_searched
                 ? " after a failure search of " + std::to_string(r.failure_rollouts) + " rollouts"
                 : std::string(" (no failure search)"))
         << ": a false alarm candidate\n";
  }
  for (const FalsifyFinding& f : r.findings)
    os << "  SOUNDNESS BUG (" << f.how
       << "): " << (f.motion.empty() ? "failed under a reliable verdict" : f.motion) << " at distance "
       << f.distance << "\n    " << f.replay << "\n";
}

}  // namespace

void add_falsify_command(CLI::App& app, CommandState& state) {
  struct Options {
    std::string task, strategy, mode = "extreme", controller = "impedance";
    FalsifyOptions falsify;
    int threads = 0;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("falsify",
                                 "Search the bounded errors for ends outside the prediction and for "
                                 "unreached predicted pieces");
  cmd->add_option("TASK", o->task, "task YAML file")->required();
  cmd->add_option("--strategy", o->strategy, "strategy name (from the task file)")->required();
  cmd->add_option("--budget", o->falsify.budget, "falsification search rollouts")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--coverage-budget", o->falsify.coverage_budget,
                  "coverage search rollouts, shared among the predicted pieces no rollout reached")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  o->falsify.gap_budget = 400;
  cmd->add_option("--gap-budget", o->falsify.gap_budget,
                  "gap search rollouts: searches for the coverage lattice points farthest from every end")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--gap-rollouts", o->falsify.gap_rollouts, "gap search rollouts per gap at most")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  o->falsify.failure_budget = 400;
  cmd->add_option("--failure-budget", o->falsify.failure_budget,
                  "failure search rollouts, under an unreliable verdict only: a search for a rollout that "
                  "fails, toward the predicted places of failure")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--random", o->falsify.random, "random rollouts first (the baseline coverage)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--mode", o->mode, "error sampling of the random rollouts")
      ->check(CLI::IsMember({"uniform", "extreme"}))
      ->capture_default_str();
  cmd->add_option("--seed", o->falsify.seed, "master seed of every draw")->capture_default_str();
  cmd->add_option("--threads", o->threads, "threads (0: all cores); results do not depend on it")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--controller", o->controller,
                  "controller form: impedance (default; the verifier's model), admittance or position")
      ->check(CLI::IsMember({"admittance", "impedance", "position"}))
      ->capture_default_str();
  cmd->add_option("--switches", o->falsify.switches, "velocity-error switches per motion in the error vector")
      ->check(CLI::Range(0, 50))
      ->capture_default_str();
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([o, &state] {
    const auto task = load_task_from_string(read_task_text(o->task), o->task);
    FalsifyOptions options = o->falsify;
    options.threads =
        o->threads > 0 ? o->threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    options.mode = *parse_sample_mode(o->mode);
    options.form = *parse_controller_form(o->controller);
    const FalsifyResult r = run_falsify(task, o->strategy, options);
    if (state.json)
      std::cout << json_text(falsify_json(*task, r), 2) << "\n";
    else
      print_summary(std::cout, r);
    state.exit_status = r.findings.empty() ? kExitSuccess : kExitFailureFound;
  });
}

}  // namespace cmt
