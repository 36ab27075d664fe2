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
