// The scoring of `cmt validate` (experiments/validation/validation.h) on synthetic predictions and rollouts,
// with every expected number derived by hand in the comments: soundness counting (inside/outside the contact
// tolerance, time-outs, unstable rollouts, motions after the verifier's failed step, a spring's free rest
// ball), coverage radii and fractions (area, length, points), and the replay command line.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "experiments/validation/piece_geometry.h"
#include "experiments/validation/validation.h"

namespace cmt {
namespace {

// An empty room [-4,4] x [-4,4] x [0,4]; the robot is a point. Scene scale = the diagonal of the atoms'
// bounding box = sqrt(8^2 + 8^2 + 4^2) = 12, so the contact tolerance is 1e-4 x 12 = 1.2e-3.
std::shared_ptr<const LoadedTask> room() {
  static const auto task = load_task_from_string(
      "name: room\nunits: in\nfriction: 0.25\n"
      "uncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.1, theta_f: 0.1}\ncspace: []\n"
      "bounds: {min: [-4, -4, 0], max: [4, 4, 4]}\nstart: {point: [0, 0, 4]}\ngoal: {point: [0, 0, 4]}\n"
      "motions:\n  m: {damper: [0, 0, -1]}\n  n: {damper: [0, 0, 1]}\nstrategies:\n  s: [m]\n",
      "room");
  return task;
}
constexpr double kTolerance = 1.2e-3;

int floor_face(const CSpace& c) {
  for (const Face& f : c.faces())
    if (f.normal.z() > 0.5) return f.id;
  return -1;
}

// A prediction with one step per given termination set.
VerifyStep step(const std::string& motion, const ReachedSet& termination) {
  return VerifyStep{.motion = motion, .termination = termination, .reached = nullptr};
}

ReachedSet square(const CSpace& c, double half) {
  ReachedSet s(c);
  s.add_face_polygon(floor_face(c), {{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}});
  return s;
}

RolloutOutcome rollout(int index, std::vector<std::pair<Vec3, Termination>> ends, bool success = true) {
  RolloutOutcome r;
  r.index = index;
  r.success = success;
  for (const auto& [p, t] : ends) {
    MotionOutcome m;
    m.end = p;
    m.termination = t;
    r.motions.push_back(m);
  }
  r.end = r.motions.back().end;
  r.termination = r.motions.back().termination;
  return r;
}

constexpr Termination kStick = Termination::kSticking;

TEST(ValidateScoring, CountsEndsOutsideThePredictionFarthestFirst) {
  const auto t = room();
  const CSpace& c = t->cspace;
  ValidationResult r;
  r.prediction.steps.push_back(step("m", square(c, 1)));  // floor square [-1,1]^2
  r.rollouts = {
      rollout(0, {{Vec3(0, 0, 0), kStick}}),                             // inside: distance 0
      rollout(1, {{Vec3(1 + kTolerance / 2, 0, 0), kStick}}),            // half a tolerance beside: inside
      rollout(2, {{Vec3(3, 0, 0), kStick}}, false),                      // 2 beside: outside
      rollout(3, {{Vec3(0, 0, 1), Termination::kNone}}, false),          // timed out: not a termination point
      rollout(4, {{Vec3(3, 3, 3), Termination::kUnstable}}, false),      // unstable: excluded
      rollout(5, {{Vec3(2, 2, 0), kStick}}, false),                      // off the corner by sqrt 2: outside
      rollout(6, {{Vec3(0.5, 0, 0), kStick}, {Vec3(0, 0, 4), kStick}}),  // 2nd motion: no step predicts it
      rollout(7, {{Vec3(1 + 2 * kTolerance, 0, 0), kStick}}, false),     // 2 tolerances beside: outside
  };
  r.rollouts[4].unstable = true;
  score_soundness(*t, &r);
  EXPECT_DOUBLE_EQ(r.contact_tolerance, kTolerance);
  EXPECT_EQ(r.successes, 3);  // rollouts 0, 1, 6
  EXPECT_EQ(r.unstable, 1);
  // Terminated ends of predicted motions in stable rollouts: rollouts 0, 1, 2, 5, 6 (first motion), 7.
  ASSERT_EQ(r.ends.size(), 6u);
  EXPECT_EQ(r.outside, 3);
  EXPECT_DOUBLE_EQ(r.soundness, 3.0 / 6.0);
  EXPECT_EQ(r.unpredicted, 1);
  ASSERT_EQ(r.timeouts.size(), 1u);
  EXPECT_EQ(r.timeouts[0].rollout, 3);
  ASSERT_EQ(r.unexpected_timeouts.size(), 1u);  // the step did not say may_not_terminate
  ASSERT_EQ(r.worst.size(), 3u);
  EXPECT_EQ(r.worst[0].rollout, 2);
  EXPECT_NEAR(r.worst[0].distance, 2, 1e-12);
  EXPECT_EQ(r.worst[1].rollout, 5);
  EXPECT_NEAR(r.worst[1].distance, std::sqrt(2.0), 1e-12);
  EXPECT_EQ(r.worst[2].rollout, 7);
  EXPECT_NEAR(r.worst[2].distance, 2 * kTolerance, 1e-12);
  EXPECT_TRUE(r.ends[1].inside);
  EXPECT_NEAR(r.ends[1].distance, kTolerance / 2, 1e-12);
  EXPECT_TRUE(contradicts_verifier(r));
}

TEST(ValidateScoring, TimeoutsWhereTheVerifierSaidMayNotTerminateAreExpected) {
  const auto t = room();
  ValidationResult r;
  r.prediction.steps.push_back(step("m", ReachedSet(t->cspace)));
  r.prediction.steps[0].may_not_terminate = true;
  r.rollouts = {rollout(0, {{Vec3(0, 0, 2), Termination::kNone}}, false)};
  score_soundness(*t, &r);
  EXPECT_EQ(r.timeouts.size(), 1u);
  EXPECT_TRUE(r.unexpected_timeouts.empty());
  EXPECT_TRUE(r.ends.empty());
  EXPECT_DOUBLE_EQ(r.soundness, 1);  // nothing to contradict
  EXPECT_FALSE(contradicts_verifier(r));
}

TEST(ValidateScoring, StickingWhereNothingCanStickIsInfinitelyFar) {
  // An empty prediction (the verifier says no reached atom can stick) and an observed sticking end.
  const auto t = room();
  ValidationResult r;
  r.prediction.steps.push_back(step("m", ReachedSet(t->cspace)));
  r.rollouts = {rollout(0, {{Vec3(0, 0, 0), kStick}}, false)};
  score_soundness(*t, &r);
  EXPECT_EQ(r.outside, 1);
  EXPECT_EQ(r.worst[0].distance, std::numeric_limits<double>::infinity());
}

TEST(ValidateScoring, SpringFreeRestBallCountsAsPredicted) {
  // Free rest ball of centre (0,0,2), radius .5; nothing on the surface.
  const auto t = room();
  VerifyStep s = step("m", ReachedSet(t->cspace));
  s.free_termination = true;
  s.free_center = Vec3(0, 0, 2);
  s.free_radius = 0.5;
  EXPECT_DOUBLE_EQ(distance_to_prediction(s, Vec3(0, 0, 2.3)), 0);    // in the ball
  EXPECT_DOUBLE_EQ(distance_to_prediction(s, Vec3(0, 0, 3)), 0.5);    // 1 from the centre
  EXPECT_DOUBLE_EQ(distance_to_prediction(s, Vec3(0, 0.6, 2)), 0.1);  // .6 from the centre
  s.termination = square(t->cspace, 1);
  EXPECT_DOUBLE_EQ(distance_to_prediction(s, Vec3(0, 0, 0.25)), 0.25);  // the floor is nearer
}

TEST(ValidateScoring, AreaCoverageUsesTheRadiusFromTheSampleSize) {
  // Prediction: the floor square [-1,1]^2, A = 4. N = 12 ends: r = sqrt(3 A / (pi N)) = 1/sqrt(pi), so each
  // disk has area pi r^2 = 1. All 12 ends at the centre: the disk (r = .564 < 1) lies inside the square and
  // covers 1/4 of it.
  const auto t = room();
  ValidationResult r;
  r.prediction.steps.push_back(step("m", square(t->cspace, 1)));
  for (int i = 0; i < 12; ++i) r.rollouts.push_back(rollout(i, {{Vec3(0, 0, 0), kStick}}));
  score_soundness(*t, &r);
  score_coverage(*t, &r);
  ASSERT_EQ(r.steps.size(), 1u);
  EXPECT_EQ(r.steps[0].measure, "area");
  EXPECT_NEAR(r.steps[0].predicted, 4, 1e-12);
  EXPECT_NEAR(r.coverage_radius, 1 / std::sqrt(std::numbers::pi), 1e-12);
  // Lattice spacing sqrt(4/20000) = .014: the disk's boundary cells move the estimate by ~1e-3.
  EXPECT_NEAR(r.coverage, 0.25, 3e-3);

  // The same ends at the four corners, 3 each: four quarter disks inside the square, again area 1.
  const Vec3 corners[] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  for (int i = 0; i < 12; ++i) r.rollouts[i] = rollout(i, {{corners[i % 4], kStick}});
  score_soundness(*t, &r);
  score_coverage(*t, &r);
  EXPECT_NEAR(r.coverage, 0.25, 3e-3);
}

TEST(ValidateScoring, PooledCoverageIsWeightedByPredictedArea) {
  // Motion m: square [-1,1]^2 (A = 4), 12 ends at the centre: r = 1/sqrt(pi), covered area 1.
  // Motion n: square [-2,2]^2 (A = 16), 48 ends at the centre: r = sqrt(3 * 16 / (48 pi)) = 1/sqrt(pi),
  // covered area 1. Pooled: (1 + 1) / (4 + 16) = .1.
  const auto t = room();
  ValidationResult r;
  r.prediction.steps.push_back(step("m", square(t->cspace, 1)));
  r.prediction.steps.push_back(step("n", square(t->cspace, 2)));
  r.contact_tolerance = kTolerance;
  for (int i = 0; i < 48; ++i)
    for (int motion = 0; motion < (i < 12 ? 2 : 1); ++motion) {
      ObservedEnd e;
      e.rollout = i;
      e.motion = i < 12 ? motion : 1;  // 12 ends of m, 48 of n
      e.inside = true;
      r.ends.push_back(e);
    }
  score_coverage(*t, &r);
  ASSERT_EQ(r.steps.size(), 2u);
  EXPECT_EQ(r.steps[0].ends, 12);
  EXPECT_EQ(r.steps[1].ends, 48);
  EXPECT_NEAR(r.steps[0].radius, 1 / std::sqrt(std::numbers::pi), 1e-12);
  EXPECT_NEAR(r.steps[1].radius, 1 / std::sqrt(std::numbers::pi), 1e-12);
  EXPECT_NEAR(r.steps[0].coverage, 0.25, 3e-3);
  EXPECT_NEAR(r.steps[1].coverage, 1.0 / 16, 3e-3);
  EXPECT_NEAR(r.coverage, 0.1, 3e-3);
}

TEST(ValidateScoring, LengthCoverageForPredictionsWithoutArea) {
  // Prediction: t in [.25, .75] of the floor edge along y = -4 (x from -2 to 2, length 4). N = 3 ends:
  // r = c L / (2 N) = 3 * 4 / 6 = 2. All three at (-2, -4, 0): they cover x in [-2, 0], half the length.
  const auto t = room();
  const CSpace& c = t->cspace;
  int edge = -1;
  for (const Edge& e : c.edges())
    if (std::abs(e.a.y() + 4) < 1e-12 && std::abs(e.b.y() + 4) < 1e-12 && std::abs(e.a.z()) < 1e-12 &&
        std::abs(e.b.z()) < 1e-12)
      edge = e.id;
  ASSERT_GE(edge, 0);
  ReachedSet s(c);
  s.add_edge_interval(edge, 0.25, 0.75);
  ValidationResult r;
  r.prediction.steps.push_back(step("m", s));
  for (int i = 0; i < 3; ++i) r.rollouts.push_back(rollout(i, {{Vec3(-2, -4, 0), kStick}}));
  score_soundness(*t, &r);
  score_coverage(*t, &r);
  EXPECT_EQ(r.outside, 0);
  EXPECT_EQ(r.steps[0].measure, "length");
  EXPECT_NEAR(r.steps[0].predicted, 4, 1e-12);
  EXPECT_NEAR(r.coverage_radius, 2, 1e-12);
  EXPECT_NEAR(r.coverage, 0.5, 1e-3);
}

TEST(ValidateScoring, PointCoverageCountsPointsReachedWithinTheTolerance) {
  // Prediction: two room corners (vertices); one observed end at one of them: coverage 1/2.
  const auto t = room();
  const CSpace& c = t->cspace;
  ReachedSet s(c);
  int added = 0;
  for (const Vertex& v : c.vertices())
    if (v.point.z() == 0 && v.point.y() == -4) {
      s.add_vertex(v.id);
      ++added;
    }
  ASSERT_EQ(added, 2);  // (-4,-4,0) and (4,-4,0)
  ValidationResult r;
  r.prediction.steps.push_back(step("m", s));
  r.rollouts = {rollout(0, {{Vec3(4, -4, 0.5 * kTolerance), kStick}})};
  score_soundness(*t, &r);
  score_coverage(*t, &r);
  EXPECT_EQ(r.outside, 0);
  EXPECT_EQ(r.steps[0].measure, "points");
  EXPECT_DOUBLE_EQ(r.coverage_radius, kTolerance);
  EXPECT_DOUBLE_EQ(r.coverage, 0.5);
}

TEST(ValidateScoring, CoverageLatticeIsAreaUniformOnTheHighestDimensionalPart) {
  // Square [-1,1]^2 (A = 4) and, beside it, a floor vertex: the area carries the measure, so the lattice is
  // the square's alone, spacing sqrt(4 / 20000) = .014, about 20000 points, each a quarter of them in each
  // quadrant. The vertex alone is a "points" lattice of one point.
  const auto t = room();
  const CSpace& c = t->cspace;
  int corner = -1;
  for (const Vertex& v : c.vertices())
    if (v.point == Vec3(-4, -4, 0)) corner = v.id;
  ASSERT_GE(corner, 0);
  ReachedSet s = square(c, 1);
  s.add_vertex(corner);
  const CoverageLattice lattice = coverage_lattice(*t, step("m", s));
  EXPECT_EQ(lattice.measure, "area");
  EXPECT_NEAR(lattice.predicted, 4, 1e-12);
  EXPECT_NEAR(static_cast<double>(lattice.points.size()), kCoverageSamples, 0.02 * kCoverageSamples);
  int first_quadrant = 0;
  for (const Vec3& q : lattice.points) {
    EXPECT_LE(std::abs(q.x()), 1);
    EXPECT_LE(std::abs(q.y()), 1);
    EXPECT_EQ(q.z(), 0);
    first_quadrant += q.x() > 0 && q.y() > 0;
  }
  EXPECT_NEAR(first_quadrant, lattice.points.size() / 4.0, 0.02 * lattice.points.size());
  ReachedSet v(c);
  v.add_vertex(corner);
  const CoverageLattice points = coverage_lattice(*t, step("m", v));
  EXPECT_EQ(points.measure, "points");
  ASSERT_EQ(points.points.size(), 1u);
  EXPECT_EQ(points.points[0], Vec3(-4, -4, 0));
  EXPECT_EQ(coverage_lattice(*t, step("m", ReachedSet(c))).measure, "none");
}

TEST(ValidateScoring, DistanceToAPieceWithAHole) {
  // Outer square [-2,2]^2 on the floor, hole [-1,1]^2.
  const auto t = room();
  ReachedPiece p;
  p.atom = floor_face(t->cspace);
  p.polygon = {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}};
  p.holes = {{{-1, -1, 0}, {-1, 1, 0}, {1, 1, 0}, {1, -1, 0}}};
  EXPECT_DOUBLE_EQ(distance_to_piece(t->cspace, p, Vec3(1.5, 0, 2)), 2);             // above the ring
  EXPECT_DOUBLE_EQ(distance_to_piece(t->cspace, p, Vec3(0, 0, 0)), 1);               // hole centre
  EXPECT_DOUBLE_EQ(distance_to_piece(t->cspace, p, Vec3(3, 0, 1)), std::sqrt(2.0));  // outside, raised
  // A lattice of spacing .5 has cell centres at +-.25, +-.75, ...: 8 x 8 = 64 in the outer square, 4 x 4
  // = 16 of them in the hole.
  EXPECT_EQ(region_lattice(t->cspace, p, 0.5).size(), 48u);
}

TEST(ValidateReplay, CommandLineRunsTheRolloutAsTheLastOne) {
  const auto t = room();
  EXPECT_EQ(replay_command(*t, "s", 7, 41, SampleMode::kExtreme, ControllerForm::kAdmittance),
            "cmt rollout room --strategy s -n 42 --seed 7 --mode extreme");
  EXPECT_EQ(replay_command(*t, "s", 7, 0, SampleMode::kUniform, ControllerForm::kImpedance),
            "cmt rollout room --strategy s -n 1 --seed 7 --mode uniform --controller impedance");
}

}  // namespace
}  // namespace cmt
