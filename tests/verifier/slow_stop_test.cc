// A stop rule that counts slides slower than kappa x the reference speed as stops (the rollouts' rule,
// controllers/termination.h) widens the termination sets (docs/verifier.md "Slow slides count as stops"):
// dampers by asin(kappa) beyond theta_v in the "never" test, velocity-model springs by kappa (|p − x0| +
// eps_s) added to eps_s in the weak sticking regions. Hand-checked thresholds on a floor.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "tests/verifier/test_geometry.h"
#include "verifier/atom_cone.h"
#include "verifier/damper.h"
#include "verifier/spring_projection.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

using test::face_at;

constexpr double kKappa = 0.01;  // asin(.01) = .0100002

// Room x, y in [-5, 5], z in [0, 5], mu = .5 (phi = atan .5 = .4636476), theta_v = .1, eps_s = .1.
std::string room(const std::string& start, const std::string& motion) {
  return "name: t\nunits: in\nfriction: 0.5\nuncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.1, theta_f: "
         "0.1, step: 0.1}\ncspace: []\nbounds: {min: [-5, -5, 0], max: [5, 5, 5]}\nstart: {point: " +
         start + "}\ngoal: {point: " + start + "}\nmotions:\n  m: " + motion + "\nstrategies:\n  s: [m]\n";
}

// A damper pushing into the floor at alpha = phi + theta_v + beyond from −z, toward +x.
std::string damper(double beyond) {
  const double alpha = std::atan(0.5) + 0.1 + beyond;
  std::ostringstream s;
  s.precision(17);
  s << "{damper: [" << std::sin(alpha) << ", 0, " << -std::cos(alpha) << "]}";
  return s.str();
}

// The floor's class: never for both beyond values without the rule; with it, may exactly when beyond <
// asin(kappa) (.008 < .0100002 < .012). "must" is untouched by the rule (a command straight down).
TEST(SlowStop, DamperNeverTestWidensByAsinKappa) {
  const auto task = load_task_from_string(room("[0, 0, 0]", damper(0.008)), "t");
  const CSpace& c = task->cspace;
  const AtomCones cones(c);
  const int floor = face_at(c, Vec3::UnitZ(), Vec3(0, 0, 0));
  ASSERT_GE(floor, 0);
  const double stop = std::asin(kKappa);
  for (const double beyond : {0.008, 0.012}) {
    const double alpha = std::atan(0.5) + 0.1 + beyond;
    const Vec3 v(std::sin(alpha), 0, -std::cos(alpha));
    EXPECT_EQ(classify_damper(cones, floor, v, 0.1), StickClass::kNever) << beyond;
    EXPECT_EQ(classify_damper(cones, floor, v, 0.1, stop),
              beyond < stop ? StickClass::kMay : StickClass::kNever)
        << beyond;
  }
  EXPECT_EQ(classify_damper(cones, floor, -Vec3::UnitZ(), 0.1, stop), StickClass::kMust);
}

// The whole projection: from (0, 0, 0) the robot slides along +x to the wall; with the rule (beyond .008)
// the floor's reached strip is in the termination set, without it only the wall's edge is.
TEST(SlowStop, DamperTerminationHoldsTheSlowFloor) {
  const auto task = load_task_from_string(room("[0, 0, 0]", damper(0.008)), "t");
  const Strategy& s = *task->task.find_strategy("s");
  const VerifyResult coulomb = verify_strategy(*task, s);
  const VerifyResult slow = verify_strategy(*task, s, {SpringModel::kVelocity, kKappa});
  EXPECT_DOUBLE_EQ(slow.stop_relative_speed, kKappa);
  for (const Vec3& q : {Vec3(0, 0, 0), Vec3(2.5, 0, 0)}) {
    EXPECT_EQ(slow.steps[0].termination.distance(q), 0) << q.transpose();
    EXPECT_GT(coulomb.steps[0].termination.distance(q), 2) << q.transpose();
  }
  // On the wall's edge up to the double rounding of its lifted points (coordinates of 5: 1.1e-15).
  EXPECT_LE(coulomb.steps[0].termination.distance(Vec3(5, 0, 0)), 5e-15);
}

// kappa (max |p − x0| + eps_s): start (1.4, 0, 0), p = (0, 0, −2): |x0 − p| = sqrt(1.96 + 4) = 2.441311,
// + .1 = 2.541311, x .01 = .02541311. kappa = 0: none.
TEST(SlowStop, SpringSlowStopRadiusHandValue) {
  const auto task = load_task_from_string(room("[1.4, 0, 0]", "{spring: [0, 0, -2]}"), "t");
  const ReachedSet start = ReachedSet::from_region(*task, task->task.start);
  const Uncertainty& u = task->task.uncertainty;
  EXPECT_NEAR(slow_stop_radius(start, Vec3(0, 0, -2), u, kKappa), 0.02541311, 1e-8);
  EXPECT_EQ(slow_stop_radius(start, Vec3(0, 0, -2), u, 0), 0);
}

// The floor's weak disk about p' = 0 for p = (0, 0, −2) (depth h = 2): x within e of the cone p + cone(+z,
// psi), psi = phi + theta_v = .5636476, i.e. radius h tan psi + e / cos psi (tan psi = .6320426, cos psi =
// .8453119): e = eps_s = .1 gives 1.382385; e = .1 + .0254131 gives 1.412448. The start at radius 1.4 lies
// between: it is a termination point with the rule and outside without it: the disk's outer polygon
// (kSpringDiskSides = 24, a corner on the +x axis) reaches 1.382385 / cos(pi / 24) = 1.394313, .005687 short.
TEST(SlowStop, SpringWeakDiskGrowsBySlowStopRadius) {
  const auto task = load_task_from_string(room("[1.4, 0, 0]", "{spring: [0, 0, -2]}"), "t");
  const Strategy& s = *task->task.find_strategy("s");
  const VerifyResult coulomb = verify_strategy(*task, s, {SpringModel::kVelocity, 0});
  const VerifyResult slow = verify_strategy(*task, s, {SpringModel::kVelocity, kKappa});
  const Vec3 start(1.4, 0, 0);
  EXPECT_EQ(slow.steps[0].termination.distance(start), 0);
  EXPECT_NEAR(coulomb.steps[0].termination.distance(start), 0.005687, 2e-6);
  // Both hold the points nearer p' than 1.38 on the robot's way (it slides toward p').
  EXPECT_EQ(coulomb.steps[0].termination.distance(Vec3(1.3, 0, 0)), 0);
  // The free-space rest ball (unused here: the robot never leaves the floor) grows by the same radius.
  EXPECT_NEAR(slow.steps[0].free_radius, 0.1 + 0.02541311, 1e-8);
}

}  // namespace
}  // namespace cmt
