// Buckley's planner over sticking arcs (verifier/planner/search.h) on §6.3.1: the cube, start a top edge,
// goal the bottom, one spring motion that sticks on the bottom; the planned motion is reliable under the
// verifier (an independent algorithm) from the closed start edge.
#include "verifier/planner/search.h"

#include <gtest/gtest.h>

#include "controllers/termination.h"
#include "models/loaded_task.h"
#include "verifier/planner/task_atoms.h"
#include "verifier/planner/verifier_check.h"
#include "verifier/verify.h"

namespace cmt::planner {
namespace {

std::shared_ptr<const LoadedTask> cube() {
  static const auto t = load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/cube.yaml");
  return t;
}

// The rollouts' model without contact lift and servo coast (`cmt plan` adds those).
VerifyOptions options() {
  VerifyOptions o;
  o.spring_model = SpringModel::kVelocity;
  o.stop_relative_speed = kStopRelativeSpeed;
  return o;
}

PlanRequest request_for(const LoadedTask& task) {
  PlanRequest r;
  r.start_atoms = start_atoms(task);
  r.goal_atom = goal_atoms(task);
  r.eps_s = task.task.uncertainty.eps_s;
  r.theta_f = task.task.uncertainty.theta_f;
  r.confirm = [&task](const State& from, const Vec3& commanded) {
    return verifier_targets(task, from, commanded, options());
  };
  return r;
}

// The spring motion to `commanded` verified from the task's start.
VerifyResult verify_commanded(const LoadedTask& task, const Vec3& commanded) {
  LoadedTask with = task;
  Motion m;
  m.name = "planned_1";
  m.kind = Motion::Kind::kSpring;
  m.target = commanded;
  with.task.motions.push_back(m);
  return verify_strategy(with, Strategy::sequence("planned", {"planned_1"}), options());
}

TEST(CubeStartAndGoal, TheTopEdgeStartsAndTheClosedBottomIsTheGoal) {
  const auto& t = *cube();
  const std::vector<int> start = start_atoms(t);
  ASSERT_EQ(start.size(), 1u);
  EXPECT_EQ(t.cspace.atom_kind(start[0]), AtomKind::kEdge);
  const std::vector<bool> goal = goal_atoms(t);
  EXPECT_EQ(std::count(goal.begin(), goal.end(), true), 9);  // the bottom face, its 4 edges, its 4 vertices
}

TEST(CubePlan, OneMotionSticksOnTheBottomAndTheVerifierAgrees) {
  const auto& t = *cube();
  AtomSimulation simulation(t.cspace, t.task.uncertainty);
  const PlanResult plan = plan_sticking(simulation, t.cspace, request_for(t));
  ASSERT_TRUE(plan.found) << plan.reason;
  ASSERT_EQ(plan.steps.size(), 1u);
  EXPECT_TRUE(plan.decision_free);
  const GraphArc& arc = plan.steps[0].arc;
  EXPECT_TRUE(arc.arc.cpositions.contains(arc.commanded));
  EXPECT_LT(arc.commanded.z(), -1.0);  // below the bottom's plane
  const VerifyResult v = verify_commanded(t, arc.commanded);
  EXPECT_TRUE(v.reliable) << v.failure << " at " << arc.commanded.transpose();
}

}  // namespace
}  // namespace cmt::planner

