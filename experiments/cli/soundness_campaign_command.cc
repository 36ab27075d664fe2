// `cmt soundness-campaign --tasks N [--first I] --seed S [-n ROLLOUTS] [--threads T] [--verifier-budget SEC]
// [--no-minimize] [--out DIR] --json`: the random-task soundness campaign
// (experiments/validation/soundness_campaign.h). Exit 0 when every task was sound, 1 when a soundness bug was
// found (saved under DIR/bugs/ with its replay command), 2 on bad usage. Rerunning with the same seed and
// rollout count resumes from DIR/results.jsonl.
#include <iostream>
#include <thread>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/validation/soundness_campaign.h"

namespace cmt {

void add_soundness_campaign_command(CLI::App& app, CommandState& state) {
  struct Options {
    CampaignOptions campaign;
    std::string out = "out/soundness-campaign";
    bool no_minimize = false;
    int threads = 0;
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
  cmd->add_option("--threads", o->threads, "rollout threads (0: all cores; results do not depend on it)");
  cmd->add_option("--verifier-budget", o->campaign.verifier_budget,
                  "seconds of wall clock per verification; a task over it is recorded as timed-out")
      ->capture_default_str();
  cmd->add_option("--out", o->out, "output folder: results.jsonl (one line per task) and bugs/")
      ->capture_default_str();
  cmd->add_flag("--no-minimize", o->no_minimize, "save bugs as generated, without shrinking them");
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
    o->campaign.minimize = !o->no_minimize;
    const CampaignSummary s = run_soundness_campaign(o->campaign, [](const CampaignRecord& r) {
      std::cerr << "task " << r.index << ": " << r.status << " (" << r.description << ")";
      if (r.status == "bug") std::cerr << " -> " << r.saved << "\n    replay: " << r.replay;
      std::cerr << "\n";
    });
    nlohmann::json bugs = nlohmann::json::array();
    for (const CampaignRecord& r : s.bug_records) bugs.push_back(campaign_record_json(r));
    const nlohmann::json j = {{"tasks", s.run},
                              {"resumed", s.resumed},
                              {"sound", s.sound},
                              {"bugs", s.bugs},
                              {"invalid", s.invalid},
                              {"timed_out", s.timed_out},
                              {"reliable", s.reliable},
                              {"seed", o->campaign.seed},
                              {"rollouts", o->campaign.rollouts},
                              {"soundness_bugs", bugs},
                              {"results", (o->campaign.out / "results.jsonl").string()}};
    if (state.json)
      print_json(j);
    else
      std::cout << s.run << " tasks: " << s.sound << " sound, " << s.bugs << " soundness bugs, " << s.invalid
                << " invalid, " << s.timed_out << " timed out (" << s.reliable << " verified reliable)\n";
    state.exit_status = s.bugs > 0 ? kExitFailureFound : kExitSuccess;
  });
}

}  // namespace cmt
