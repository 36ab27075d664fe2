// The reproducers of the soundness issue (models/tasks/soundness/), each verified and checked against
// extreme-mode rollouts: every observed end must lie in the prediction (soundness 1), and the verdict must be
// the one physics shows (stated per task from the scene, not from the program's output).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "controllers/random.h"
#include "experiments/validation/soundness_campaign.h"
#include "experiments/validation/validation.h"
#include "models/loaded_task.h"

namespace cmt {
namespace {

ValidationResult validate_file(const std::string& name, const std::string& strategy, int n,
                               std::uint64_t seed = 3, bool spring_coast = true) {
  const std::filesystem::path path = std::filesystem::path(CMT_SOURCE_DIR) / "models/tasks/soundness" / name;
  const auto task = load_task(path);
  ValidateOptions o;
  o.n = n;
  o.seed = seed;
  o.threads = 2;
  o.mode = SampleMode::kExtreme;
  o.counterexample_budget = 0;
  o.spring_coast = spring_coast;
  return run_validation(task, strategy, o);
}

void expect_sound(const ValidationResult& r) {
  EXPECT_EQ(r.outside, 0) << r.task << ": farthest end outside at "
                          << (r.worst.empty() ? 0.0 : r.worst.front().distance);
  EXPECT_DOUBLE_EQ(r.soundness, 1);
  EXPECT_FALSE(r.soundness_bug);
  EXPECT_GT(r.ends.size(), 0u);
}

// Bug 1: the slide toward x = 10.2 may end past the goal's edge x = 9.72 (the model allows stops up to x ~
// 9.77, and extreme rollouts end there): unreliable, and every end inside the prediction.
TEST(SoundnessReproducers, DirectionConeReachesTheWholeFace) {
  const ValidationResult r = validate_file("trunc.yaml", "s", 200);
  EXPECT_FALSE(r.prediction.reliable);
  expect_sound(r);
}

// Bug 2: 100 in from the origin the slide must still be predicted: the robot slides .3 in toward x = 100.8,
// out of the .1 in goal square, so unreliable, with every end inside the prediction.
TEST(SoundnessReproducers, SectionsDoNotDependOnTheWorldOrigin) {
  const ValidationResult r = validate_file("far_slide.yaml", "s", 200);
  EXPECT_FALSE(r.prediction.reliable);
  expect_sound(r);
}

// Class A: pressing into the floor 300 in from the origin; the goal is the whole floor, and a spring pressing
// 1.2 in below it (pull within 44° of straight down, beyond phi = .29 + theta_v = .2 only at first) ends on
// the floor in every rollout: the termination set is not empty, every end lies in it.
TEST(SoundnessReproducers, FarFromTheOriginTheFloorStillSticks) {
  const ValidationResult r = validate_file("min_a_off300.yaml", "s", 150);
  ASSERT_FALSE(r.prediction.steps.empty());
  EXPECT_FALSE(r.prediction.steps[0].termination.empty());
  EXPECT_FALSE(r.prediction.steps[0].may_not_terminate);
  expect_sound(r);
}

// Bug 3: from a convex block corner, pulled diagonally into the block, the robot may slide off the vertex
// (onto the top or a side face); the goal is the vertex alone: unreliable, every end predicted.
TEST(SoundnessReproducers, ConvexCornerIsNotMustStick) {
  const ValidationResult r = validate_file("convex_corner.yaml", "s", 150);
  EXPECT_FALSE(r.prediction.reliable);
  expect_sound(r);
}

// Termination: a spring pulled 1.7 mm into a mu .1 box top with theta_v .27 (> phi = .10) may be pushed back
// and forth about the foot of its command by a switching velocity error and never stop (the campaign's seed
// 2, task 106: rollout 20 slides about for the whole time-out). Unreliable, because it may slide forever;
// every end that does occur is predicted, and physics shows the non-termination.
TEST(SoundnessReproducers, SwitchingErrorsCanKeepASpringSliding) {
  const ValidationResult r = validate_file("campaign2_106.yaml", "s", 30, 10905525725756348068ull);
  EXPECT_FALSE(r.prediction.reliable);
  EXPECT_NE(r.prediction.failure.find("may slide forever on f6"), std::string::npos) << r.prediction.failure;
  EXPECT_FALSE(r.timeouts.empty());  // rollout 20 of this seed never stops
  expect_sound(r);
}

// Class B: sliding into the wall y = 7 at mu .75, the rollouts' robot hops (MuJoCo's convex contact) and some
// stick on the wall above the edge. With the contact lift the prediction holds those ends (soundness 1) and
// the verdict is unreliable, as the failing rollouts show; every end on the wall lies within the derived
// lift bound of the floor (the bound is checked by physics, not assumed).
TEST(SoundnessReproducers, ContactLiftCoversHopsIntoAWall) {
  const ValidationResult r = validate_file("min_b.yaml", "s", 150);
  EXPECT_FALSE(r.prediction.reliable);
  EXPECT_GT(r.prediction.contact_lift, 0);
  expect_sound(r);
  EXPECT_LT(r.successes, static_cast<int>(r.rollouts.size()));  // some rollouts do stick above the edge
  double highest = 0;
  for (const ObservedEnd& e : r.ends) highest = std::max(highest, e.end.z());
  EXPECT_GT(highest, r.contact_tolerance);  // the hop is real: above the edge by more than the tolerance
  EXPECT_LE(highest, r.prediction.contact_lift);  // and within the bound
}

// Class C, the servo transient (docs/verifier.md "Servo coast"): dampers that slide off a box top, hop over
// its rim or land on a wall that holds them, where the rollouts' servo keeps the old velocity for its time
// constant. Under first-order velocity changes 1 to 16 of these 150 extreme rollouts each ended beside the
// prediction (by 2.4e-5 to 1.5e-4 m, the files' comments). Every robot leaves the box top, the goal:
// unreliable, as every rollout shows; every end must lie in the prediction with the servo coast of the
// rollouts' scene.
TEST(SoundnessReproducers, ServoCoastCoversLandingsAndRimDepartures) {
  const std::pair<const char*, std::uint64_t> cases[] = {
      {"impact_coast_4.yaml", 10905525725756348106ULL}, {"impact_coast_10.yaml", 10905525725756348100ULL},
      {"campaign2_73.yaml", 10905525725756348039ULL},   {"campaign3_63.yaml", 2092789425003139026ULL},
      {"campaign3_163.yaml", 2092789425003138894ULL},   {"campaign3_278.yaml", 2092789425003138811ULL},
      {"campaign3_341.yaml", 2092789425003138744ULL},   {"campaign3_541.yaml", 2092789425003138544ULL}};
  for (const auto& [file, seed] : cases) {
    SCOPED_TRACE(file);
    const ValidationResult r = validate_file(file, "s", 150, seed);
    EXPECT_GT(r.prediction.servo_coast, 0);
    EXPECT_FALSE(r.prediction.reliable);
    EXPECT_EQ(r.successes, 0);
    expect_sound(r);
  }
}

// Class C for springs (slanted campaign seed 9, task 197): a spring slides off a box top over its convex rim
// and lands on a ramp below, where it sticks; the servo keeps the sliding velocity for its time constant and
// carries the robot farther out than the first-order flight. Most rollouts leave the box top, the goal, so
// unreliable; with the spring coast (the default) every end must lie in the prediction, and with the
// first-order flights some do not (the bug is real, and the coast is what covers it).
TEST(SoundnessReproducers, SpringServoCoastCoversARimDeparture) {
  const ValidationResult first_order =
      validate_file("slanted9_197.yaml", "s", 150, 12587370737594032289ULL, false);
  EXPECT_GT(first_order.outside, 0);
  const ValidationResult r = validate_file("slanted9_197.yaml", "s", 150, 12587370737594032289ULL);
  EXPECT_GT(r.prediction.servo_coast, 0);
  EXPECT_FALSE(r.prediction.reliable);
  EXPECT_LT(r.successes, static_cast<int>(r.rollouts.size()));
  expect_sound(r);
}

// The rollouts' scene at a ramp's sharp edge (slanted campaign seed 9, task 224): a spring pulls the robot up
// a slope and over the ramp's high edge, where the slope meets the vertical front face at 74 degrees, toward
// a target 2.2 mm in front of that face. The cube-eroded ramp was cut back there (a shelf 9.5 mm below the
// edge): every rollout slid along it and one stuck on the front face outside the prediction. With the ramp
// met by its reflected copy every rollout must be stable and every end inside the prediction; the goal is
// the start point, which no rollout keeps, so unreliable.
TEST(SoundnessReproducers, ARampsSharpEdgeIsExactInTheRolloutsScene) {
  const ValidationResult r = validate_file("slanted9_224.yaml", "s", 150, 12587370737594032260ULL);
  EXPECT_EQ(r.unstable, 0);
  EXPECT_FALSE(r.prediction.reliable);
  EXPECT_EQ(r.successes, 0);
  expect_sound(r);
}

// Class B for springs (campaign seed 3, task 10): a spring slides along the floor into a wall at mu .72 and
// some rollouts hop onto the wall above the edge and stick there, so the goal (the floor) is missed. Physics
// says unreliable (rollouts fail); every end must lie in the prediction, the wall ends within the lift bound.
TEST(SoundnessReproducers, SpringLiftStripsCoverHopsIntoAWall) {
  const ValidationResult r = validate_file("campaign3_10.yaml", "s", 150, 2092789425003139047ULL);
  EXPECT_FALSE(r.prediction.reliable);
  expect_sound(r);
  EXPECT_LT(r.successes, static_cast<int>(r.rollouts.size()));  // some rollouts stick on the wall
}

// Class B for springs (campaign seed 3, task 430, inches): the robot hops up to .0098 in off the floor and
// more than half the extreme rollouts stick on the wall f11 above the floor edge, the only prediction under
// first-order contact. Every end must lie in the prediction, and the wall ends within the lift bound.
TEST(SoundnessReproducers, SpringLiftStripsHoldMostEndsAboveTheEdge) {
  const ValidationResult r = validate_file("campaign3_430.yaml", "s", 150, 2092789425003138627ULL);
  expect_sound(r);
  const double floor_z = -1.53595007053;
  int above = 0;
  for (const ObservedEnd& e : r.ends) {
    above += e.end.z() - floor_z > r.contact_tolerance;
    EXPECT_LE(e.end.z() - floor_z, r.prediction.contact_lift);
  }
  EXPECT_GT(above, 10);  // the hops are real: many ends lie on the wall, above the edge
}

// Generated tasks are reproducible and load.
TEST(SoundnessCampaign, TasksAreSeededAndLoad) {
  for (int i = 0; i < 40; ++i) {
    const CampaignTask a = generate_campaign_task(7, i), b = generate_campaign_task(7, i);
    EXPECT_EQ(a.yaml, b.yaml);
    EXPECT_NO_THROW(load_task_from_string(a.yaml, "campaign")) << a.yaml;
  }
  EXPECT_NE(generate_campaign_task(7, 0).yaml, generate_campaign_task(7, 1).yaml);
  EXPECT_NE(generate_campaign_task(7, 0).yaml, generate_campaign_task(8, 0).yaml);
}

// The gap between a start and the nearest rim of its face's top (the floor: the bounds; else the box whose
// top holds the start), over the start's points.
double rim_gap(const Task& t) {
  const Vec3& p0 = t.start.points.front();
  AxisBox face = *t.bounds;
  for (const ConvexPart& box : t.cspace)
    if (std::abs(box.box.max.z() - p0.z()) < 1e-9 && box.box.min.x() <= p0.x() && p0.x() <= box.box.max.x() &&
        box.box.min.y() <= p0.y() && p0.y() <= box.box.max.y())
      face = box.box;
  double gap = std::numeric_limits<double>::infinity();
  for (const Vec3& p : t.start.points)
    for (int k = 0; k < 2; ++k) gap = std::min({gap, p[k] - face.min[k], face.max[k] - p[k]});
  return gap;
}

// kRimBand (.05 room units) at the largest room unit: 2 in times the task's unit (docs/validation.md).
double max_rim_band(const std::string& yaml) {
  const double per_inch = yaml.find("units: mm") != std::string::npos    ? 25.4
                          : yaml.find("units: m\n") != std::string::npos ? 0.0254
                                                                         : 1.0;
  return 0.05 * 2 * per_inch + 1e-9;
}

// The wide generator draws what the default leaves out (friction >= 1, lifted boxes, starts near a rim), its
// tasks load and are seeded, and it differs from the default generator for the same seed.
TEST(SoundnessCampaign, WideTasksReachFrictionAboveOneLiftedBoxesAndRims) {
  int high_friction = 0, lifted = 0, near_rim = 0;
  for (int i = 0; i < 60; ++i) {
    const CampaignTask a = generate_campaign_task(7, i, CampaignGenerator::kWide);
    EXPECT_EQ(a.yaml, generate_campaign_task(7, i, CampaignGenerator::kWide).yaml);
    std::shared_ptr<const LoadedTask> task;
    ASSERT_NO_THROW(task = load_task_from_string(a.yaml, "campaign")) << a.yaml;
    high_friction += task->task.friction >= 1;
    for (const ConvexPart& box : task->task.cspace) lifted += box.box.min.z() > task->task.bounds->min.z();
    if (a.description.find("start near a rim") != std::string::npos) {
      ++near_rim;
      const Region& start = task->task.start;
      if (start.kind != Region::Kind::kSegment) {
        EXPECT_LE(rim_gap(task->task), max_rim_band(a.yaml)) << a.yaml;
      }
    }
    EXPECT_NE(a.description.find("wide: "), std::string::npos) << a.description;
  }
  EXPECT_GT(high_friction, 0);
  EXPECT_GT(lifted, 0);
  EXPECT_GT(near_rim, 0);
  EXPECT_NE(generate_campaign_task(7, 0, CampaignGenerator::kWide).yaml, generate_campaign_task(7, 0).yaml);
}

// The slanted generator: seeded, every task loads, ramps (convex parts) occur, and so do starts on a slope (a
// face whose normal is not along an axis). A ramp side flush with a wall reaches through it by at least
// 0.1 x the scene scale, twice the largest cube half size of the rollouts' scene, so that the eroded ramp
// stays under a cube that touches the wall; no ramp ends within that of a wall outside the bounds.
TEST(SoundnessCampaign, SlantedTasksHaveRampsAndStartsOnSlopes) {
  int ramps = 0, on_slope = 0;
  for (int i = 0; i < 60; ++i) {
    const CampaignTask a = generate_campaign_task(7, i, CampaignGenerator::kSlanted);
    EXPECT_EQ(a.yaml, generate_campaign_task(7, i, CampaignGenerator::kSlanted).yaml);
    std::shared_ptr<const LoadedTask> task;
    ASSERT_NO_THROW(task = load_task_from_string(a.yaml, "campaign")) << a.yaml;
    const AxisBox room = *task->task.bounds;
    for (const ConvexPart& part : task->task.cspace) {
      if (part.shape == ConvexPart::Shape::kBox) continue;
      ++ramps;
      for (int k = 0; k < 2; ++k) {
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const Vec3& v : part.vertices) lo = std::min(lo, v[k]), hi = std::max(hi, v[k]);
        const double reach = 0.1 * task->cspace.scale();
        EXPECT_TRUE(lo > room.min[k] || lo <= room.min[k] - reach) << a.yaml;
        EXPECT_TRUE(hi < room.max[k] || hi >= room.max[k] + reach) << a.yaml;
      }
    }
    if (a.description.find("start on a slope") != std::string::npos) {
      ++on_slope;
      const int atom = task->cspace.nearest_atom(task->task.start.points.front(), task->surface_tolerance());
      ASSERT_GE(atom, 0) << a.yaml;
      ASSERT_EQ(task->cspace.atom_kind(atom), AtomKind::kFace) << a.yaml;
      const Vec3 n = task->cspace.faces()[static_cast<std::size_t>(atom)].normal;
      EXPECT_LT(n.cwiseAbs().maxCoeff(), 1 - 1e-6) << a.yaml;
    }
    EXPECT_NE(a.description.find("slanted: "), std::string::npos) << a.description;
  }
  EXPECT_GT(ramps, 0);
  EXPECT_GT(on_slope, 0);
  EXPECT_NE(generate_campaign_task(7, 0, CampaignGenerator::kSlanted).yaml,
            generate_campaign_task(7, 0).yaml);
}

// A task is inconclusive, not sound, when more than a tenth of its rollouts are unstable (the scene did not
// represent the task for them); ends outside the prediction are a bug whatever the share.
TEST(SoundnessCampaign, ManyUnstableRolloutsMakeATaskInconclusive) {
  EXPECT_EQ(campaign_status(150, 0, 0, false), "sound");
  EXPECT_EQ(campaign_status(150, 15, 0, false), "sound");  // exactly a tenth
  EXPECT_EQ(campaign_status(150, 16, 0, false), "inconclusive");
  EXPECT_EQ(campaign_status(150, 146, 0, false), "inconclusive");
  EXPECT_EQ(campaign_status(150, 146, 1, false), "bug");
  EXPECT_EQ(campaign_status(150, 0, 0, true), "bug");
  EXPECT_EQ(campaign_status(150, 20, 0, true), "bug");
}

// The bounded campaign CI runs: 30 generated tasks, 60 extreme rollouts each, no soundness bug. The
// false-alarm check is a stand-in here (cmt soundness-campaign passes cmt falsify's failure search): it must
// be asked exactly about the tasks verified unreliable whose stable rollouts all succeeded, each saved as
// unreliable/task-<i>.yaml, with the task's validation seed; its answer lands in the record and the counts.
TEST(SoundnessCampaign, ThirtyTasksWithoutASoundnessBug) {
  CampaignOptions o;
  o.tasks = 30;
  o.seed = 1;
  o.rollouts = 60;
  o.threads = 2;
  o.verifier_budget = 120;
  o.out = std::filesystem::temp_directory_path() / ("cmt-campaign-test-" + std::to_string(::getpid()));
  std::filesystem::remove_all(o.out);
  std::map<std::string, std::uint64_t> asked;  // saved task file -> seed
  o.false_alarm_check = [&](const std::filesystem::path& file, std::uint64_t seed) {
    asked[file.string()] = seed;
    FalseAlarmCheck check;
    check.failure_found = asked.size() % 2 == 0;  // every other one "finds" a failure
    check.rollouts = 7;
    return check;
  };
  std::vector<CampaignRecord> records;
  const CampaignSummary s = run_soundness_campaign(o, [&](const CampaignRecord& r) { records.push_back(r); });
  EXPECT_EQ(s.run, 30);
  EXPECT_EQ(s.bugs, 0) << "first bug: " << (s.bug_records.empty() ? "" : s.bug_records.front().replay);
  EXPECT_GE(s.sound, 25);  // at most a few invalid or timed-out draws
  int candidates = 0;
  for (const CampaignRecord& r : records) {
    const bool candidate = r.status == "sound" && !r.reliable && r.rollouts > r.unstable &&
                           r.successes == r.rollouts - r.unstable;
    EXPECT_EQ(r.candidate, candidate) << r.index;
    EXPECT_EQ(r.false_alarm.has_value(), candidate) << r.index;
    if (!candidate) continue;
    ++candidates;
    const std::filesystem::path file = o.out / "unreliable" / ("task-" + std::to_string(r.index) + ".yaml");
    EXPECT_EQ(r.saved, file.string());
    ASSERT_EQ(asked.count(file.string()), 1u) << r.index;
    EXPECT_EQ(asked[file.string()], splitmix64(o.seed) ^ static_cast<std::uint64_t>(r.index));
    EXPECT_EQ(load_task(file)->task.strategy_named("s").motions.size(), 1u);
    EXPECT_EQ(r.check.rollouts, 7);
  }
  EXPECT_GE(candidates, 1);
  long rollouts = 0, unstable = 0;
  int inconclusive = 0;
  for (const CampaignRecord& r : records) {
    if (r.status != "sound" && r.status != "bug" && r.status != "inconclusive") continue;
    rollouts += r.rollouts;
    unstable += r.unstable;
    EXPECT_EQ(r.status, campaign_status(r.rollouts, r.unstable, r.outside, r.soundness_bug)) << r.index;
    if (r.status != "inconclusive") continue;
    ++inconclusive;
    EXPECT_EQ(r.saved, (o.out / "inconclusive" / ("task-" + std::to_string(r.index) + ".yaml")).string());
    EXPECT_TRUE(std::filesystem::exists(r.saved)) << r.index;
  }
  EXPECT_EQ(s.rollouts, rollouts);
  EXPECT_EQ(s.unstable, unstable);
  EXPECT_EQ(s.inconclusive, inconclusive);
  EXPECT_EQ(static_cast<int>(asked.size()), candidates);
  EXPECT_EQ(s.candidates, candidates);
  EXPECT_EQ(s.false_alarms + s.failures_found, candidates);
  EXPECT_EQ(s.failures_found, candidates / 2);

  // Resumed: the range's tasks are read back, none is run again.
  CampaignOptions tail = o;
  tail.first = 28;
  const CampaignSummary resumed = run_soundness_campaign(tail);
  EXPECT_EQ(resumed.run, 2);
  EXPECT_EQ(resumed.resumed, 2);
  EXPECT_EQ(asked.size(), static_cast<std::size_t>(candidates));  // read back, not checked again
  EXPECT_EQ(resumed.candidates, records[28].candidate + records[29].candidate);
  EXPECT_EQ(resumed.false_alarms, (records[28].false_alarm && *records[28].false_alarm) +
                                      (records[29].false_alarm && *records[29].false_alarm));
  EXPECT_EQ(resumed.rollouts, records[28].rollouts + records[29].rollouts);
  EXPECT_EQ(resumed.unstable, records[28].unstable + records[29].unstable);

  // In a new folder, --first 29 runs task 29 alone, with the same outcome as in the whole campaign.
  CampaignOptions last = tail;
  last.first = 29;
  last.out = o.out.string() + "-last";
  std::filesystem::remove_all(last.out);
  std::vector<CampaignRecord> whole, alone;
  run_soundness_campaign(tail, [&](const CampaignRecord& r) { whole.push_back(r); });
  const CampaignSummary one =
      run_soundness_campaign(last, [&](const CampaignRecord& r) { alone.push_back(r); });
  EXPECT_EQ(one.run, 1);
  EXPECT_EQ(one.resumed, 0);
  ASSERT_EQ(alone.size(), 1u);
  ASSERT_EQ(whole.size(), 2u);
  EXPECT_EQ(alone[0].index, 29);
  EXPECT_EQ(alone[0].description, whole[1].description);
  EXPECT_EQ(alone[0].status, whole[1].status);
  EXPECT_EQ(alone[0].reliable, whole[1].reliable);
  EXPECT_EQ(alone[0].outside, whole[1].outside);
  std::filesystem::remove_all(o.out);
  std::filesystem::remove_all(last.out);
}

}  // namespace
}  // namespace cmt