namespace cmt::planner {
namespace {

PlanRequest chain_request_for(const LoadedTask& task) {
  PlanRequest r = request_for(task);
  r.confirm = nullptr;
  return r;
}

TEST(CubePlanChainCheck, TheVerifiedChainIsAcceptedAtOnce) {
  const auto& t = *cube();
  AtomSimulation simulation(t.cspace, t.task.uncertainty);
  PlanRequest r = chain_request_for(t);
  r.confirm_chain = [&t](const std::vector<Vec3>& commanded) {
    return verifier_chain(t, commanded, options());
  };
  const PlanResult plan = plan_sticking(simulation, t.cspace, r);
  ASSERT_TRUE(plan.found) << plan.reason;
  EXPECT_EQ(plan.chains_checked, 1);
  EXPECT_EQ(plan.confirmed, 1);
  ASSERT_EQ(plan.steps.size(), 1u);
  EXPECT_TRUE(verify_commanded(t, plan.steps[0].arc.commanded).reliable);
}

TEST(CubePlanChainCheck, AMotionThatMayFailMovesItsArcToItsNextCell) {
  const auto& t = *cube();
  // The first candidate when every chain is accepted.
  AtomSimulation first_simulation(t.cspace, t.task.uncertainty);
  PlanRequest accept_all = chain_request_for(t);
  accept_all.confirm_chain = [](const std::vector<Vec3>& commanded) {
    return ChainVerdict{true,
                        std::vector<std::optional<std::vector<int>>>(commanded.size(), std::vector<int>{})};
  };
  const PlanResult first = plan_sticking(first_simulation, t.cspace, accept_all);
  ASSERT_TRUE(first.found) << first.reason;
  ASSERT_EQ(first.steps.size(), 1u);
  ASSERT_FALSE(first.steps[0].arc.alternatives.empty());  // the cube's first arc has several cells

  // The same search, the first candidate refuted as "may fail" (e.g. slide forever).
  AtomSimulation simulation(t.cspace, t.task.uncertainty);
  PlanRequest r = chain_request_for(t);
  int calls = 0;
  r.confirm_chain = [&](const std::vector<Vec3>&) {
    ChainVerdict v;
    v.reliable = ++calls > 1;
    v.ends = {v.reliable ? std::optional<std::vector<int>>(std::vector<int>{}) : std::nullopt};
    return v;
  };
  const PlanResult plan = plan_sticking(simulation, t.cspace, r);
  ASSERT_TRUE(plan.found) << plan.reason;
  EXPECT_EQ(plan.chains_checked, 2);
  EXPECT_EQ(plan.rejected, 1);
  ASSERT_EQ(plan.steps.size(), 1u);
  EXPECT_EQ(plan.steps[0].state, first.steps[0].state);
  EXPECT_EQ(plan.steps[0].arc_index, first.steps[0].arc_index);  // the same arc ...
  EXPECT_EQ(plan.steps[0].arc.arc.targets, first.steps[0].arc.arc.targets);
  EXPECT_EQ(plan.steps[0].arc.commanded,
            first.steps[0].arc.alternatives.front().second.point);  // ... next cell
}

TEST(CubePlanChainCheck, WideningByTheVerifierAddsTheTargetsToTheArc) {
  const auto& t = *cube();
  AtomSimulation simulation(t.cspace, t.task.uncertainty);
  PlanRequest r = chain_request_for(t);
  const std::vector<int> start = start_atoms(t);  // a top edge: not in the goal
  int calls = 0;
  r.confirm_chain = [&](const std::vector<Vec3>&) {
    ChainVerdict v;
    v.reliable = ++calls > 1;
    v.ends = {start};  // first: "may also stop where it started"
    return v;
  };
  const PlanResult plan = plan_sticking(simulation, t.cspace, r);
  EXPECT_EQ(plan.widened, 1);
  ASSERT_TRUE(plan.found) << plan.reason;
  EXPECT_EQ(plan.chains_checked, 2);
  // The widened arc may also end in the start edge, which sensing tells apart from the bottom: its heads
  // branch, so it is dropped and another arc is planned.
  for (const PlanStep& step : plan.steps)
    EXPECT_FALSE(
        std::includes(step.arc.arc.targets.begin(), step.arc.arc.targets.end(), start.begin(), start.end()));
}

TEST(CubePlanChainCheck, TheCheckLimitEndsASearchWhoseChainsAllFail) {
  const auto& t = *cube();
  AtomSimulation simulation(t.cspace, t.task.uncertainty);
  PlanRequest r = chain_request_for(t);
  r.max_chain_checks = 3;
  r.confirm_chain = [](const std::vector<Vec3>&) { return ChainVerdict{false, {std::nullopt}}; };
  const PlanResult plan = plan_sticking(simulation, t.cspace, r);
  EXPECT_FALSE(plan.found) << plan.steps.size() << " steps, decision free " << plan.decision_free << ", "
                           << plan.chains_checked << " checks";
  EXPECT_EQ(plan.chains_checked, 3);
  EXPECT_NE(plan.reason.find("check limit"), std::string::npos) << plan.reason;
}

}  // namespace
}  // namespace cmt::planner
