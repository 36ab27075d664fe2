// Sliding forever (verifier/slide_forever.h): hand-checked speed bounds of non-progressive slides, and the
// atoms a damper or a spring on a floor may slide about forever.
#include "verifier/slide_forever.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "tests/verifier/test_geometry.h"
#include "verifier/damper_projection.h"
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

// The exact damper edge bound by hand: into a square concave corner (floor +z, wall +x) at 45 degrees, a
// v_a turned d along the edge and a' about it slides at sin d − mu sqrt(2) cos d cos a', largest at d =
// theta_v, a' = 0: sin .3 − .1 sqrt(2) cos .3 = .1604 (the face-count bound gives .2000).
TEST(SlideForever, ExactEdgeBoundByHand) {
  const Vec3 floor = Vec3::UnitZ(), wall = Vec3::UnitX(), e = Vec3::UnitY();
  const Vec3 into_corner = Vec3(-1, 0, -1).normalized();
  EXPECT_NEAR(edge_slide_speed(into_corner, 0.3, floor, 0.1, wall, 0.1, e),
              std::sin(0.3) - 0.1 * std::sqrt(2.0) * std::cos(0.3), 1e-8);
  // two_blocks v3 (down, tilted .29 left) in A's right corner: mu .25 holds it, though the face-count bound
  // sin(.25 − .245) / cos(.245) = .005 does not.
  EXPECT_LT(edge_slide_speed(Vec3(-0.3, 0, -1).normalized(), 0.25, floor, 0.25, wall, 0.25, e), 0);
  EXPECT_GT(edge_nonprogressive_speed(0, 0.25, 0.25), 0);
  // two_blocks v2 (down-left 45 degrees) at B's top-left convex edge (top +z, wall −x) and at its foot
  // (floor +z, wall −x): every v_a leaves the edge.
  EXPECT_LT(edge_slide_speed(into_corner, 0.25, floor, 0, -wall, 0, e), 0);
  // Tilted along the edge by .1: only the slide against the tilt is non-progressive, sin(.3 − .1) with mu 0.
  const Vec3 tilted = (std::cos(0.1) * into_corner + std::sin(0.1) * e).normalized();
  EXPECT_NEAR(edge_slide_speed(tilted, 0.3, floor, 0, wall, 0, e), std::sin(0.2), 1e-8);
}

// Against brute force: the exact bound is at least every sampled admissible v_a's slide speed (sound) and
// within 1e-3 of the best sample (tight), and never above the face-count bound.
TEST(SlideForever, ExactEdgeBoundAgainstSampling) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1), angle(0.1, 0.6), friction(0, 0.25);
  auto random_unit = [&] { return Vec3(unit(rng), unit(rng), unit(rng)).normalized(); };
  const Vec3 e = Vec3::UnitY();
  int compared = 0, leaving = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const double a1 = 3.14159 * unit(rng),
                 a2 = a1 + (0.3 + 2.5 * (unit(rng) + 1) / 2) * (unit(rng) < 0 ? -1 : 1);
    const Vec3 n1(std::cos(a1), 0, std::sin(a1)), n2(std::cos(a2), 0, std::sin(a2));
    const double mu1 = friction(rng), mu2 = friction(rng), theta_v = angle(rng);
    // Commands about W's directions, some pointing out of it.
    const double mix = 0.5 + 0.7 * unit(rng);
    const Vec3 u = (-(mix * n1 + (1 - mix) * n2).normalized() + 0.4 * unit(rng) * e).normalized();
    const double exact = edge_slide_speed(u, theta_v, n1, mu1, n2, mu2, e);
    const double c = n1.dot(n2), det = 1 - c * c;
    // Samples in the cap, on its rim and on the planes N_i = 0 (where the peaks lie).
    const Vec3 a[2] = {(n1 - c * n2).normalized(), (n2 - c * n1).normalized()};
    double sampled = -1;
    for (int k = 0; k < 30000; ++k) {
      const Vec3 w = random_unit();
      const Vec3 side = (w - w.dot(u) * u).normalized();
      const double d = k % 3 == 1 ? theta_v : theta_v * std::sqrt((unit(rng) + 1) / 2);
      Vec3 v = std::cos(d) * u + std::sin(d) * side;
      if (k % 3 == 2) {
        const Vec3& plane = a[k % 2];
        v = (v - v.dot(plane) * plane).normalized();
        if (v.dot(u) < std::cos(theta_v)) continue;
      }
      const double b1 = -n1.dot(v), b2 = -n2.dot(v);
      const double N1 = (b1 - c * b2) / det, N2 = (b2 - c * b1) / det;
      if (N1 < -1e-12 || N2 < -1e-12) continue;
      const double along = v.dot(e);
      if (along * u.dot(e) > 0) continue;  // progressive
      sampled = std::max(sampled, std::abs(along) - mu1 * std::max(0.0, N1) - mu2 * std::max(0.0, N2));
    }
    compared += sampled > 0;
    leaving += exact < 0;
    if (sampled > 0) {
      EXPECT_GE(exact, sampled) << trial;
      EXPECT_LE(exact, sampled + 1e-3) << trial;
    }
    const double gamma = std::asin(std::min(1.0, std::abs(u.dot(e))));
    if (exact > 0) {
      EXPECT_LE(exact, edge_nonprogressive_speed(gamma, theta_v, std::min(mu1, mu2)) + 1e-9);
    }
  }
  EXPECT_GT(compared, 40);  // both kinds of case occur
  EXPECT_GT(leaving, 10);
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
