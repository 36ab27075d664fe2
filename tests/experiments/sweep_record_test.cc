// unit_record (experiments/sweep/sweep_executor.h): a validation result turned into the rows of the results
// store, checked on a hand-built result: one row per motion of every rollout, each motion starting where the
// previous one ended, scored ends carrying inside/distance and unscored ones NULL.
#include <gtest/gtest.h>

#include "experiments/sweep/sweep_executor.h"
#include "tests/experiments/sweep_test_util.h"

namespace cmt {
namespace {

MotionOutcome motion(const std::string& name, const Vec3& end, int atom, Termination t) {
  MotionOutcome m;
  m.motion = name;
  m.end = end;
  m.atom = atom;
  m.termination = t;
  return m;
}

TEST(SweepRecord, RowsFromAValidationResult) {
  const auto task = load_task(test::source_task("two_blocks"));
  ValidationResult v;
  v.prediction.reliable = false;
  v.prediction.failure = "termination of motion 'v1' is not inside the goal";
  v.verify_seconds = 1.5;
  v.rollout_seconds = 0.75;
  // Rollout 0: two motions, both scored. Rollout 1: the second motion timed out (not scored). Rollout 2:
  // ended before its first motion did.
  RolloutOutcome r0;
  r0.index = 0;
  r0.start = Vec3(3, 0, 3);
  r0.motions = {motion("v1", Vec3(2, 0, 3), 8, Termination::kSticking),
                motion("v2", Vec3(-1.5, 0, 0), 3, Termination::kSticking)};
  r0.success = true;
  RolloutOutcome r1;
  r1.index = 1;
  r1.start = Vec3(3, 1, 3);
  r1.motions = {motion("v1", Vec3(4, 1, 3), 8, Termination::kSticking),
                motion("v2", Vec3(5, 1, 3), 8, Termination::kNone)};
  RolloutOutcome r2;
  r2.index = 2;
  r2.start = Vec3(3, -1, 3);
  r2.end = Vec3(3, -1, 3.5);
  r2.unstable = true;
  r2.termination = Termination::kUnstable;
  v.rollouts = {r0, r1, r2};
  auto end = [](int rollout, int m, bool inside, double distance) {
    ObservedEnd e;
    e.rollout = rollout;
    e.motion = m;
    e.inside = inside;
    e.distance = distance;
    return e;
  };
  v.ends = {end(0, 0, true, 0), end(0, 1, true, 0), end(1, 0, false, 0.25)};
  v.successes = 1;
  v.unstable = 1;
  v.outside = 1;
  v.soundness = 2.0 / 3;
  v.coverage = 0.5;
  v.coverage_radius = 0.125;
  v.contact_tolerance = 0.001;

  const UnitRecord r = unit_record(*task, v);
  EXPECT_FALSE(r.reliable);
  EXPECT_EQ(r.failure, v.prediction.failure);
  EXPECT_EQ(r.verify_seconds, 1.5);
  EXPECT_EQ(nlohmann::json::parse(r.verify_json)["reliable"], false);
  ASSERT_EQ(r.rollouts.size(), 5u);
  const RolloutRow& a = r.rollouts[1];  // rollout 0, motion 1: starts where motion 0 ended
  EXPECT_EQ(a.rollout, 0);
  EXPECT_EQ(a.motion, 1);
  EXPECT_EQ(a.start, (std::array<double, 3>{2, 0, 3}));
  EXPECT_EQ(a.end, (std::array<double, 3>{-1.5, 0, 0}));
  EXPECT_EQ(a.atom, 3);
  EXPECT_EQ(a.termination, "sticking");
  EXPECT_EQ(a.inside, true);
  EXPECT_EQ(a.distance, 0.0);
  EXPECT_TRUE(a.success);
  EXPECT_EQ(r.rollouts[0].start, (std::array<double, 3>{3, 0, 3}));  // motion 0: the rollout's start
  const RolloutRow& b = r.rollouts[2];                               // rollout 1, motion 0: outside
  EXPECT_EQ(b.inside, false);
  EXPECT_EQ(b.distance, 0.25);
  EXPECT_FALSE(b.success);
  const RolloutRow& c = r.rollouts[3];  // rollout 1, motion 1: timed out, not scored
  EXPECT_EQ(c.termination, "none");
  EXPECT_FALSE(c.inside.has_value());
  EXPECT_FALSE(c.distance.has_value());
  const RolloutRow& d = r.rollouts[4];  // rollout 2: no motion
  EXPECT_EQ(d.rollout, 2);
  EXPECT_EQ(d.motion, -1);
  EXPECT_EQ(d.end, (std::array<double, 3>{3, -1, 3.5}));
  EXPECT_EQ(d.termination, "unstable");
  EXPECT_TRUE(d.unstable);

  EXPECT_EQ(r.rollout_count, 3);
  EXPECT_EQ(r.successes, 1);
  EXPECT_EQ(r.unstable, 1);
  EXPECT_EQ(r.ends, 3);
  EXPECT_EQ(r.outside, 1);
  EXPECT_EQ(r.soundness, 2.0 / 3);
  EXPECT_EQ(r.coverage, 0.5);
  EXPECT_EQ(r.coverage_radius, 0.125);
  EXPECT_EQ(r.contact_tolerance, 0.001);
  EXPECT_FALSE(r.soundness_bug);
  EXPECT_FALSE(r.counterexample.has_value());
  EXPECT_FALSE(r.sticking.has_value());
  EXPECT_EQ(r.rollout_seconds, 0.75);
}

}  // namespace
}  // namespace cmt
