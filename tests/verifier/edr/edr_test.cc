// EDR on slices (verifier/edr; Donald 1987 Example (1) as models/tasks/step_offset.yaml, Example (6) as
// models/tasks/hole_width.yaml, Example (3) as models/tasks/twin_universe.yaml), under Buckley's first-order
// model (the rollouts' model adds the contact lift and the servo coast; docs/edr.md).
#include "verifier/edr/edr.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <sstream>

#include "models/loaded_task.h"
#include "models/model_error.h"
#include "models/task_loader.h"

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

// Slicing-gap refinement: between alpha = 0 (no goal) and .5 the pair straddles the goal's appearance, so it
// is bisected to the depth (.25, then .125, then .0625 toward 0); elsewhere the landings on A's face (a
// region that scales with alpha about B's rim) and the far wall's H (the same for every alpha <= 0) move
// affinely, so every midpoint lies in its pair's sweep and none joins.
TEST(StepOffsetEdr, RefinementBisectsTowardWhereTheGoalAppears) {
  const auto task = step_offset();
  EdrOptions options;
  options.refine_depth = 3;
  const EdrResult r = verify_edr(task->task, {"left"}, model_slices(task->task, 5), options);
  std::vector<double> alphas;
  for (const EdrSlice& s : r.slices) alphas.push_back(s.values[0]);
  EXPECT_EQ(alphas, (std::vector<double>{-1, -0.5, 0, 0.0625, 0.125, 0.25, 0.5, 1}));
  for (const EdrSlice& s : r.slices) EXPECT_EQ(s.goal_empty, s.values[0] <= 0) << s.values[0];
  EXPECT_TRUE(r.edr_reliable) << r.reason;
  EXPECT_EQ(r.refine_depth, 3);
  // For alpha > 0 the robot flies off B's rim into the gap and sticks on A's face: the refined slices too
  // reach the goal and are reliable.
  for (const EdrSlice& s : r.slices)
    if (s.values[0] > 0 && s.values[0] < 0.5) {
      EXPECT_TRUE(s.reliable) << s.values[0];
      EXPECT_TRUE(s.success && !s.success->empty()) << s.values[0];
    }
  // Without the option no refinement is applied.
  EXPECT_EQ(verify_edr(task->task, {"left"}, model_slices(task->task, 5), EdrOptions{}).refine_depth, 0);
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

// step_offset.yaml with one more motion, `name: {damper: direction}`, after its others.
Task step_offset_with(const std::string& name, const Vec3& direction) {
  const std::string path = std::string(CMT_SOURCE_DIR) + "/models/tasks/step_offset.yaml";
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string down = "down: {damper: [0, 0, -1]}";
  EXPECT_NE(text.find(down), std::string::npos);
  std::ostringstream motion;
  motion << std::setprecision(17) << "\n  " << name << ": {damper: [" << direction.x() << ", "
         << direction.y() << ", " << direction.z() << "]}";
  text.replace(text.find(down), down.size(), down + motion.str());
  return parse_task_string(text, path);
}

// Linking (Donald §12.5, (L0)): `left` stops in the goal wherever it exists; a second motion straight up
// leads the robot out of it (to the ceiling), so the composed strategy is not linked there. Where the goal
// vanishes G ∩ push is empty and the condition holds.
TEST(StepOffsetEdr, ASecondMotionLeavingTheGoalBreaksTheLink) {
  const Task t = step_offset_with("up", Vec3(0, 0, 1));
  const EdrResult r = verify_edr(t, {"left", "up"}, model_slices(t, 5), EdrOptions{});
  ASSERT_TRUE(r.terminates) << r.reason;
  EXPECT_FALSE(r.linked);
  EXPECT_FALSE(r.edr_reliable);
  for (const EdrSlice& s : r.slices) {
    EXPECT_EQ(s.linked, s.goal_empty) << s.values[0];
    if (!s.linked) {
      EXPECT_NE(s.linking_problem.find("L0"), std::string::npos) << s.linking_problem;
    }
  }
  // The one-motion strategy has no link.
  EXPECT_TRUE(verify_edr(t, {"left"}, model_slices(t, 5), EdrOptions{}).linked);
}

// The link holds where it is not trivial: a second motion pressing into A's face (left and down, at the
// friction angle from its normal) keeps a robot that stopped there in the goal (stuck on the face, or slid
// down it to the bottom edge, which bounds the goal), so in every slice with a goal, where the first motion's
// push-forward meets it, the remaining motion ends in the goal; where the goal vanishes G ∩ push is empty.
TEST(StepOffsetEdr, ASecondMotionPressingIntoTheGoalKeepsTheLink) {
  const Task t = step_offset_with("press", Vec3(-1, 0, -0.5));
  const EdrResult first = verify_edr(t, {"left"}, model_slices(t, 5), EdrOptions{});
  const EdrResult r = verify_edr(t, {"left", "press"}, model_slices(t, 5), EdrOptions{});
  ASSERT_TRUE(r.terminates) << r.reason;
  ASSERT_EQ(r.slices.size(), first.slices.size());
  int met = 0;
  for (std::size_t i = 0; i < r.slices.size(); ++i) {
    const EdrSlice& s = r.slices[i];
    EXPECT_TRUE(s.linked) << s.values[0] << ": " << s.linking_problem;
    if (!s.goal_empty) {
      ASSERT_TRUE(first.slices[i].success != nullptr);
      EXPECT_FALSE(first.slices[i].success->empty()) << s.values[0];  // G ∩ push is not empty
      ++met;
    }
  }
  EXPECT_GE(met, 2);
  EXPECT_TRUE(r.linked);
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
  EXPECT_TRUE(r.linked);
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

std::shared_ptr<const LoadedTask> twin_universe() {
  return load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/twin_universe.yaml");
}

EdrResult run_twin(const std::vector<std::string>& motions, bool preimages = true) {
  const auto task = twin_universe();
  EdrOptions options;
  options.preimages = preimages;
  return verify_edr(task->task, motions, model_slices(task->task, 5), options);
}

// The union of a slice's termination pieces as sorted rounded points (to compare positions across slices).
std::vector<std::vector<long>> termination_points(const EdrSlice& s) {
  std::vector<std::vector<long>> out;
  for (const ReachedPiece& p : s.termination->pieces())
    for (const Vec3& q : p.polygon)
      out.push_back({std::lround(q.x() * 1e6), std::lround(q.y() * 1e6), std::lround(q.z() * 1e6)});
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Donald's Example (3): J = {1, 2}, the goal only in universe 1. The first motion pushes forward to the shaft
// floor in both universes, at the same positions (S1 u S2: the sensors cannot tell them apart), and never
// reaches the goal.
TEST(TwinUniverseEdr, TheFirstMotionPushesForwardToTheSamePlaceInBothUniverses) {
  const EdrResult r = run_twin({"down"});
  ASSERT_EQ(r.slices.size(), 2u);  // the two universes, at any resolution
  EXPECT_EQ(r.slices[0].values, (std::vector<double>{1}));
  EXPECT_EQ(r.slices[1].values, (std::vector<double>{2}));
  EXPECT_FALSE(r.slices[0].goal_empty);
  EXPECT_TRUE(r.slices[1].goal_empty);
  EXPECT_FALSE(r.reaches_goal);
  for (const EdrSlice& s : r.slices) {
    ASSERT_TRUE(s.terminates) << s.termination_problem;
    for (const ReachedPiece& p : s.termination->pieces())
      for (const Vec3& q : p.polygon) {
        EXPECT_NEAR(q.z(), 0, 1e-9);  // the shaft floor
        EXPECT_GE(q.x(), -1 + 1e-9);  // in the shaft, .3 in at most from its right wall
        EXPECT_LE(q.x(), -0.5 + 1e-9);
      }
  }
  EXPECT_EQ(termination_points(r.slices[0]), termination_points(r.slices[1]));
}

// The two-step strategy: in universe 1 every termination is in the goal (the tunnel's far upper corner); in
// universe 2 every one is on the short tunnel's end face x = -2.5, F(S2), 2.5 in or more from any goal point.
// No sweeps: nothing lies between the universes.
TEST(TwinUniverseEdr, TheTwoStepStrategyIsEdrReliable) {
  const EdrResult r = run_twin({"down", "up_left"});
  ASSERT_EQ(r.slices.size(), 2u);
  const EdrSlice& one = r.slices[0];
  const EdrSlice& two = r.slices[1];
  ASSERT_TRUE(one.terminates) << one.termination_problem;
  ASSERT_TRUE(two.terminates) << two.termination_problem;
  EXPECT_TRUE(one.reliable);
  EXPECT_TRUE(one.failure_pieces.empty());
  EXPECT_FALSE(one.success->empty());
  EXPECT_TRUE(two.success->empty());
  ASSERT_FALSE(two.failure_pieces.empty());
  for (const ReachedPiece& p : two.failure_pieces)
    for (const Vec3& q : p.polygon) {
      EXPECT_NEAR(q.x(), -2.5, 1e-9);
      EXPECT_GE(q.z(), 0.3);  // it rises at 11 degrees or more over the 1.5 in from the shaft
    }
  EXPECT_TRUE(r.swept_success.empty());
  EXPECT_TRUE(r.swept_failure.empty());
  EXPECT_TRUE(r.linked);  // `down` never stops in the goal
  EXPECT_TRUE(r.edr_reliable) << r.reason;
}

// No one-step EDR strategy: commanded directions all round the x-z plane (every 15 degrees), none of which
// reaches the goal in either universe (the geometric argument in the task file), and the same tilted toward
// y, none of which is EDR-reliable (Donald: "there is no one-step EDR strategy" from the start). A tilted
// command may reach the goal under the verifier's edge-sliding over-approximation: sliding along the shaft's
// left wall at the friction cone's edge, it may creep down into the tunnel.
TEST(TwinUniverseEdr, NoOneStepCommandIsEdrReliable) {
  const std::string path = std::string(CMT_SOURCE_DIR) + "/models/tasks/twin_universe.yaml";
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string direct = "direct: {damper: [-1, 0, -0.5], edr: true}";
  ASSERT_NE(text.find(direct), std::string::npos);
  EdrOptions options;
  options.preimages = false;
  for (int k = 0; k < 24; ++k)
    for (double y : {0.0, 0.5}) {
      const double angle = k * M_PI / 12;
      std::ostringstream probe;
      probe << std::setprecision(17) << "direct: {damper: [" << std::cos(angle) << ", " << y << ", "
            << std::sin(angle) << "], edr: true}";
      std::string changed = text;
      changed.replace(changed.find(direct), direct.size(), probe.str());
      const Task t = parse_task_string(changed, path);
      const EdrResult r = verify_edr(t, {"direct"}, model_slices(t, 2), options);
      if (y == 0) {
        EXPECT_FALSE(r.reaches_goal) << probe.str();
      }
      EXPECT_FALSE(r.edr_reliable) << probe.str();
    }
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
