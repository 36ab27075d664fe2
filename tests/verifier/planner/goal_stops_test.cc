// Goal stops (verifier/planner/goal_stops.h) on Buckley's §6.3.2 cube (models/tasks/cube_sensing.yaml): the
// goal is the bottom z = -1 inset by eps_s = .2 to [-.8, .8]^2, the start the bottom edge y = -1. mu = .25,
// theta_v = .25, eps_s = .2. Expected values are derived from the geometry in each test.
#include "verifier/planner/goal_stops.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "controllers/termination.h"
#include "models/loaded_task.h"
#include "verifier/atom_cone.h"
#include "verifier/planner/search.h"
#include "verifier/planner/simulation.h"
#include "verifier/planner/task_atoms.h"
#include "verifier/planner/verifier_check.h"
#include "verifier/spring.h"

namespace cmt::planner {
namespace {

std::shared_ptr<const LoadedTask> load(const std::string& name) {
  return load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/" + name + ".yaml");
}

// The face atom whose outward normal is `normal`.
int face_with_normal(const CSpace& c, const Vec3& normal) {
  for (const Face& f : c.faces())
    if ((f.normal - normal).norm() < 1e-12) return f.id;
  return -1;
}

// The rollouts' spring model without contact lift and servo coast (search_test.cc).
VerifyOptions options() {
  VerifyOptions o;
  o.spring_model = SpringModel::kVelocity;
  o.stop_relative_speed = kStopRelativeSpeed;
  return o;
}

GoalStops stops_of(const LoadedTask& t, bool sensing) {
  GoalStops s;
  s.partial_faces = partial_goal_faces(t, goal_atoms(t));
  if (sensing) {
    s.sensed_positions = goal_sensed_positions(t);
    s.senses = sensing_atoms(t, s.sensed_positions);
  }
  return s;
}

TEST(PartialGoalFaces, TheInsetGoalLiesOnTheBottomAloneWithItsFourSides) {
  const auto t = load("cube_sensing");
  const std::vector<bool> goal = goal_atoms(*t);
  EXPECT_EQ(std::count(goal.begin(), goal.end(), true), 0);  // no atom's closure is in the inset square
  const auto faces = partial_goal_faces(*t, goal);
  ASSERT_EQ(faces.size(), 1u);
  EXPECT_EQ(faces[0].atom, face_with_normal(t->cspace, Vec3::UnitZ()));  // the bottom, facing up
  ASSERT_EQ(faces[0].sides.size(), 4u);
  for (const HalfSpace& side : faces[0].sides) {
    EXPECT_NEAR(side.normal.z(), 0, 1e-12);
    EXPECT_NEAR(side.offset, 0.8, 1e-12);  // |x| <= .8, |y| <= .8
  }
  // The whole bottom is the goal of cube.yaml: its atoms are goal atoms, no face is partly in the goal.
  const auto cube = load("cube");
  EXPECT_TRUE(partial_goal_faces(*cube, goal_atoms(*cube)).empty());
}

TEST(GoalSensedPositions, TheGoalShrunkByEpsSAndTwoEpsSThick) {
  const auto t = load("cube_sensing");
  const std::vector<AxisBox> boxes = goal_sensed_positions(*t);
  ASSERT_EQ(boxes.size(), 1u);
  const double margin = kSensedSetRelativeMargin * t->cspace.scale();
  for (int k = 0; k < 2; ++k) {  // .8 - eps_s - 2 margin, to the bisection's resolution
    EXPECT_NEAR(boxes[0].max[k], 0.6 - 2 * margin, 1e-9);
    EXPECT_NEAR(boxes[0].min[k], -0.6 + 2 * margin, 1e-9);
  }
  EXPECT_DOUBLE_EQ(boxes[0].min.z(), -1.2);
  EXPECT_DOUBLE_EQ(boxes[0].max.z(), -0.8);
  // Only the bottom lies within eps_s of it (the walls and the bottom's edges are .4 away).
  const std::vector<bool> senses = sensing_atoms(*t, boxes);
  for (int a = 0; a < t->cspace.atom_count(); ++a)
    EXPECT_EQ(senses[a], a == face_with_normal(t->cspace, Vec3::UnitZ())) << t->cspace.atom_name(a);
}

// The whole closed bottom as the goal (cube.yaml): the bottom shrunk by eps_s + 2 margin; grown by eps_s +
// margin it stays a margin clear of the walls, so only the bottom is sensed. A goal square .3 wide has no
// room for a box once shrunk by eps_s on each side.
TEST(GoalSensedPositions, WallsAlongTheGoalsEdgeStayClearAndASmallGoalHasNone) {
  const auto cube = load("cube");
  const std::vector<AxisBox> boxes = goal_sensed_positions(*cube);
  ASSERT_EQ(boxes.size(), 1u);
  const double margin = kSensedSetRelativeMargin * cube->cspace.scale();
  EXPECT_NEAR(boxes[0].max.x(), 0.8 - 2 * margin, 1e-9);
  const std::vector<bool> senses = sensing_atoms(*cube, boxes);
  EXPECT_EQ(std::count(senses.begin(), senses.end(), true), 1);
  LoadedTask small = *cube;
  small.task.goal = {
      Region{Region::Kind::kPolygon,
             {Vec3(-0.15, -0.15, -1), Vec3(0.15, -0.15, -1), Vec3(0.15, 0.15, -1), Vec3(-0.15, 0.15, -1)},
             "goal"}};
  EXPECT_TRUE(goal_sensed_positions(small).empty());
}

// Type 3 on the whole closed bottom (cube.yaml): F_s is the bottom's friction cone (half angle atan .25)
// widened by theta_f = .3, about +z (the reaction on the robot); the walls' cones lie about horizontal axes
// and, widened, stay pi/2 - 2 (atan .25 + .3) = .48 rad clear of it, so P_s may reach every side of the
// bottom: the bottom itself within a margin, 2 eps_s thick. Only the bottom and its edges and corners (whose
// summed cones hold the bottom's) may stop by sensing there, all in the goal.
TEST(GoalSensedPositions, TypeThreeReachesTheWallsAroundTheGoal) {
  const auto cube = load("cube");
  const std::vector<ForceCone> forces = goal_sensed_forces(*cube);
  ASSERT_EQ(forces.size(), 1u);
  EXPECT_NEAR((forces[0].direction - Vec3::UnitZ()).norm(), 0, 1e-12);
  EXPECT_NEAR(forces[0].angle, std::atan(0.25) + 0.3 + kSensedForceMargin, 1e-12);
  const std::vector<AxisBox> boxes = goal_sensed_positions(*cube, forces);
  ASSERT_EQ(boxes.size(), 1u);
  const double margin = kSensedSetRelativeMargin * cube->cspace.scale();
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(boxes[0].max[k], 1 - margin, 1e-9);
    EXPECT_NEAR(boxes[0].min[k], -1 + margin, 1e-9);
  }
  EXPECT_DOUBLE_EQ(boxes[0].min.z(), -1.2);
  EXPECT_DOUBLE_EQ(boxes[0].max.z(), -0.8);
  const std::vector<bool> senses = sensing_atoms(*cube, boxes, forces);
  int sensed = 0;
  for (int a = 0; a < cube->cspace.atom_count(); ++a) {
    const std::vector<Vec3> points = atom_points(cube->cspace, a);
    const bool on_bottom =
        std::all_of(points.begin(), points.end(), [](const Vec3& p) { return std::abs(p.z() + 1) < 1e-12; });
    EXPECT_EQ(senses[a], on_bottom) << cube->cspace.atom_name(a);
    sensed += senses[a];
  }
  EXPECT_EQ(sensed, 9);  // the bottom, its 4 edges and 4 corners
  // Without F_s the walls would sense: the type 2 box stays eps_s inside them.
  EXPECT_NEAR(goal_sensed_positions(*cube)[0].max.x(), 0.8 - 2 * margin, 1e-9);
}

// Type 3 on the inset goal (cube_sensing.yaml): the bottom continues .2 beyond every side of the goal and
// senses the goal's force there, so every side keeps the type 2 inset: the same box as type 2.
TEST(GoalSensedPositions, TypeThreeKeepsTheInsetWhereTheGoalFaceContinues) {
  const auto t = load("cube_sensing");
  const std::vector<ForceCone> forces = goal_sensed_forces(*t);
  ASSERT_EQ(forces.size(), 1u);
  const std::vector<AxisBox> with_force = goal_sensed_positions(*t, forces),
                             without = goal_sensed_positions(*t);
  ASSERT_EQ(with_force.size(), 1u);
  ASSERT_EQ(without.size(), 1u);
  EXPECT_EQ(with_force[0].min, without[0].min);
  EXPECT_EQ(with_force[0].max, without[0].max);
}

// A spring to p sticks on the bottom only within rho = (d + eps_s) t + eps_s of p's projection, d the depth
// of p below z = -1, t = tan(atan(.25) + .25) ~ .5398: inside the goal |x| <= .8 when
// |x_p| + d t <= .8 - eps_s (1 + t) ~ .4920.
TEST(GoalSticking, HoldsTheCommandsWhoseStickingDiscLiesInTheGoal) {
  const auto t = load("cube_sensing");
  AtomSimulation sim(t->cspace, t->task.uncertainty, stops_of(*t, false));
  const int bottom = face_with_normal(t->cspace, Vec3::UnitZ());
  const double tan_alpha = std::tan(std::atan(0.25) + 0.25);
  ASSERT_NEAR(tan_alpha, 0.5398, 1e-4);
  const double level = 0.8 - 0.2 * (1 + tan_alpha);
  ASSERT_NEAR(level, 0.4920, 1e-4);
  EXPECT_TRUE(sim.goal_sticking(bottom).contains(Vec3(0, 0, -1.7)));     // .7 t = .378
  EXPECT_TRUE(sim.goal_sticking(bottom).contains(Vec3(0.1, 0, -1.7)));   // .478
  EXPECT_FALSE(sim.goal_sticking(bottom).contains(Vec3(0.2, 0, -1.7)));  // .578
  EXPECT_TRUE(sim.goal_sticking(bottom).contains(Vec3(0.2, 0, -1.3)));   // .2 + .3 t = .362
  EXPECT_FALSE(sim.goal_sticking(bottom).contains(Vec3(0, 0, -2)));      // 1 t = .540
  // Other atoms have none.
  EXPECT_TRUE(sim.goal_sticking(face_with_normal(t->cspace, -Vec3::UnitZ())).empty());
}

// Independently of the bound: at every corner of the goal sticking set (a convex set, and the disc's centre
// and radius are affine in p there), the verifier's own polygon of the bottom's weak sticking points
// (face_sticking_configurations, Fig 3.16) lies in the goal square.
TEST(GoalSticking, TheVerifiersStickingPolygonAtEveryCornerLiesInTheGoal) {
  const auto t = load("cube_sensing");
  AtomSimulation sim(t->cspace, t->task.uncertainty, stops_of(*t, false));
  const int bottom = face_with_normal(t->cspace, Vec3::UnitZ());
  const Face& face = t->cspace.faces()[t->cspace.atom_index(bottom)];
  const CPositionSet& set = sim.goal_sticking(bottom);
  ASSERT_FALSE(set.empty());
  int corners = 0;
  for (const ConvexPiece& piece : set.pieces())
    for (const Vec3& v : piece.vertices) {
      ++corners;
      const FaceStickingConfigurations c = face_sticking_configurations(face, v, t->task.uncertainty);
      for (const Vec3& x : c.weak) {
        EXPECT_LE(std::abs(x.x()), 0.8 + 1e-9) << v.transpose();
        EXPECT_LE(std::abs(x.y()), 0.8 + 1e-9) << v.transpose();
      }
    }
  EXPECT_GE(corners, 5);  // a pyramid's apex and base at least
}

// From the start edge: the spring to (0, 0, -1.7) lands on the bottom and sticks in the goal (a goal stop);
// to (.2, 0, -1.7) it may stick on the bottom outside the goal; with P_s (type 2) it may also stop there by
// sensing, in the goal.
TEST(GoalStopTargets, StickingInTheGoalOrSensingIsAGoalStop) {
  const auto t = load("cube_sensing");
  const std::vector<int> start = start_atoms(*t);
  const int bottom = face_with_normal(t->cspace, Vec3::UnitZ());
  AtomSimulation sticking(t->cspace, t->task.uncertainty, stops_of(*t, false));
  const int goal_stop = sticking.goal_stop_atom();
  EXPECT_EQ(goal_stop, t->cspace.atom_count() + 1);
  EXPECT_EQ(sticking.targets_at(start, Vec3(0, 0, -1.7)), std::vector<int>{goal_stop});
  EXPECT_EQ(sticking.targets_at(start, Vec3(0.2, 0, -1.7)), std::vector<int>{bottom});
  AtomSimulation sensing(t->cspace, t->task.uncertainty, stops_of(*t, true));
  EXPECT_EQ(sensing.targets_at(start, Vec3(0.2, 0, -1.7)), (std::vector<int>{bottom, goal_stop}));
  // The cell of (0, 0, -1.7) keeps its targets: so does the vertex centroid of each of its pieces.
  const CPositionSet cell = sticking.cell_at(start, Vec3(0, 0, -1.7));
  ASSERT_FALSE(cell.empty());
  for (const ConvexPiece& piece : cell.pieces()) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& v : piece.vertices) c += v;
    c /= static_cast<double>(piece.vertices.size());
    EXPECT_EQ(sticking.targets_at(start, c), std::vector<int>{goal_stop});
  }
}

