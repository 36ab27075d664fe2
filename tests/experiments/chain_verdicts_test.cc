// The planner's memoized chain checks (experiments/plan/chain_verdicts.h): the text form round-trips, and
// verdicts prefetched in forked children equal those verified in this process (the plan must not depend on
// --threads).
#include "experiments/plan/chain_verdicts.h"

#include <gtest/gtest.h>

#include "controllers/termination.h"
#include "models/loaded_task.h"
#include "verifier/planner/verifier_check.h"

namespace cmt {
namespace {

TEST(ChainVerdictText, RoundTrips) {
  planner::ChainVerdict v;
  v.reliable = false;
  v.ends = {std::vector<int>{3, 7, 28}, std::vector<int>{}, std::nullopt};
  const planner::ChainVerdict back = verdict_from_text(verdict_text(v));
  EXPECT_EQ(back.reliable, v.reliable);
  EXPECT_EQ(back.ends, v.ends);
  planner::ChainVerdict r;
  r.reliable = true;
  r.ends = {std::vector<int>{1}};
  EXPECT_TRUE(verdict_from_text(verdict_text(r)).reliable);
  EXPECT_THROW(verdict_from_text(""), std::runtime_error);
}

// The verdicts on Buckley's §6.3.2 cube with its P_s (the task's p1's termination), under `cmt verify`'s
// velocity model and stop rule, `parallel` children at a time.
ChainVerdicts cube_sensing_verdicts(int parallel) {
  static const auto t = load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/cube_sensing.yaml");
  VerifyOptions options;
  options.spring_model = SpringModel::kVelocity;
  options.stop_relative_speed = kStopRelativeSpeed;
  return ChainVerdicts(*t, options, t->task.find_motion("p1")->terminate, parallel);
}

// Three one-motion chains: prefetched two at a time in children, then
// asked for, they equal the verdicts of a ChainVerdicts that verifies each in this process.
TEST(ChainVerdicts, PrefetchedInChildrenEqualVerifiedHere) {
  const std::vector<std::vector<Vec3>> chains = {
      {Vec3(0, 0, -1.7)}, {Vec3(0.5, 0, -1.7)}, {Vec3(0, 0, -1.4)}};
  ChainVerdicts forked = cube_sensing_verdicts(2), here = cube_sensing_verdicts(1);
  forked.prefetch(chains);
  EXPECT_EQ(forked.running(), 2u);  // two slots: the third is verified when asked for
  here.prefetch(chains);            // one at a time: does nothing
  EXPECT_EQ(here.running(), 0u);
  for (const auto& chain : chains) {
    const planner::ChainVerdict a = forked.get(chain), b = here.get(chain);
    EXPECT_EQ(a.reliable, b.reliable) << chain[0].transpose();
    EXPECT_EQ(a.ends, b.ends) << chain[0].transpose();
  }
  EXPECT_TRUE(here.get(chains[0]).reliable);   // the task's own p1
  EXPECT_FALSE(here.get(chains[1]).reliable);  // off centre: may stop past the goal's edge
  EXPECT_EQ(forked.running(), 0u);
}

// Chains announced but never asked for: stop() drops their children (ForkedWork's destructor kills and reaps
// them, tests/experiments/verifier_budget_test.cc), and asking afterwards verifies here.
TEST(ChainVerdicts, StopDropsTheChildrenNotAskedFor) {
  ChainVerdicts forked = cube_sensing_verdicts(2);
  forked.prefetch({{Vec3(0, 0, -1.7)}, {Vec3(0.5, 0, -1.7)}});
  EXPECT_EQ(forked.running(), 2u);
  forked.stop();
  EXPECT_EQ(forked.running(), 0u);
  EXPECT_TRUE(forked.get({Vec3(0, 0, -1.7)}).reliable);
}

}  // namespace
}  // namespace cmt
