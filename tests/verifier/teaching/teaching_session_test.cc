// The teaching session (verifier/teaching/teaching_session.h): Buckley §5.2 on the hole task, a hand-checked
// corner scene, inline motions and undo.
#include "verifier/teaching/teaching_session.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "controllers/termination.h"
#include "models/task_error.h"

namespace cmt::teaching {
namespace {

std::shared_ptr<const LoadedTask> hole() {
  return load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/hole.yaml");
}

// The spring model and stop rule of `cmt teach` (the rollouts' kappa: a slide slower than 1 % of the
// reference speed is a stop; under Coulomb sticking alone p1 may slide forever on the hole bottom with
// mu = .25); contact lift and servo coast stay 0, the first-order contact these hand checks reason about.
TeachOptions rollout_like(int refine_depth = 2) {
  TeachOptions o;
  o.verify.spring_model = SpringModel::kVelocity;
  o.verify.stop_relative_speed = kStopRelativeSpeed;
  o.refine_depth = refine_depth;
  return o;
}

// A floor z = 0 with a wall block at x >= 2; start: a floor segment at x in [-3, -1]; goal: the floor strip
// before the wall and the wall's lowest half inch. `lift` (straight up) ends on the ceiling z = 4. A damper
// along +x pressed into the floor (tangent/normal = 1/.3 > tan(atan .5 + .2) = .76) slides to the wall and
// sticks in the concave corner: it solves the start alone.
constexpr const char* kCorner = R"(
name: corner
units: in
friction: 0.5
uncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.2, theta_f: 0.1}
cspace:
  - box: {min: [2, -2, 0], max: [4, 2, 2]}
bounds: {min: [-4, -2, 0], max: [4, 2, 4]}
start:
  segment: [[-3, 0, 0], [-1, 0, 0]]
goal:
  - polygon: [[1, -2, 0], [2, -2, 0], [2, 2, 0], [1, 2, 0]]
  - polygon: [[2, -2, 0], [2, 2, 0], [2, 2, 0.5], [2, -2, 0.5]]
motions:
  lift: {damper: [0, 0, 1]}
)";

// The motions of a decision-free strategy; a conditional one is a failure here.
std::vector<std::string> sequence(const Strategy& s) {
  EXPECT_FALSE(s.conditional()) << strategy_text(s);
  return s.motions;
}

Motion damper(const Vec3& v) {
  Motion m;
  m.kind = Motion::Kind::kDamper;
  m.target = v.normalized();
  return m;
}

TEST(TeachingSession, CornerLiftSolvesNothingAndNamesTheCeilingThenASlideSolvesTheStartAlone) {
  Session session(load_task_from_string(kCorner, "corner"), rollout_like());
  const TeachStep& lift = session.propose("lift");
  EXPECT_TRUE(lift.solved.empty());
  EXPECT_FALSE(session.solved());
  ASSERT_FALSE(lift.blocking.empty());
  for (const ReachedPiece& p : lift.blocking)
    for (const Vec3& q : p.polygon) EXPECT_DOUBLE_EQ(q.z(), 4);  // only the ceiling
  EXPECT_NEAR(lift.remaining_measure, 2, 1e-12);

  const TeachStep& slide = session.propose(damper(Vec3(1, 0, -0.3)));
  EXPECT_EQ(slide.motion, "taught_2");
  EXPECT_TRUE(session.solved());
  // [taught_2, lift] would leave the goal; the motion alone is the chain that solves the start.
  EXPECT_EQ(sequence(slide.chain), (std::vector<std::string>{"taught_2"}));
  ASSERT_TRUE(session.strategy().has_value());
  EXPECT_EQ(sequence(*session.strategy()), (std::vector<std::string>{"taught_2"}));
  EXPECT_NEAR(slide.solved_measure, 2, 1e-12);
  EXPECT_TRUE(verify_strategy(session.task(), *session.strategy(), rollout_like().verify).reliable);
}