TEST(ConfusableSets, IdsPastTheTableAreStatesOfTheirOwn) {
  const auto t = load("cube_sensing");
  const Confusability confusable(t->cspace, 0.2, 0.3);
  const int n = t->cspace.atom_count();
  const std::vector<State> sets = confusable_sets(confusable, {n + 1});
  EXPECT_EQ(sets, (std::vector<State>{{n + 1}}));
  const int bottom = face_with_normal(t->cspace, Vec3::UnitZ());
  EXPECT_EQ(confusable_sets(confusable, {bottom, n + 1}), (std::vector<State>{{bottom}, {n + 1}}));
}

// The verifier's stops of the hand-written type 2 motion lie on the bottom, inside the goal: the goal stop.
TEST(VerifierChain, StopsInsideAPartialGoalAreTheGoalStop) {
  const auto t = load("cube_sensing");
  const Motion& p1 = *t->task.find_motion("p1");
  const ChainVerdict v = verifier_chain(*t, {p1.target}, options(), p1.terminate);
  EXPECT_TRUE(v.reliable);
  ASSERT_EQ(v.ends.size(), 1u);
  ASSERT_TRUE(v.ends[0].has_value());
  EXPECT_EQ(*v.ends[0], std::vector<int>{t->cspace.atom_count() + 1});
  // Commanded off centre, (.5, 0, -1.7): it may stick on the bottom past the goal's edge x = .8.
  const ChainVerdict off = verifier_chain(*t, {Vec3(0.5, 0, -1.7)}, options(), p1.terminate);
  EXPECT_FALSE(off.reliable);
}

}  // namespace
}  // namespace cmt::planner
