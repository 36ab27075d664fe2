// One-step EDR on slices (verifier/edr; Donald 1987 Example (1) as models/tasks/step_offset.yaml), under
// Buckley's first-order model (the rollouts' model adds the contact lift and the servo coast; docs/edr.md).
#include "verifier/edr/edr.h"

#include <gtest/gtest.h>

#include "models/loaded_task.h"
#include "models/model_error.h"

namespace cmt {
namespace {

std::shared_ptr<const LoadedTask> step_offset() {
  return load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/step_offset.yaml");
}

EdrResult run(const std::string& motion) {
  const auto task = step_offset();
  return verify_edr(task->task, {motion}, model_slices(task->task, 5), EdrOptions{});
}

TEST(StepOffsetEdr, TheGoalVanishesExactlyWhereTheBlocksMeet) {
  const EdrResult r = run("left");
  ASSERT_EQ(r.slices.size(), 5u);  // alpha = -1, -.5, 0 (critical), .5, 1
  for (const EdrSlice& s : r.slices) EXPECT_EQ(s.goal_empty, s.values[0] <= 0) << s.values[0];
}

// Donald's ground truth for Example (1): the backprojection is empty where G vanishes, H is non-empty only
// there, and G and H are distinguishable, so the motion is an EDR strategy.
TEST(StepOffsetEdr, LeftIsEdrReliableWithFailureOnlyWhereTheGoalVanishes) {
  const EdrResult r = run("left");
  EXPECT_TRUE(r.terminates);
  EXPECT_TRUE(r.reaches_goal);
  EXPECT_TRUE(r.distinguishable);
  EXPECT_TRUE(r.edr_reliable) << r.reason;
  for (const EdrSlice& s : r.slices) {
    ASSERT_TRUE(s.terminates) << s.termination_problem;
    ASSERT_TRUE(s.strong.has_value());
    if (s.values[0] > 0) {
      EXPECT_TRUE(s.failure_pieces.empty()) << s.values[0];
      EXPECT_FALSE(s.success->empty());
      EXPECT_TRUE(s.reliable);
      EXPECT_GT(s.strong->area(), 0);  // P holds where the robot lands on A's face
    } else {
      EXPECT_FALSE(s.failure_pieces.empty()) << s.values[0];
      EXPECT_TRUE(s.success->empty());
      EXPECT_EQ(s.strong->area(), 0);  // nothing reaches a goal that is not there
      // H: the far wall x = -6 (and the y walls beside it) where the robot sticks after crossing A's top.
      for (const ReachedPiece& p : s.failure_pieces)
        for (const Vec3& q : p.polygon) EXPECT_LE(q.x(), -4 + 1e-9) << "H piece on atom " << p.atom;
    }
  }
}

// Steep may stick on the gap floor beside A's face: a stop there is within 2 eps_s of a stop at the face's
// foot (in the goal) with a reaction force in the foot edge's cone, so success cannot be recognized.
TEST(StepOffsetEdr, SteepIsNotEdrReliable) {
  const EdrResult r = run("steep");
  EXPECT_TRUE(r.reaches_goal);
  EXPECT_FALSE(r.distinguishable);
  EXPECT_FALSE(r.edr_reliable);
  ASSERT_FALSE(r.confusions.empty());
  const EdrConfusion& c = r.confusions.front();
  EXPECT_LE(c.distance, 2 * 0.2);
  EXPECT_LE(c.force_angle, 2 * 0.35);
  // The failure piece lies on a floor (z = 0) of a slice with a goal.
  EXPECT_FALSE(r.slices[c.failure_slice].goal_empty);
  for (const Vec3& q : c.failure_piece.polygon) EXPECT_NEAR(q.z(), 0, 1e-9);
}

TEST(StepOffsetEdr, DownNeverReachesTheGoal) {
  const EdrResult r = run("down");
  EXPECT_FALSE(r.reaches_goal);
  EXPECT_FALSE(r.edr_reliable);
}

ReachedPiece piece(std::vector<Vec3> points) {
  ReachedPiece p;
  p.polygon = std::move(points);
  return p;
}

TEST(PieceDistance, HandChecked) {
  const ReachedPiece square = piece({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  // A parallel square 2 above, shifted: the planes' distance.
  EXPECT_NEAR(piece_distance_lower_bound(square, piece({{0.5, 0.5, 2}, {3, 0.5, 2}, {3, 3, 2}, {0.5, 3, 2}})),
              2, 1e-12);
  // A segment piercing the square's interior: 0.
  EXPECT_NEAR(piece_distance_lower_bound(square, piece({{0.5, 0.5, -1}, {0.5, 0.5, 1}})), 0, 1e-12);
  // A segment crossing above an edge: edge to edge, 3 up and across x = 1.
  EXPECT_NEAR(piece_distance_lower_bound(square, piece({{1, -1, 3}, {1, 2, 3}})), 3, 1e-12);
  // A point beside a corner.
  EXPECT_NEAR(piece_distance_lower_bound(square, piece({{2, 2, 0}})), std::sqrt(2.0), 1e-12);
  // A non-convex outline counts as its hull (a lower bound): the point in the notch is at distance 0.
  const ReachedPiece ell = piece({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}});
  EXPECT_EQ(piece_distance_lower_bound(ell, piece({{1.4, 1.4, 0}})), 0);
}

}  // namespace
}  // namespace cmt