// Buckley's table of solved regions with a sensed dispatch (Alg 5.1) on models/tasks/ridge.yaml: floor z = 0,
// ceiling z = 4, a ridge x in [0, .5] up to z = 1. Start: the ceiling segment x in [-1, 2]. Goal: the floor
// strip x in [-.5, 0] left of the ridge with the ridge's lowest half inch, the ridge top, and the floor x in
// [.5, 3] right of it. `down` lands on the floor or the ridge top within 4 tan(.2) = .81 of the start's x: in
// the goal except on the floor x in [-1.81, -.5). `right` slides along the floor into the ridge's left corner
// and rests there; from the ceiling it flies to the wall x = 4. So [down] fails on the left floor, [down,
// right] fails wherever down lands right of the ridge (right slides on to x = 4), and the robot must sense
// after down: on the left floor run right, elsewhere stop.
std::shared_ptr<const LoadedTask> ridge() {
  return load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/ridge.yaml");
}

TEST(TeachingSession, RidgeNeedsASensedDispatchAfterDown) {
  Session session(ridge(), rollout_like());
  const TeachStep& right = session.propose("right");
  EXPECT_TRUE(right.solved.empty());
  EXPECT_EQ(right.dispatches, 0);  // nothing taught before: no dispatch to build
  ASSERT_FALSE(right.blocking.empty());
  for (const ReachedPiece& p : right.blocking)
    for (const Vec3& q : p.polygon) EXPECT_DOUBLE_EQ(q.x(), 4);  // only the wall x = 4

  const TeachStep& down = session.propose("down");
  ASSERT_TRUE(session.solved());
  ASSERT_TRUE(session.strategy().has_value());
  const Strategy taught = *session.strategy();
  EXPECT_TRUE(same_strategy(taught, down.chain));
  EXPECT_NEAR(down.solved_measure, 3, 1e-12);  // the whole start, by the dispatch
  EXPECT_GE(down.dispatches, 1);
  // down, then: sensed on the left floor -> right; else stop.
  ASSERT_EQ(taught.nodes.size(), 2u);
  EXPECT_EQ(taught.nodes[0].motion, "down");
  ASSERT_EQ(taught.nodes[0].branches.size(), 2u);
  const StrategyBranch& sensed = taught.nodes[0].branches[0];
  const StrategyBranch& otherwise = taught.nodes[0].branches[1];
  EXPECT_FALSE(sensed.otherwise);
  EXPECT_TRUE(otherwise.otherwise);
  EXPECT_EQ(otherwise.first, -1);  // stop
  ASSERT_EQ(sensed.first, 1);
  EXPECT_EQ(taught.nodes[1].motion, "right");
  // The test's boxes hold every floor point left of the strip, grown by eps_s, and stay left of the ridge.
  ASSERT_FALSE(sensed.when.position.empty());
  double min_x = 1e9, max_x = -1e9;
  for (const AxisBox& b : sensed.when.position) {
    min_x = std::min(min_x, b.min.x());
    max_x = std::max(max_x, b.max.x());
    EXPECT_LE(b.min.z(), -0.1);
    EXPECT_GE(b.max.z(), 0.1);
    EXPECT_LT(b.max.z(), 0.5);  // the ridge top (z = 1) cannot read inside
  }
  EXPECT_LE(min_x, -1 - 4 * std::tan(0.2) - 0.1);
  EXPECT_GE(max_x, -0.5 + 0.1);
  EXPECT_LT(max_x, -0.5 + 0.1 + 1e-3);

  const VerifyOptions o = rollout_like().verify;
  EXPECT_TRUE(verify_strategy(session.task(), taught, o).reliable);
  EXPECT_FALSE(verify_motions(session.task(), {"down"}, o).reliable);
  EXPECT_FALSE(verify_motions(session.task(), {"down", "right"}, o).reliable);
}

