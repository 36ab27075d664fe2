// Conditional strategies in rollouts (Buckley §4.2; docs/task-format.md "Conditional strategies"): the branch
// choice from one sensor reading, and two_blocks `probe` end to end against the verifier's prediction for
// every strategy node.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "models/loaded_task.h"
#include "sim/rollout.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

StrategyNode node_with_tests(bool with_else) {
  StrategyNode n;
  n.motion = std::string(1, 'm');  // not = "m": g++ 12 -Wrestrict false positive (GCC bug 105329)
  StrategyBranch in_box;
  in_box.when.position.push_back({Vec3(0, 0, 0), Vec3(1, 1, 1)});
  in_box.first = 1;
  StrategyBranch pushed_up;
  pushed_up.when.force.push_back({Vec3::UnitZ(), 0.3});
  pushed_up.first = 2;
  n.branches = {in_box, pushed_up};
  if (with_else) {
    StrategyBranch otherwise;
    otherwise.otherwise = true;
    n.branches.push_back(otherwise);
  }
  return n;
}

TEST(ChooseBranch, FirstPassingTestWinsElseCatchesTheRest) {
  const StrategyNode n = node_with_tests(true);
  const Vec3 up(0, 0, 5), sideways(5, 0, 0);
  EXPECT_EQ(choose_branch(n, Vec3(0.5, 0.5, 0.5), up), 0);        // both pass: the first wins
  EXPECT_EQ(choose_branch(n, Vec3(0.5, 0.5, 0.5), sideways), 0);  // position only
  EXPECT_EQ(choose_branch(n, Vec3(2, 0.5, 0.5), up), 1);          // force only
  EXPECT_EQ(choose_branch(n, Vec3(2, 0.5, 0.5), Vec3(1, 0, 4)),
            1);  // atan(1/4) = .245 rad from +z: inside .3
  EXPECT_EQ(choose_branch(n, Vec3(2, 0.5, 0.5), Vec3(1, 0, 3)), 2);  // atan(1/3) = .322 rad: outside, else
  EXPECT_EQ(choose_branch(n, Vec3(2, 0.5, 0.5), Vec3::Zero()), 2);   // no contact force: no force test passes
  EXPECT_EQ(choose_branch(node_with_tests(false), Vec3(2, 0.5, 0.5), sideways), -1);
  // A test with both sets needs both.
  StrategyNode both;
  StrategyBranch b;
  b.when.position.push_back({Vec3(0, 0, 0), Vec3(1, 1, 1)});
  b.when.force.push_back({Vec3::UnitZ(), 0.3});
  both.branches = {b};
  EXPECT_EQ(choose_branch(both, Vec3(0.5, 0.5, 0.5), up), 0);
  EXPECT_EQ(choose_branch(both, Vec3(0.5, 0.5, 0.5), sideways), -1);
  EXPECT_EQ(choose_branch(both, Vec3(2, 0.5, 0.5), up), -1);
}

// two_blocks `probe` (models/tasks/two_blocks.yaml): v3 may stick on B's top (z = 3) or slide into the gap
// floor; a reading near the gap floor stops (branch 0), any other runs v2 (branch 1, node 1), which slides
// into the gap. The test box extends more than eps_s = .2 beyond the gap floor and B's top lies 2.5 above
// it, so branch 0 is taken exactly when v3 ended in the gap.
TEST(ConditionalRollout, TwoBlocksProbeTakesBothBranchesAndEndsInsideThePredictedSets) {
  const auto task = load_task(std::filesystem::path(CMT_SOURCE_DIR) / "models/tasks/two_blocks.yaml");
  const Strategy& probe = *task->task.find_strategy("probe");
  SimOptions options;
  options.form = ControllerForm::kImpedance;  // the form the verifier's theta_v bounds (docs/validation.md)
  const auto scene = RolloutScene::build(task, options);
  const int n = 24;
  const auto one = run_rollouts(scene, probe, n, 1, 1);
  const auto two = run_rollouts(scene, probe, n, 1, 2);
  const VerifyResult predicted = verify_strategy(*task, probe);
  ASSERT_TRUE(predicted.reliable) << predicted.failure;
  int stopped = 0, slid_on = 0;
  for (int i = 0; i < n; ++i) {
    const RolloutOutcome& r = one[static_cast<std::size_t>(i)];
    ASSERT_FALSE(r.unstable) << r.unstable_reason;
    EXPECT_TRUE(r.success) << i;
    EXPECT_FALSE(r.no_branch);
    ASSERT_GE(r.motions.size(), 1u);
    const MotionOutcome& first = r.motions[0];
    EXPECT_EQ(first.node, 0);
    const bool in_gap = std::abs(first.end.x()) <= 1.5 + scene->atom_tolerance() &&
                        std::abs(first.end.z()) <= scene->atom_tolerance();
    if (first.branch == 0) {
      ++stopped;
      EXPECT_TRUE(in_gap) << i << ": " << first.end.transpose();
      EXPECT_EQ(r.motions.size(), 1u);
    } else {
      ++slid_on;
      EXPECT_EQ(first.branch, 1) << i;
      EXPECT_FALSE(in_gap) << i << ": " << first.end.transpose();
      ASSERT_EQ(r.motions.size(), 2u) << i;
      EXPECT_EQ(r.motions[1].node, 1);
      EXPECT_EQ(r.motions[1].motion, "v2");
      EXPECT_EQ(r.motions[1].branch, -1);
    }
    // Every motion ends in the prediction for its node (within the rollouts' contact tolerance).
    for (const MotionOutcome& m : r.motions) {
      const VerifyStep* step = predicted.step_of_node(m.node);
      ASSERT_NE(step, nullptr) << i;
      EXPECT_LE(step->termination.distance(m.end), scene->atom_tolerance()) << i << " " << m.motion;
    }
    // Thread count changes nothing, the branch choice included.
    const RolloutOutcome& s = two[static_cast<std::size_t>(i)];
    ASSERT_EQ(s.motions.size(), r.motions.size());
    for (std::size_t k = 0; k < r.motions.size(); ++k) {
      EXPECT_EQ(s.motions[k].end, r.motions[k].end);
      EXPECT_EQ(s.motions[k].branch, r.motions[k].branch);
    }
  }
  EXPECT_GT(stopped, 0);
  EXPECT_GT(slid_on, 0);
}

}  // namespace
}  // namespace cmt
