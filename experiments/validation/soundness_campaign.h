// The random-task soundness campaign (property-based testing of the verifier against physics): a seeded
// generator of small C-space scenes that nobody tuned the verifier for (a floor and 0-3 boxes, near or far
// from the origin, in inches or millimetres; a start on a top face; one damper or spring motion; error bounds
// across the documented ranges), each verified and checked by extreme-mode MuJoCo rollouts (cmt validate). A
// task whose rollouts end outside the prediction, or fail under a "reliable" verdict, is a soundness bug: it
// is minimized (parts dropped, the start reduced to a point while the bug stays) and saved with its replay
// command. docs/validation.md, "Random-task soundness campaign".
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace cmt {

// One generated task: its YAML text (a complete task file, strategy `s` of one motion `m`) and a one-line
// description of how it was drawn.
struct CampaignTask {
  int index = 0;
  std::string yaml;
  std::string description;
};

// Which scenes a campaign draws (docs/validation.md "Random-task soundness campaign"). kWide adds what the
// default leaves out: friction up to 1.5 (mu >= 1, where a face's cone is wider than 45 degrees), boxes
// lifted off the floor (a tunnel under a C-obstacle, rims over free space) and starts near a face's rim.
// kSlanted makes some obstacles ramps (convex parts whose top slopes: slanted faces, convex and concave edges
// that are not axis-aligned creases, meshes in the rollouts' scene) and starts on their slopes.
enum class CampaignGenerator { kDefault, kWide, kSlanted };
const char* campaign_generator_name(CampaignGenerator g);

// Task `index` of campaign `seed`: the same triple always gives the same text.
CampaignTask generate_campaign_task(std::uint64_t seed, int index,
                                    CampaignGenerator generator = CampaignGenerator::kDefault);

// What the false-alarm check found for one task (CampaignOptions::false_alarm_check).
struct FalseAlarmCheck {
  bool failure_found = false;  // some search rollout failed: the "unreliable" verdict stands
  int rollouts = 0;            // search rollouts run
  double closest = std::numeric_limits<double>::infinity();  // closest final end to the predicted failure
  std::string replay;                                        // the failing rollout's replay command
};

struct CampaignOptions {
  int tasks = 30;
  int first = 0;  // the first task index run (tasks [first, tasks))
  std::uint64_t seed = 1;
  CampaignGenerator generator = CampaignGenerator::kDefault;
  int rollouts = 150;            // extreme-mode rollouts per task
  int threads = 1;               // rollout threads (results are identical for every count)
  double verifier_budget = 120;  // s of wall clock per verification; a task over it is recorded, not scored
  bool minimize = true;          // shrink each bug before saving it
  bool spring_coast = true;      // ValidateOptions::spring_coast (false: first-order spring flights)
  std::filesystem::path out = "out/soundness-campaign";  // results.jsonl, bugs/, unreliable/
  // The false-alarm check (docs/validation.md "False alarms"): a task verified unreliable whose stable
  // rollouts all succeeded is saved as unreliable/task-<i>.yaml and, when this is set, searched for a
  // failing rollout with the validation's seed. The adversarial search (experiments/falsify) depends on this
  // library, so `cmt soundness-campaign` passes it in. Unset: the task is saved and counted, not searched.
  std::function<FalseAlarmCheck(const std::filesystem::path& task_file, std::uint64_t seed)>
      false_alarm_check;
};

// A task whose unstable rollouts (sim/rollout.h: a penetration or an end inside the solid deeper than the
// unstable penetration, a non-finite state, a MuJoCo warning; the scene did not represent the task) exceed
// this share of its rollouts is "inconclusive" rather than "sound" when its stable rollouts show no bug: an
// artefact of the scene that sinks many robots would otherwise leave a task "sound" with its telling
// rollouts dropped. Ends outside the prediction among the stable rollouts are a bug whatever the share.
inline constexpr double kInconclusiveUnstableShare = 0.1;

// "bug" (an end outside the prediction, or a failing rollout under a "reliable" verdict), "inconclusive"
// (no bug, more than kInconclusiveUnstableShare of the rollouts unstable) or "sound".
std::string campaign_status(int rollouts, int unstable, int outside, bool soundness_bug);

// The outcome of one task.
struct CampaignRecord {
  int index = 0;
  std::string status;  // "sound", "bug", "inconclusive", "invalid" (the generated task does not load),
                       // "timed-out"
  std::string description, detail;
  bool reliable = false;
  int rollouts = 0, successes = 0, unstable = 0, ends = 0, outside = 0;
  double soundness = 1, max_distance_outside = 0, verify_seconds = 0;
  bool soundness_bug = false;  // verified reliable, a rollout failed
  std::string saved, replay;   // for bugs: the saved (minimized) task file and the command that replays it
  // A false-alarm candidate (sound, unreliable, every stable rollout succeeded): saved under unreliable/;
  // with the check, false_alarm says whether its search found no failure either.
  bool candidate = false;
  std::optional<bool> false_alarm;
  FalseAlarmCheck check;
};

nlohmann::json campaign_record_json(const CampaignRecord& r);

struct CampaignSummary {
  int run = 0, resumed = 0, sound = 0, bugs = 0, inconclusive = 0, invalid = 0, timed_out = 0, reliable = 0;
  long rollouts = 0, unstable = 0;  // over the scored tasks (sound, bug or inconclusive)
  int candidates = 0, false_alarms = 0, failures_found = 0;  // the false-alarm check's counts
  std::vector<CampaignRecord> bug_records, inconclusive_records;
};

// Runs tasks [options.first, options.tasks) of campaign options.seed, appending one JSON line per task to
// options.out/results.jsonl as it finishes; tasks already recorded there for the same seed and rollout count
// are not rerun (a killed campaign resumes where it stopped). Bugs are saved (minimized) under bugs/,
// inconclusive tasks as generated under inconclusive/. `progress` is called after each task.
CampaignSummary run_soundness_campaign(const CampaignOptions& options,
                                       const std::function<void(const CampaignRecord&)>& progress = {});

}  // namespace cmt
