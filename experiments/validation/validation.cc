// run_validation (experiments/validation/validation.h): the verifier's prediction, N rollouts, the scores,
// the counterexample (from the rollouts or the search) and the optional sticking table.
#include "experiments/validation/validation.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <sstream>
#include <stdexcept>

#include "experiments/common/verifier_budget.h"
#include "experiments/validation/counterexample_search.h"
#include "models/input_error.h"

namespace cmt {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A shell word: as is when it has no special characters, else single-quoted.
std::string shell_word(const std::string& s) {
  const bool plain = !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) ||
           std::string("_./-+=:,").find(c) != std::string::npos;
  });
  if (plain) return s;
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

std::string replay_command(const LoadedTask& task, const std::string& strategy, std::uint64_t seed, int index,
                           SampleMode mode, ControllerForm form) {
  std::ostringstream os;
  os << "cmt rollout " << shell_word(task.task.source_file) << " --strategy " << shell_word(strategy)
     << " -n " << index + 1 << " --seed " << seed << " --mode " << sample_mode_name(mode);
  if (form != ControllerForm::kAdmittance) os << " --controller " << controller_form_name(form);
  return os.str();
}

ValidationResult run_validation(std::shared_ptr<const LoadedTask> task, const std::string& strategy_name,
                                const ValidateOptions& options) {
  const Strategy* strategy = &task->task.strategy_named(strategy_name);
  if (options.n <= 0) throw std::invalid_argument("run_validation: n must be > 0");
  if (options.form == ControllerForm::kPosition)
    for (const std::string& name : strategy->motions) {
      const Motion* m = task->task.find_motion(name);
      if (m != nullptr && m->kind == Motion::Kind::kDamper)
        throw InputError(task->task.source_file, "motions." + name,
                         "the position controller implements generalized springs only (Buckley eq. 3.25); '" +
                             name + "' is a damper");
    }
  ValidationResult r;
  r.task = task->task.name;
  r.strategy = strategy->name;
  r.options = options;
  r.options.threads = std::max(1, options.threads);
  r.verifier = make_verifier_model(task, options.form);

  auto start = std::chrono::steady_clock::now();
  const bool timed_out = options.verifier_timed_out_after > 0;
  if (timed_out) {
    std::ostringstream why;
    why << kVerifierTimedOut << " after " << options.verifier_timed_out_after
        << " s (no prediction: the motion ends are not scored)";
    r.prediction.failure = why.str();
    r.verify_seconds = options.verifier_timed_out_after;
  } else {
    // The widened task has the same strategies and C-space; only its uncertainty differs.
    VerifyOptions verify_options = r.verifier.verify_options();
    verify_options.spring_coast = options.spring_coast;
    r.prediction = verify_strategy(*r.verifier.task, *r.verifier.task->task.find_strategy(strategy_name),
                                   verify_options);
    r.verify_seconds = seconds_since(start);
  }
  if (options.after_verify) options.after_verify();

  start = std::chrono::steady_clock::now();
  SimOptions sim;
  sim.form = options.form;
  sim.mode = options.mode;
  r.rollouts =
      run_rollouts(RolloutScene::build(task, sim), *strategy, options.n, options.seed, r.options.threads);
  r.rollout_seconds = seconds_since(start);

  score_soundness(*task, &r);
  score_coverage(*task, &r);

  // Unstable rollouts are simulation failures, not physics: they are never counterexamples.
  const auto failed = std::find_if(r.rollouts.begin(), r.rollouts.end(),
                                   [](const RolloutOutcome& o) { return !o.success && !o.unstable; });
  if (failed != r.rollouts.end()) {
    Counterexample cx;
    cx.seed = options.seed;
    cx.index = failed->index;
    cx.mode = options.mode;
    cx.how = "rollouts";
    cx.replay = replay_command(*task, strategy->name, cx.seed, cx.index, cx.mode, options.form);
    cx.outcome = *failed;
    r.counterexample = cx;
    r.soundness_bug = r.prediction.reliable;
  } else if (!r.prediction.reliable && !timed_out && options.counterexample_budget > 0) {
    start = std::chrono::steady_clock::now();
    SearchResult s =
        search_counterexample(task, *strategy, r.options, r.prediction, r.rollouts, r.contact_tolerance);
    r.counterexample = std::move(s.counterexample);
    r.search = std::move(s.report);
    r.search_seconds = seconds_since(start);
  }

  if (options.sticking_trials > 0) {
    start = std::chrono::steady_clock::now();
    // The rollouts' Coulomb-calibrated scene, as cmt check-sticking
    // (experiments/validation/sticking_check.h).
    r.sticking = check_sticking(task, options.sticking_trials, options.seed, r.options.threads);
    r.sticking_seconds = seconds_since(start);
  }
  return r;
}

std::string validate_with_verifier_budget(double budget, ValidateOptions options,
                                          const std::function<std::string(const ValidateOptions&)>& work) {
  const ForkedRun run = run_forked_with_budget(budget, [&](const std::function<void()>& phase_done) {
    ValidateOptions o = options;
    o.after_verify = phase_done;
    return work(o);
  });
  if (!run.timed_out) return run.payload;
  options.verifier_timed_out_after = budget;
  return work(options);
}

}  // namespace cmt