TEST(TeachingSession, UndoRemovesTheStepAndItsInlineMotion) {
  Session session(load_task_from_string(kCorner, "corner"), rollout_like());
  session.propose("lift");
  session.propose(damper(Vec3(1, 0, -0.3)));
  ASSERT_TRUE(session.solved());
  ASSERT_NE(session.task().task.find_motion("taught_2"), nullptr);
  EXPECT_TRUE(session.undo());
  EXPECT_EQ(session.steps().size(), 1u);
  EXPECT_FALSE(session.solved());
  EXPECT_FALSE(session.strategy().has_value());
  EXPECT_TRUE(session.inline_motions().empty());
  EXPECT_EQ(session.task().task.find_motion("taught_2"), nullptr);
  EXPECT_TRUE(session.undo());
  EXPECT_FALSE(session.undo());
  EXPECT_THROW(session.propose("no_such_motion"), TaskError);
}

// Buckley §5.2: p1 first (beneath the hole) solves nothing of the start, which sticks on the top face near
// the hole; then p2 (behind the far wall, halfway down) with p1 after it solves the whole start: (p2, p1).
TEST(TeachingSession, HoleSessionReproducesBuckleySection52) {
  Session session(hole(), rollout_like());
  const TeachStep& p1 = session.propose("p1");
  EXPECT_TRUE(p1.solved.empty());
  ASSERT_FALSE(p1.blocking.empty());
  for (const ReachedPiece& p : p1.blocking)
    for (const Vec3& q : p.polygon) EXPECT_NEAR(q.z(), 0, 1e-9);  // the top surface, around the hole
  const TeachStep& p2 = session.propose("p2");
  EXPECT_TRUE(session.solved());
  EXPECT_EQ(sequence(p2.chain), (std::vector<std::string>{"p2", "p1"}));
  // p1's unsolved quarters merge back into the start: p2 from it, then p1 from where p2 stops.
  EXPECT_EQ(p2.verifications, 2);
  ASSERT_TRUE(session.strategy().has_value());
  EXPECT_EQ(sequence(*session.strategy()), (std::vector<std::string>{"p2", "p1"}));
}

// "It is important not to make p2 too deep, or else the robot may stick on the way to the hole" (L1435): the
// reason names top-face points in front of the hole (y < -1, z = 0) where p2_deep may stop.
TEST(TeachingSession, HoleSessionWithP2TooDeepNamesTheTopFaceBeforeTheHole) {
  Session session(hole(), rollout_like(1));
  session.propose("p1");
  const TeachStep& deep = session.propose("p2_deep");
  EXPECT_FALSE(session.solved());
  EXPECT_TRUE(deep.solved.empty());
  EXPECT_FALSE(session.strategy().has_value());
  const bool before_the_hole =
      std::any_of(deep.blocking.begin(), deep.blocking.end(), [](const ReachedPiece& p) {
        return p.kind == AtomKind::kFace &&
               std::all_of(p.polygon.begin(), p.polygon.end(),
                           [](const Vec3& q) { return std::abs(q.z()) < 1e-9; }) &&
               std::any_of(p.polygon.begin(), p.polygon.end(), [](const Vec3& q) { return q.y() < -1; });
      });
  EXPECT_TRUE(before_the_hole);
}

// The §5.2 values (mu = .25, theta_f = .3) instead of the §6.3.3 ones the task file uses: the same strategy.
TEST(TeachingSession, HoleSessionWithTheSection52FrictionAndForceError) {
  std::ifstream in(std::string(CMT_SOURCE_DIR) + "/models/tasks/hole.yaml");
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  const auto replace = [&](const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace("\nfriction: 0.48\n", "\nfriction: 0.25\n");
  replace("  theta_f: 0.05\n", "  theta_f: 0.3\n");
  Session session(load_task_from_string(text, "hole (Sec 5.2 values)"), rollout_like());
  EXPECT_TRUE(session.propose("p1").solved.empty());
  session.propose("p2");
  ASSERT_TRUE(session.strategy().has_value());
  EXPECT_EQ(sequence(*session.strategy()), (std::vector<std::string>{"p2", "p1"}));
}

}  // namespace
}  // namespace cmt::teaching
