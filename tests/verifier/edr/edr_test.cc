// EDR on slices (verifier/edr; Donald 1987 Example (1) as models/tasks/step_offset.yaml, Example (6) as
// models/tasks/hole_width.yaml), under Buckley's first-order model (the rollouts' model adds the contact lift
// and the servo coast; docs/edr.md).
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

EdrResult run_hole_width(const std::vector<std::string>& motions) {
  const auto task = load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/hole_width.yaml");
  return verify_edr(task->task, motions, model_slices(task->task, 5), EdrOptions{});
}

// Donald's Example (6), the width alone: the hole (and the goal, its bottom) exists only for w > 1 (the peg
// is 1 wide). The two-motion plan ends on the bottom there, and in the far corner (x = -6, z = 0) where the
// hole is missing: 5.8 in or more from any goal, so the plan is EDR-reliable.
TEST(HoleWidthEdr, TwoMotionPlanIsEdrReliableWithFailureInTheFarCorner) {
  const EdrResult r = run_hole_width({"left", "down"});
  // w = .5, 1.125, 1.75, 2.375, 3; the critical 1 (where the blocks' C-obstacles meet); the midpoints .75 and
  // 2 of [.5, 1] and [1, 3].
  ASSERT_EQ(r.slices.size(), 8u);
  for (const EdrSlice& s : r.slices) {
    const double w = s.values[0];
    EXPECT_EQ(s.goal_empty, w <= 1) << w;
    ASSERT_TRUE(s.terminates) << w << ": " << s.termination_problem;
    if (w > 1) {
      EXPECT_TRUE(s.failure_pieces.empty()) << w;
      EXPECT_TRUE(s.reliable) << w;
      for (const ReachedPiece& p : s.success->pieces())
        for (const Vec3& q : p.polygon) EXPECT_NEAR(q.z(), -3, 1e-9) << w;
    } else {
      EXPECT_TRUE(s.success->empty()) << w;
      ASSERT_FALSE(s.failure_pieces.empty()) << w;
      for (const ReachedPiece& p : s.failure_pieces)
        for (const Vec3& q : p.polygon) {
          EXPECT_LE(q.x(), -6 + 0.6) << w;  // the corner, within the velocity error's spread
          EXPECT_GE(q.z(), -1e-9) << w;
        }
    }
  }
  EXPECT_TRUE(r.edr_reliable) << r.reason;
  // Between adjacent slices with a goal, its stops sweep: per atom the hull of both slices' pieces, e.g. the
  // strip of the bottom between two positions of the right wall's foot edge. Every world between the slices
  // stops in it, so the EDR predicate recognizes it there too.
  ASSERT_FALSE(r.swept_success.empty());
  bool strip = false;
  for (const SlicePiece& p : r.swept_success) {
    EXPECT_GE(p.slice, 3);  // from the first slice with a goal on
    for (const Vec3& q : p.piece.polygon) EXPECT_NEAR(q.z(), -3, 1e-9);
    strip = strip || p.piece.polygon.size() == 4;
  }
  EXPECT_TRUE(strip);
}

// The first motion alone ends on the hole's left wall: never in the goal (Donald: success is not yet
// recognizable after it).
TEST(HoleWidthEdr, TheFirstMotionAloneNeverReachesTheGoal) {
  const EdrResult r = run_hole_width({"left"});
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
  EXPECT_NEAR(piece_distance_lower_bound(piece({{0.5, 0.5, -1}, {0.5, 0.5, 1}}), square), 0,
              1e-12);  // symmetric
  // A segment crossing above an edge: edge to edge, 3 up and across x = 1.
  EXPECT_NEAR(piece_distance_lower_bound(square, piece({{1, -1, 3}, {1, 2, 3}})), 3, 1e-12);
  // A point beside a corner.
  EXPECT_NEAR(piece_distance_lower_bound(square, piece({{2, 2, 0}})), std::sqrt(2.0), 1e-12);
  // Points in any order: a "bow-tie" listing of a rectangle is the rectangle (its centre at distance 0).
  const ReachedPiece bow_tie = piece({{0, -3, 0}, {0, 3, 0}, {1, -3, 0}, {1, 3, 0}});
  EXPECT_EQ(piece_distance_lower_bound(bow_tie, piece({{0.5, 0, 0}})), 0);
  // A non-convex outline counts as its hull (a lower bound): the point in the notch is at distance 0.
  const ReachedPiece ell = piece({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}});
  EXPECT_EQ(piece_distance_lower_bound(ell, piece({{1.4, 1.4, 0}})), 0);
}

}  // namespace
}  // namespace cmt
