// Buckley's planner over sticking arcs (verifier/planner/search.h) on §6.3.1: the cube, start a top edge,
// goal the bottom, one spring motion that sticks on the bottom; the planned motion is reliable under the
// verifier (an independent algorithm) from the closed start edge.
#include "verifier/planner/search.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

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

// The simulation alone (no check in the search): its plan is one motion the verifier finds reliable.
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

// The chain check left to each test's script, with room for many scripted refutations.
PlanRequest scripted_request_for(const LoadedTask& task) {
  PlanRequest r = request_for(task);
  r.max_chain_checks = 1000;
  return r;
}

// The cube's bottom face: the first goal atom (faces come first).
int bottom_face(const LoadedTask& task) {
  const std::vector<bool> goal = goal_atoms(task);
  const int bottom = static_cast<int>(std::find(goal.begin(), goal.end(), true) - goal.begin());
  EXPECT_EQ(task.cspace.atom_kind(bottom), AtomKind::kFace);
  return bottom;
}

// Every step whose arc is a start projection is at the root: a start state with every motion still to go.
void expect_projections_at_root(const PlanResult& plan, const PlanRequest& r) {
  for (const PlanStep& step : plan.steps) {
    if (!step.arc.from_start_projection) continue;
    EXPECT_EQ(step.motions_left, r.max_motions);
    EXPECT_NE(std::find(plan.start_states.begin(), plan.start_states.end(), step.state),
              plan.start_states.end());
  }
}

// With the verifier's chain check (tests replace it where they script its verdicts).
PlanRequest chain_request_for(const LoadedTask& task) {
  PlanRequest r = request_for(task);
  r.confirm_chain = [&task](const std::vector<Vec3>& commanded) {
    return verifier_chain(task, commanded, options());
  };
  return r;
}

