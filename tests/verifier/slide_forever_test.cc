// Sliding forever (verifier/slide_forever.h): hand-checked speed bounds of non-progressive slides, and the
// atoms a damper or a spring on a floor may slide about forever.
#include "verifier/slide_forever.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "tests/verifier/test_geometry.h"
#include "verifier/forward_projection.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

using test::face_at;

// Room x, y in [-5, 5], z in [0, 5], friction mu, theta_v; the start is a point on the floor.
std::string room(double mu, double theta_v, const std::string& start, const std::string& motion) {
  std::ostringstream s;
  s.precision(17);
  s << "name: t\nunits: in\nfriction: " << mu
    << "\nuncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: " << theta_v
    << ", theta_f: 0.1, step: 0.1}\ncspace: []\nbounds: {min: [-5, -5, 0], max: [5, 5, 5]}\nstart: {point: "
    << start << "}\ngoal: {point: " << start << "}\nmotions:\n  m: " << motion << "\nstrategies:\n  s: [m]\n";
  return s.str();
}

TEST(SlideForever, FaceSpeedBound) {
  // Straight at the face (beta 0): non-progressive velocities reach psi = theta_v; speed sin(theta_v − phi)
  // / cos(phi) with phi = atan(.1) = .0996687.
  EXPECT_NEAR(face_nonprogressive_speed(0, 0.27, 0.1), std::sin(0.27 - 0.0996687) / std::cos(0.0996687),
              1e-6);
  // beta .2 < theta_v .3: psi = acos(cos .3 / cos .2) = .2248; phi = 0 gives sin(psi).
  EXPECT_NEAR(face_nonprogressive_speed(0.2, 0.3, 0), std::sin(std::acos(std::cos(0.3) / std::cos(0.2))),
              1e-6);
  EXPECT_LT(face_nonprogressive_speed(0.31, 0.3, 0), 0);  // beta > theta_v: every slide progresses
  EXPECT_LT(face_nonprogressive_speed(0, 0.2, 0.25), 0);  // theta_v < phi = .245: they stick
}

TEST(SlideForever, EdgeSpeedBound) {
  EXPECT_NEAR(edge_nonprogressive_speed(0.1, 0.3, 0), std::sin(0.2), 1e-6);
  EXPECT_NEAR(edge_nonprogressive_speed(0, 0.3, 0.1), std::sin(0.3 - 0.0996687) / std::cos(0.0996687), 1e-6);
  EXPECT_LT(edge_nonprogressive_speed(0.35, 0.3, 0), 0);
  EXPECT_LT(edge_nonprogressive_speed(0.1, 0.3, 0.25), 0);  // .2 < phi .245
}

// A damper straight down on the floor: theta_v .3 > phi = atan .1 slides about in every direction at .2 V,
// far above kappa = .01: the floor is a slide-forever atom and the verdict is unreliable although the goal is
// the whole floor. With mu .25 and theta_v .25 (the hole's values) the fastest such slide is .0052 V, below
// kappa: the stop rule ends it (but not with kappa 0). Tilted .5 rad from straight down, every slide
// progresses.
TEST(SlideForever, DamperOnAFloor) {
  struct Case {
    double mu, theta_v, kappa;
    std::string dir;
    bool forever;
  };
  for (const Case& k : {Case{0.1, 0.3, 0.01, "[0, 0, -1]", true}, Case{0.25, 0.25, 0.01, "[0, 0, -1]", false},
                        Case{0.25, 0.25, 0, "[0, 0, -1]", true},
                        Case{0.1, 0.3, 0.01, "[0.479425538604203, 0, -0.8775825618903728]", false}}) {
    const auto task =
        load_task_from_string(room(k.mu, k.theta_v, "[0, 0, 0]", "{damper: " + k.dir + "}"), "t");
    const CSpace& c = task->cspace;
    const int floor = face_at(c, Vec3::UnitZ(), Vec3(0, 0, 0));
    ASSERT_GE(floor, 0);
    const AtomCones cones(c);
    const ReachedSet start = ReachedSet::from_region(*task, task->task.start);
    const DamperProjection p =
        forward_project_damper(*task, cones, start, task->task.motions[0].target, k.kappa, 0);
    const bool on_floor =
        std::find(p.slide_forever.begin(), p.slide_forever.end(), floor) != p.slide_forever.end();
    EXPECT_EQ(on_floor, k.forever) << "mu " << k.mu << " theta_v " << k.theta_v << " kappa " << k.kappa;
  }
}

// A spring pulled 1 in below the floor from 3 in away: its zone is the disk of radius 1.1 tan(.3) + .1 = .44
// about (0, 0, 0). The robot reaches it (it slides toward the foot), so with theta_v .3 > phi it may slide
// forever; with mu .5 (phi .46 > theta_v) every non-progressive velocity sticks.
TEST(SlideForever, SpringZoneOnAFloor) {
  for (const double mu : {0.1, 0.5}) {
    const auto task = load_task_from_string(room(mu, 0.3, "[3, 0, 0]", "{spring: [0, 0, -1]}"), "t");
    const CSpace& c = task->cspace;
    const int floor = face_at(c, Vec3::UnitZ(), Vec3(0, 0, 0));
    const VerifyResult r =
        verify_strategy(*task, task->task.strategies[0], {SpringModel::kVelocity, 0.01, 0});
    ASSERT_FALSE(r.steps.empty());
    const auto& sf = r.steps[0].slide_forever;
    EXPECT_EQ(std::find(sf.begin(), sf.end(), floor) != sf.end(), mu < 0.3) << "mu " << mu;
    if (mu < 0.3) {
      EXPECT_NE(r.failure.find("may slide forever"), std::string::npos) << r.failure;
    }
  }
  // The zone only: a reached set far from the foot is not flagged.
  const auto task = load_task_from_string(room(0.1, 0.3, "[3, 0, 0]", "{spring: [0, 0, -1]}"), "t");
  const ReachedSet start = ReachedSet::from_region(*task, task->task.start);
  const std::vector<bool> strong(static_cast<std::size_t>(task->cspace.atom_count()), false);
  EXPECT_TRUE(spring_slide_forever_atoms(task->cspace, start, start, Vec3(0, 0, -1), task->task.uncertainty,
                                         0.01, strong)
                  .empty());
}

}  // namespace
}  // namespace cmt
