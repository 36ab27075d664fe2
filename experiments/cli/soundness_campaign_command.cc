// `cmt soundness-campaign --tasks N [--first I] --seed S [-n ROLLOUTS] [--threads T] [--verifier-budget SEC]
// [--no-minimize] [--no-spring-coast] [--false-alarm-budget N] [--out DIR] --json`: the random-task soundness
// campaign (experiments/validation/soundness_campaign.h), with `cmt falsify`'s failure search as its
// false-alarm check. Exit 0 when no soundness bug was found, 1 when one was (saved under DIR/bugs/ with its
// replay command), 2 on bad usage. A task with more than kInconclusiveUnstableShare of its rollouts unstable
// and no bug is counted inconclusive (saved under DIR/inconclusive/), as a timed-out one is counted, not
// scored. Rerunning with the same seed and rollout count resumes from DIR/results.jsonl.
#include <iostream>
#include <thread>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/falsify/falsify.h"
#include "experiments/validation/soundness_campaign.h"
#include "models/loaded_task.h"

namespace cmt {

void add_soundness_campaign_command(CLI::App& app, CommandState& state) {
  struct Options {
    CampaignOptions campaign;
    std::string out = "out/soundness-campaign";
    std::string generator = "default";
    bool no_minimize = false, no_spring_coast = false;
    int threads = 0;
    int false_alarm_budget = 0;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("soundness-campaign",
                                 "Verify random small tasks and check each against extreme-mode rollouts");
  cmd->add_option("--tasks", o->campaign.tasks, "end of the task range (tasks FIRST..TASKS-1 are run)")
      ->capture_default_str();
  cmd->add_option("--first", o->campaign.first,
                  "first task index (tasks FIRST..TASKS-1: continues a campaign whose folder is gone)")
      ->capture_default_str();
  cmd->add_option("--seed", o->campaign.seed, "campaign seed (task i is the same for the same seed)")
      ->capture_default_str();
  cmd->add_option("-n,--rollouts", o->campaign.rollouts, "extreme-mode rollouts per task")
      ->capture_default_str();
  cmd->add_option(
         "--generator", o->generator,
         "default; wide: friction up to 1.5, boxes lifted off the floor, starts near a rim; or slanted: "
         "ramps (convex parts with sloped tops) and starts on their slopes (docs/validation.md \"Random-task "
         "soundness campaign\"; a campaign resumes only with its own generator)")
      ->check(CLI::IsMember({"default", "wide", "slanted"}))
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "rollout threads (0: all cores; results do not depend on it)");
  cmd->add_option("--verifier-budget", o->campaign.verifier_budget,
                  "seconds of wall clock per verification; a task over it is recorded as timed-out")
      ->capture_default_str();
  cmd->add_option("--out", o->out, "output folder: results.jsonl (one line per task) and bugs/")
      ->capture_default_str();
  cmd->add_flag("--no-minimize", o->no_minimize, "save bugs as generated, without shrinking them");
  cmd->add_flag(
      "--no-spring-coast", o->no_spring_coast,
      "verify with first-order spring flights (cmt verify --no-spring-coast; a campaign resumes only "
      "with its own setting)");
  cmd->add_option("--false-alarm-budget", o->false_alarm_budget,
                  "failure search rollouts (cmt falsify's) for each task verified unreliable whose rollouts "
                  "all succeeded (0: such tasks are saved under unreliable/ and counted, not searched)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([o, &state] {
    if (o->campaign.tasks < 0) throw CLI::ValidationError("--tasks", "must be >= 0");
    if (o->campaign.first < 0 || o->campaign.first > o->campaign.tasks)
      throw CLI::ValidationError("--first", "must be in [0, --tasks]");
    if (o->campaign.rollouts < 1) throw CLI::ValidationError("--rollouts", "must be >= 1");
    if (!(o->campaign.verifier_budget > 0)) throw CLI::ValidationError("--verifier-budget", "must be > 0");
    if (o->threads < 0) throw CLI::ValidationError("--threads", "must be >= 0");
    o->campaign.threads =
        o->threads > 0 ? o->threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    o->campaign.out = o->out;
    o->campaign.generator = o->generator == "wide"      ? CampaignGenerator::kWide
                            : o->generator == "slanted" ? CampaignGenerator::kSlanted
                                                        : CampaignGenerator::kDefault;
    o->campaign.minimize = !o->no_minimize;
    o->campaign.spring_coast = !o->no_spring_coast;
    if (o->false_alarm_budget > 0)
      o->campaign.false_alarm_check = [budget = o->false_alarm_budget, threads = o->campaign.threads](
                                          const std::filesystem::path& file, std::uint64_t seed) {
        FalsifyOptions f;
        f.budget = f.coverage_budget = f.gap_budget = f.random = 0;  // the validation ran the random ones
        f.failure_budget = budget;
        f.seed = seed;
        f.threads = threads;
        const FalsifyResult r = run_falsify(load_task(file), "s", f);
        FalseAlarmCheck check;
        check.failure_found = r.failures > 0;
        check.rollouts = r.failure_rollouts;
        check.closest = r.failure_closest;
        if (r.first_failure) check.replay = r.first_failure->replay;
        return check;
      };
    const CampaignSummary s = run_soundness_campaign(o->campaign, [](const CampaignRecord& r) {
      std::cerr << "task " << r.index << ": " << r.status << " (" << r.description << ")";
      if (r.status == "bug" || r.status == "inconclusive")
        std::cerr << " -> " << r.saved << "\n    replay: " << r.replay;
      if (r.status == "inconclusive")
        std::cerr << "\n    " << r.unstable << " of " << r.rollouts << " rollouts unstable";
      if (r.false_alarm)
        std::cerr << (*r.false_alarm
                          ? "; unreliable, no failure found in " + std::to_string(r.check.rollouts) +
                                " search rollouts: a false alarm"
                          : "; unreliable, failure found: " + r.check.replay);
      std::cerr << "\n";
    });
    nlohmann::json bugs = nlohmann::json::array();
    for (const CampaignRecord& r : s.bug_records) bugs.push_back(campaign_record_json(r));
    nlohmann::json inconclusive = nlohmann::json::array();
    for (const CampaignRecord& r : s.inconclusive_records) inconclusive.push_back(campaign_record_json(r));
    const nlohmann::json j = {{"tasks", s.run},
                              {"resumed", s.resumed},
                              {"sound", s.sound},
                              {"bugs", s.bugs},
                              {"inconclusive", s.inconclusive},
                              {"scored_rollouts", s.rollouts},
                              {"unstable_rollouts", s.unstable},
                              {"invalid", s.invalid},
                              {"timed_out", s.timed_out},
                              {"reliable", s.reliable},
                              {"false_alarm_candidates", s.candidates},
                              {"false_alarms", s.false_alarms},
                              {"failures_found", s.failures_found},
                              {"seed", o->campaign.seed},
                              {"generator", o->generator},
                              {"rollouts", o->campaign.rollouts},
                              {"soundness_bugs", bugs},
                              {"inconclusive_tasks", inconclusive},
                              {"results", (o->campaign.out / "results.jsonl").string()}};
    if (state.json)
      print_json(j);
    else
      std::cout << s.run << " tasks: " << s.sound << " sound, " << s.bugs << " soundness bugs, "
                << s.inconclusive << " inconclusive (over " << kInconclusiveUnstableShare * 100
                << " % of their rollouts unstable), " << s.invalid << " invalid, " << s.timed_out
                << " timed out (" << s.reliable << " verified reliable; " << s.unstable << " of "
                << s.rollouts << " scored rollouts unstable); " << s.candidates
                << " verified unreliable with every rollout successful, of which " << s.false_alarms
                << " false alarms and " << s.failures_found << " failures found by the search\n";
    state.exit_status = s.bugs > 0 ? kExitFailureFound : kExitSuccess;
  });
}

}  // namespace cmt