TEST(CubePlanChainCheck, TheVerifiedChainIsAcceptedAtOnce) {
  const auto& t = *cube();
  AtomSimulation simulation(t.cspace, t.task.uncertainty);
  PlanRequest r = chain_request_for(t);
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

// A refutation at the last motion of a chain moves that motion's arc to its next cell and leaves the arcs
// before it as they were. The scripted check refutes every one-motion chain (so a longer plan is needed) and
// the first longer chain at its last motion.
TEST(CubePlanChainCheck, ARefutationAtALaterMotionMovesThatMotionsArc) {
  const auto& t = *cube();
  AtomSimulation simulation(t.cspace, t.task.uncertainty);
  PlanRequest r = chain_request_for(t);
  r.max_chain_checks = 2000;
  std::vector<std::vector<Vec3>> longer;
  r.confirm_chain = [&](const std::vector<Vec3>& commanded) {
    if (commanded.size() < 2) return ChainVerdict{false, {std::nullopt}};
    longer.push_back(commanded);
    ChainVerdict v{longer.size() > 1,
                   std::vector<std::optional<std::vector<int>>>(commanded.size(), std::vector<int>{})};
    if (!v.reliable) v.ends.back() = std::nullopt;
    return v;
  };
  const PlanResult plan = plan_sticking(simulation, t.cspace, r);
  ASSERT_TRUE(plan.found) << plan.reason;
  ASSERT_EQ(longer.size(), 2u);
  const std::vector<Vec3>& first = longer[0];
  const std::vector<Vec3>& second = longer[1];
  ASSERT_EQ(second.size(), first.size());
  for (std::size_t i = 0; i + 1 < first.size(); ++i) EXPECT_EQ(second[i], first[i]) << i;  // kept
  EXPECT_NE(second.back(), first.back());  // the last motion's arc moved to its next cell
  ASSERT_EQ(plan.steps.size(), second.size());
  for (std::size_t i = 0; i < second.size(); ++i) EXPECT_EQ(plan.steps[i].arc.commanded, second[i]);
  EXPECT_EQ(plan.steps.back().arc.commanded, plan.steps.back().arc.arc.cpositions.interior_point()->point);
  EXPECT_EQ(plan.widened, 0);
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

namespace cmt::planner {
namespace {

TEST(ContactSeeds, LieBehindTheFaceOnItsCentroidsNormal) {
  const auto& t = *cube();
  const double unit = t.task.uncertainty.eps_s;
  for (const Face& f : t.cspace.faces()) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& v : f.polygon) c += v;
    c /= static_cast<double>(f.polygon.size());
    const std::vector<Vec3> seeds = contact_seeds(f, unit);
    ASSERT_EQ(seeds.size(), std::size(kContactSeedDepths));
    for (std::size_t i = 0; i < seeds.size(); ++i) {
      EXPECT_NEAR(f.offset - f.normal.dot(seeds[i]), kContactSeedDepths[i] * unit, 1e-12);  // behind
      EXPECT_LT((seeds[i] - c - f.normal * f.normal.dot(seeds[i] - c)).norm(), 1e-12);      // on the centroid
    }
  }
}

// With start_targets, the start state gets arcs whose targets are the projection's from the start region
// itself, one new target set per round, after the simulation's arcs at the same goal distance. Here the
// projection stops every motion on the bottom and the check refutes every chain whose first motion is not a
// projection's: the simulation's arcs from the start move through their cells and are rejected, and the
// first seed's arc is planned (its chain given to the check as it is: no cell is claimed).
TEST(CubePlanStartProjection, AProjectedArcIsPlannedWhenTheSimulationsArcsAreRefuted) {
  const auto& t = *cube();
  AtomSimulation simulation(t.cspace, t.task.uncertainty);
  PlanRequest r = scripted_request_for(t);
  const int bottom = bottom_face(t);
  std::vector<Vec3> asked;
  r.start_targets = [&](const Vec3& commanded) -> std::optional<std::vector<int>> {
    asked.push_back(commanded);
    return std::vector<int>{bottom};
  };
  std::vector<std::vector<Vec3>> checked;
  r.confirm_chain = [&](const std::vector<Vec3>& commanded) {
    checked.push_back(commanded);
    if (std::find(asked.begin(), asked.end(), commanded[0]) == asked.end())
      return ChainVerdict{false, {std::nullopt}};
    return ChainVerdict{true, {std::vector<int>{bottom}}};
  };
  const PlanResult plan = plan_sticking(simulation, t.cspace, r);
  ASSERT_TRUE(plan.found) << plan.reason;
  EXPECT_EQ(plan.start_projections, static_cast<int>(asked.size()));
  EXPECT_GT(plan.chains_checked, 1);  // the simulation's first arc came first
  ASSERT_EQ(plan.steps.size(), 1u);
  const GraphArc& arc = plan.steps[0].arc;
  EXPECT_TRUE(arc.from_start_projection);
  EXPECT_EQ(arc.commanded, asked[0]);
  EXPECT_EQ(arc.arc.targets, std::vector<int>{bottom});
  EXPECT_TRUE(arc.arc.cpositions.pieces().empty());
  ASSERT_FALSE(checked.empty());
  EXPECT_EQ(checked.back(), std::vector<Vec3>{asked[0]});
  expect_projections_at_root(plan, r);
  // The first seed is behind a goal face: the bottom (the cube's only goal face).
  const std::vector<Vec3> behind_bottom =
      contact_seeds(t.cspace.faces()[static_cast<std::size_t>(bottom)], t.task.uncertainty.eps_s);
  EXPECT_NE(std::find(behind_bottom.begin(), behind_bottom.end(), asked[0]), behind_bottom.end())
      << asked[0].transpose();
}

// A projection that may fail (nothing) makes no arc: the next seed's is planned.
TEST(CubePlanStartProjection, AProjectionThatMayFailMakesNoArc) {
  const auto& t = *cube();
  AtomSimulation simulation(t.cspace, t.task.uncertainty);
  PlanRequest r = scripted_request_for(t);
  const int bottom = bottom_face(t);
  std::vector<Vec3> asked;
  r.start_targets = [&](const Vec3& commanded) -> std::optional<std::vector<int>> {
    asked.push_back(commanded);
    if (asked.size() == 1) return std::nullopt;
    return std::vector<int>{bottom};
  };
  r.confirm_chain = [&](const std::vector<Vec3>& commanded) {
    if (asked.size() < 2 || commanded[0] != asked[1]) return ChainVerdict{false, {std::nullopt}};
    return ChainVerdict{true, {std::vector<int>{bottom}}};
  };
  const PlanResult plan = plan_sticking(simulation, t.cspace, r);
  ASSERT_TRUE(plan.found) << plan.reason;
  ASSERT_GE(asked.size(), 2u);
  ASSERT_EQ(plan.steps.size(), 1u);
  EXPECT_TRUE(plan.steps[0].arc.from_start_projection);
  EXPECT_EQ(plan.steps[0].arc.commanded, asked[1]);
  expect_projections_at_root(plan, r);
}

// A candidate that branches on sensed states is not a chain. Every projection may stop on the bottom or on
// one of the four walls (two states the robot tells apart by the force's direction), and a wall goes on to
// the bottom by the simulation's arcs; the check refutes every chain. So the search's candidates once the
// walls are expanded branch at their first motion. With the chain check set, each branching arc is rejected
// without a verifier call (strategies with tests are not written), and the search ends at its limit with
// nothing found instead of returning a branching plan.
TEST(CubePlanStartProjection, ABranchingCandidateLosesItsBranchingArc) {
  const auto& t = *cube();
  AtomSimulation simulation(t.cspace, t.task.uncertainty);
  PlanRequest r = scripted_request_for(t);
  r.max_expansions = 8;
  const int bottom = bottom_face(t);
  const Confusability confusable(t.cspace, t.task.uncertainty.eps_s, t.task.uncertainty.theta_f);
  std::vector<std::vector<int>> branching;
  for (const Face& f : t.cspace.faces())
    if (std::abs(f.normal.z()) < 0.5) {
      std::vector<int> targets = {bottom, f.id};
      std::sort(targets.begin(), targets.end());
      ASSERT_EQ(confusable_sets(confusable, targets).size(), 2u);
      branching.push_back(targets);
    }
  ASSERT_EQ(branching.size(), 4u);
  std::vector<Vec3> asked;
  r.start_targets = [&](const Vec3& commanded) -> std::optional<std::vector<int>> {
    asked.push_back(commanded);
    return branching[(asked.size() - 1) % branching.size()];
  };
  std::vector<std::vector<Vec3>> checked;
  r.confirm_chain = [&](const std::vector<Vec3>& commanded) {
    checked.push_back(commanded);
    return ChainVerdict{false, {std::nullopt}};
  };
  const PlanResult plan = plan_sticking(simulation, t.cspace, r);
  EXPECT_FALSE(plan.found);
  EXPECT_EQ(plan.expanded, r.max_expansions);
  EXPECT_NE(plan.reason.find("expansion limit"), std::string::npos) << plan.reason;
  EXPECT_FALSE(asked.empty());
  EXPECT_FALSE(checked.empty());     // the simulation's chains were checked (and refuted)
  for (const auto& chain : checked)  // the branching candidates never reached the verifier
    EXPECT_EQ(std::find(asked.begin(), asked.end(), chain.front()), asked.end()) << chain.front().transpose();
}

// A projected arc the chain check refutes takes the next seed with the same targets as its command.
TEST(CubePlanStartProjection, ARefutedProjectionTakesTheNextSeedWithItsTargets) {
  const auto& t = *cube();
  AtomSimulation simulation(t.cspace, t.task.uncertainty);
  PlanRequest r = scripted_request_for(t);
  const int bottom = bottom_face(t);
  std::vector<Vec3> asked;
  r.start_targets = [&](const Vec3& commanded) -> std::optional<std::vector<int>> {
    asked.push_back(commanded);
    return std::vector<int>{bottom};
  };
  std::vector<Vec3> projected_checked;
  r.confirm_chain = [&](const std::vector<Vec3>& commanded) {
    if (std::find(asked.begin(), asked.end(), commanded[0]) == asked.end())
      return ChainVerdict{false, {std::nullopt}};  // the simulation's arcs
    projected_checked.push_back(commanded[0]);
    if (commanded[0] == asked[0]) return ChainVerdict{false, {std::nullopt}};
    return ChainVerdict{true, {std::vector<int>{bottom}}};
  };
  const PlanResult plan = plan_sticking(simulation, t.cspace, r);
  ASSERT_TRUE(plan.found) << plan.reason;
  ASSERT_GE(asked.size(), 2u);
  EXPECT_EQ(projected_checked, (std::vector<Vec3>{asked[0], asked[1]}));
  ASSERT_EQ(plan.steps.size(), 1u);
  EXPECT_TRUE(plan.steps[0].arc.from_start_projection);
  EXPECT_EQ(plan.steps[0].arc.commanded, asked[1]);
  EXPECT_EQ(plan.steps[0].arc.arc.targets, std::vector<int>{bottom});
  expect_projections_at_root(plan, r);
}

// No projection is paid for when the simulation's arcs from the start are accepted at once.
TEST(CubePlanStartProjection, NoneIsMadeWhenTheFirstCandidateHolds) {
  const auto& t = *cube();
  AtomSimulation simulation(t.cspace, t.task.uncertainty);
  PlanRequest r = chain_request_for(t);
  r.confirm_chain = [](const std::vector<Vec3>&) { return ChainVerdict{true, {std::vector<int>{}}}; };
  int asked = 0;
  r.start_targets = [&](const Vec3&) -> std::optional<std::vector<int>> {
    ++asked;
    return std::nullopt;
  };
  const PlanResult plan = plan_sticking(simulation, t.cspace, r);
  ASSERT_TRUE(plan.found) << plan.reason;
  EXPECT_EQ(asked, 0);
  EXPECT_EQ(plan.start_projections, 0);
  ASSERT_EQ(plan.steps.size(), 1u);
  EXPECT_FALSE(plan.steps[0].arc.from_start_projection);
}

// A side face of the cube (horizontal normal) that touches the bottom.
int side_face(const LoadedTask& task) {
  for (const Face& f : task.cspace.faces())
    if (std::abs(f.normal.z()) < 1e-12) return f.id;
  ADD_FAILURE() << "no side face";
  return 0;
}

// Chains of projections: the start projection stops every motion on a side face (not a goal) and only a
// chain through one edge seed reaches the bottom. The projection's arc gets that seed's continuation, with
// the second motion's verified stops as targets, and the plan is the two (the projection, then the
// continuation from its head); the simulation's arcs from the side face are refuted.
TEST(CubePlanChainProjection, AStartProjectionsHeadContinuesAtTheSeedWhoseChainReachesTheGoal) {
  const auto& t = *cube();
  AtomSimulation simulation(t.cspace, t.task.uncertainty);
  PlanRequest r = scripted_request_for(t);
  const int bottom = bottom_face(t), side = side_face(t);
  const std::vector<Vec3> seeds = chain_seeds(t.cspace, r.goal_atom, r.eps_s);
  const Vec3 good = seeds[5];  // an edge seed: the bottom's contact seeds come first
  std::vector<Vec3> asked;
  r.start_targets = [&](const Vec3& commanded) -> std::optional<std::vector<int>> {
    asked.push_back(commanded);
    return std::vector<int>{side};
  };
  std::vector<std::vector<Vec3>> chains;
  r.confirm_chain = [&](const std::vector<Vec3>& commanded) {
    chains.push_back(commanded);
    const bool projected = std::find(asked.begin(), asked.end(), commanded[0]) != asked.end();
    if (!projected) return ChainVerdict{false, {std::nullopt}};
    if (commanded.size() < 2) return ChainVerdict{false, {std::vector<int>{side}}};
    if (commanded[1] != good) return ChainVerdict{false, {std::vector<int>{side}, std::nullopt}};
    return ChainVerdict{true, {std::vector<int>{side}, std::vector<int>{bottom}}};
  };
  const PlanResult plan = plan_sticking(simulation, t.cspace, r);
  ASSERT_TRUE(plan.found) << plan.reason;
  ASSERT_EQ(plan.steps.size(), 2u);
  EXPECT_TRUE(plan.steps[0].arc.from_start_projection);
  EXPECT_EQ(plan.steps[0].arc.commanded, asked[0]);
  const GraphArc& next = plan.steps[1].arc;
  EXPECT_TRUE(next.from_chain_projection);
  EXPECT_EQ(plan.steps[1].state, std::vector<int>{side});
  EXPECT_EQ(plan.steps[1].motions_left, r.max_motions - 1);
  EXPECT_EQ(next.commanded, good);
  EXPECT_EQ(next.arc.targets, std::vector<int>{bottom});
  EXPECT_TRUE(next.arc.cpositions.pieces().empty());
  EXPECT_TRUE(plan.decision_free);
  EXPECT_TRUE(plan.chain_verified);
  EXPECT_GE(plan.chain_projections, 6);  // the seeds before the good one were tried (after asked[0])
  // The chain projections are the projection's command followed by the seeds in order (other chains through
  // it are candidates with the simulation's arcs from the side face); the accepted chain was verified once
  // (the continuation's verdict is reused for the candidate).
  std::vector<Vec3> tried;
  for (const auto& c : chains)
    if (c.size() == 2 && c[0] == asked[0] && std::find(seeds.begin(), seeds.end(), c[1]) != seeds.end())
      tried.push_back(c[1]);
  ASSERT_GE(tried.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(tried[i], seeds[i]);
  EXPECT_EQ(std::count(tried.begin(), tried.end(), good), 1);
}

// Turned off, no continuation is made: the same script finds no plan through the good seed.
TEST(CubePlanChainProjection, NoneAreMadeWhenTurnedOff) {
  const auto& t = *cube();
  AtomSimulation simulation(t.cspace, t.task.uncertainty);
  PlanRequest r = scripted_request_for(t);
  r.chain_projections = false;
  r.max_expansions = 10;
  r.max_chain_checks = 20;
  const int bottom = bottom_face(t), side = side_face(t);
  const Vec3 good = chain_seeds(t.cspace, r.goal_atom, r.eps_s)[5];
  std::vector<Vec3> asked;
  r.start_targets = [&](const Vec3& commanded) -> std::optional<std::vector<int>> {
    asked.push_back(commanded);
    return std::vector<int>{side};
  };
  int through_good = 0;
  r.confirm_chain = [&](const std::vector<Vec3>& commanded) {
    if (commanded.size() == 2 && commanded[1] == good) ++through_good;
    if (commanded.size() < 2 || commanded[1] != good) return ChainVerdict{false, {std::nullopt}};
    return ChainVerdict{true, {std::vector<int>{side}, std::vector<int>{bottom}}};
  };
  const PlanResult plan = plan_sticking(simulation, t.cspace, r);
  EXPECT_FALSE(plan.found);
  EXPECT_EQ(plan.chain_projections, 0);
  EXPECT_EQ(through_good, 0);
  EXPECT_FALSE(asked.empty());  // the start projections still ran
}

// The chain seeds: the contact seeds behind each goal face, then, shallow pairs first, one seed per edge of
// the goal faces, behind both of the edge's faces by kEdgeSeedDepths times the unit.
TEST(ChainSeeds, BehindTheGoalFacesThenBehindTheirEdges) {
  const auto& t = *cube();
  const double unit = t.task.uncertainty.eps_s;
  const int bottom = bottom_face(t);
  const Face& b = t.cspace.faces()[static_cast<std::size_t>(bottom)];
  const std::vector<Vec3> seeds = chain_seeds(t.cspace, goal_atoms(t), unit);
  ASSERT_EQ(seeds.size(), std::size(kContactSeedDepths) + b.edges.size() * std::size(kEdgeSeedDepths));
  const std::vector<Vec3> behind = contact_seeds(b, unit);
  for (std::size_t i = 0; i < behind.size(); ++i) EXPECT_EQ(seeds[i], behind[i]);
  for (std::size_t k = 0; k < std::size(kEdgeSeedDepths); ++k)
    for (std::size_t e = 0; e < b.edges.size(); ++e) {
      const Edge& edge = t.cspace.edges()[static_cast<std::size_t>(b.edges[e]) - t.cspace.faces().size()];
      ASSERT_EQ(edge.faces.size(), 2u);
      const Vec3 p = seeds[behind.size() + k * b.edges.size() + e];
      const Vec3 middle = (edge.a + edge.b) / 2;
      for (int j = 0; j < 2; ++j) {  // the cube's faces at an edge are perpendicular
        const Face& f = t.cspace.faces()[static_cast<std::size_t>(edge.faces[static_cast<std::size_t>(j)])];
        EXPECT_NEAR(f.normal.dot(middle - p), kEdgeSeedDepths[k][j] * unit, 1e-12);
      }
    }
}

}  // namespace
}  // namespace cmt::planner

namespace cmt::planner {
namespace {

std::shared_ptr<const LoadedTask> hole() {
  static const auto t = load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/hole.yaml");
  return t;
}

// The face of `cspace` whose vertex centroid is c.
const Face& face_at(const CSpace& cspace, const Vec3& c) {
  for (const Face& f : cspace.faces()) {
    Vec3 m = Vec3::Zero();
    for (const Vec3& v : f.polygon) m += v;
    if ((m / static_cast<double>(f.polygon.size()) - c).norm() < 1e-12) return f;
  }
  ADD_FAILURE() << "no face centred at " << c.transpose();
  return cspace.faces().front();
}

// The hole's walls seen from the start segment's middle (0, -3, 0): the far wall y = 1 (normal -y) is met
// head on, the side walls x = -1 and x = 1 obliquely, the near wall y = -1 (normal +y) looks away; the
// bottom (normal +z) is met at the angle of (0, 3, -2).
TEST(ProjectionSeedOrder, TheHolesWallsByHowSquarelyThePullFromTheStartMeetsThem) {
  const CSpace& c = hole()->cspace;
  const Vec3 start(0, -3, 0);
  EXPECT_NEAR(projection_seed_order(face_at(c, {0, 1, -1}), start), 4 / std::sqrt(17.0), 1e-12);
  EXPECT_NEAR(projection_seed_order(face_at(c, {-1, 0, -1}), start), 1 / std::sqrt(11.0), 1e-12);
  EXPECT_NEAR(projection_seed_order(face_at(c, {1, 0, -1}), start), 1 / std::sqrt(11.0), 1e-12);
  EXPECT_NEAR(projection_seed_order(face_at(c, {0, -1, -1}), start), -2 / std::sqrt(5.0), 1e-12);
  EXPECT_NEAR(projection_seed_order(face_at(c, {0, 0, -2}), start), 2 / std::sqrt(13.0), 1e-12);
  EXPECT_EQ(projection_seed_order(face_at(c, {0, 1, -1}), {0, 1, -1}), 0);  // the start at the centroid
}

// The seeds the start projections are asked for, in order, when every projection may fail (so the search
// asks for all of them): the goal's (the bottom's) first, then at equal goal distance (the four walls touch
// the bottom) the far wall's, the side walls', the near wall's last; without a start point the walls come
// by face id.
std::vector<Vec3> asked_projection_seeds(const std::optional<Vec3>& start_point) {
  const LoadedTask& t = *hole();
  AtomSimulation simulation(t.cspace, t.task.uncertainty);
  PlanRequest r = request_for(t);
  r.max_expansions = 1;
  r.chain_projections = false;
  r.start_point = start_point;
  std::vector<Vec3> asked;
  r.start_targets = [&](const Vec3& commanded) -> std::optional<std::vector<int>> {
    asked.push_back(commanded);
    return std::nullopt;
  };
  r.confirm_chain = [](const std::vector<Vec3>&) { return ChainVerdict{false, {std::nullopt}}; };
  plan_sticking(simulation, t.cspace, r);
  return asked;
}

std::vector<Vec3> seeds_behind(const Vec3& centroid) {
  const LoadedTask& t = *hole();
  return contact_seeds(face_at(t.cspace, centroid), t.task.uncertainty.eps_s);
}

TEST(HolePlanStartProjection, SeedsBehindTheFacesThePullMeetsSquarelyComeFirst) {
  // `cmt plan`'s start point: the start segment's middle.
  EXPECT_EQ(region_centroid(hole()->task.start), Vec3(0, -3, 0));
  const std::vector<Vec3> asked = asked_projection_seeds(region_centroid(hole()->task.start));
  std::vector<Vec3> expected;
  for (const Vec3& c : {Vec3(0, 0, -2), Vec3(0, 1, -1), Vec3(-1, 0, -1), Vec3(1, 0, -1), Vec3(0, -1, -1)})
    for (const Vec3& p : seeds_behind(c)) expected.push_back(p);
  ASSERT_GE(asked.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i)
    EXPECT_EQ(asked[i], expected[i]) << "seed " << i << ": " << asked[i].transpose();
}

TEST(HolePlanStartProjection, WithoutAStartPointTheWallsComeByFaceId) {
  const std::vector<Vec3> asked = asked_projection_seeds(std::nullopt);
  std::vector<Vec3> expected;
  // Face ids: x = -1 (f0), y = -1 (f2), y = 1 (f10), x = 1 (f12).
  for (const Vec3& c : {Vec3(0, 0, -2), Vec3(-1, 0, -1), Vec3(0, -1, -1), Vec3(0, 1, -1), Vec3(1, 0, -1)})
    for (const Vec3& p : seeds_behind(c)) expected.push_back(p);
  ASSERT_GE(asked.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i)
    EXPECT_EQ(asked[i], expected[i]) << "seed " << i << ": " << asked[i].transpose();
}

// The edge of `cspace` whose midpoint is m.
const Edge& edge_at(const CSpace& cspace, const Vec3& m) {
  for (const Edge& e : cspace.edges())
    if (((e.a + e.b) / 2 - m).norm() < 1e-12) return e;
  ADD_FAILURE() << "no edge with midpoint " << m.transpose();
  return cspace.edges().front();
}

// From the far wall's centroid (0, 1, -1): the bottom's near edge y = -1 (faces +z and +y) is met at the
// angle of (0, -2, -1) to its inward bisector (0, -1, -1)/sqrt 2, the side edges at (-+1, -1, -1) to
// (-+1, 0, -1)/sqrt 2, the far edge y = 1 at (0, 0, -1) to (0, 1, -1)/sqrt 2.
TEST(ChainSeedOrder, TheHolesBottomEdgesFromTheFarWall) {
  const CSpace& c = hole()->cspace;
  const Vec3 from(0, 1, -1);
  EXPECT_NEAR(edge_seed_order(c, edge_at(c, {0, -1, -2}), from), 3 / std::sqrt(10.0), 1e-12);
  EXPECT_NEAR(edge_seed_order(c, edge_at(c, {-1, 0, -2}), from), 2 / std::sqrt(6.0), 1e-12);
  EXPECT_NEAR(edge_seed_order(c, edge_at(c, {1, 0, -2}), from), 2 / std::sqrt(6.0), 1e-12);
  EXPECT_NEAR(edge_seed_order(c, edge_at(c, {0, 1, -2}), from), 1 / std::sqrt(2.0), 1e-12);
  EXPECT_EQ(edge_seed_order(c, edge_at(c, {0, -1, 0}), {0, -1, 0}), 0);  // from the midpoint itself
}

// With a point to start from, the goal's contact seeds come first, then each edge's seeds together, the
// edges the pull meets most squarely first (ties by id: the side edges in id order).
TEST(ChainSeeds, FromAPointTheEdgesThePullMeetsSquarelyComeFirst) {
  const LoadedTask& t = *hole();
  const CSpace& c = t.cspace;
  const double unit = t.task.uncertainty.eps_s;
  const std::vector<Vec3> seeds = chain_seeds(c, goal_atoms(t), unit, Vec3(0, 1, -1));
  std::vector<Vec3> expected = contact_seeds(face_at(c, {0, 0, -2}), unit);
  const Edge& left = edge_at(c, {-1, 0, -2});
  const Edge& right = edge_at(c, {1, 0, -2});
  for (const Edge* e : {&edge_at(c, {0, -1, -2}), left.id < right.id ? &left : &right,
                        left.id < right.id ? &right : &left, &edge_at(c, {0, 1, -2})})
    for (const Vec3& p : edge_seeds(c, *e, unit)) expected.push_back(p);
  EXPECT_EQ(seeds.size(), expected.size());
  for (std::size_t i = 0; i < std::min(seeds.size(), expected.size()); ++i)
    EXPECT_EQ(seeds[i], expected[i]) << "seed " << i << ": " << seeds[i].transpose();
  // Without the point: the same seeds in the shallow-pairs-first order.
  std::vector<Vec3> plain = chain_seeds(c, goal_atoms(t), unit);
  EXPECT_NE(plain, seeds);
  std::sort(plain.begin(), plain.end(), [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  std::vector<Vec3> sorted = seeds;
  std::sort(sorted.begin(), sorted.end(), [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  EXPECT_EQ(plain, sorted);
}

TEST(AtomsCentroid, MeansTheAtomsVertexCentroidsAndSkipsIdsPastTheTable) {
  const CSpace& c = hole()->cspace;
  const int wall = face_at(c, {0, 1, -1}).id;
  const int edge = edge_at(c, {0, 1, -2}).id;
  EXPECT_LT((*atoms_centroid(c, {wall, edge}) - Vec3(0, 1, -1.5)).norm(), 1e-12);
  EXPECT_LT((*atoms_centroid(c, {wall, c.atom_count()}) - Vec3(0, 1, -1)).norm(), 1e-12);
  EXPECT_FALSE(atoms_centroid(c, {c.atom_count(), c.atom_count() + 1}));
}

}  // namespace
}  // namespace cmt::planner
