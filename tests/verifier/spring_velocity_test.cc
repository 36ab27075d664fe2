// The velocity-form spring model (docs/verifier.md, "Velocity-form spring model"): the spiral bound checked
// against an independent integration of the extreme spiral, the reach bound derived by hand, and the
// projection checked against trajectories of the model's own dynamics (a fixed p* within eps_s of p, the
// velocity within theta_v of p* − x, Coulomb sliding on faces), integrated here without the verifier.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "tests/verifier/test_geometry.h"
#include "verifier/spring.h"
#include "verifier/spring_projection.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

using test::face_at;

// delta(.25) = e^(−.25 / tan .25) sin .25: tan .25 = .2553419, .25 / .2553419 = .9790802, e^−.9790802 =
// .3756611, sin .25 = .2474040, product .0929390. theta_v = 0: straight paths, no deviation.
TEST(SpringVelocity, SpiralDeviationHandValues) {
  EXPECT_NEAR(spring_spiral_deviation(0.25), 0.092939, 1e-6);
  EXPECT_EQ(spring_spiral_deviation(0), 0);
}

// The extreme spiral (velocity always theta_v off the direction to p*, turning the same way; Buckley App. B)
// integrated with small steps: its largest distance from seg[x0, p*] is delta |x0 − p*| (the bound is tight:
// within 1 %), never more.
TEST(SpringVelocity, ExtremeSpiralAttainsTheDeviationBound) {
  for (const double theta : {0.1, 0.25, 0.5}) {
    const Vec3 p(0, 0, 0), x0(3, 0, 0);
    const double r0 = (x0 - p).norm(), delta = spring_spiral_deviation(theta);
    Vec3 x = x0;
    double worst = 0;
    const double h = 1e-5;
    for (int i = 0; i < 10'000'000 && (x - p).norm() > 1e-4; ++i) {
      const Vec3 u = (p - x).normalized();
      const Vec3 side = Vec3::UnitZ().cross(u);
      const Vec3 v = std::cos(theta) * u + std::sin(theta) * side;
      x += h * v;
      // distance from seg[x0, p] (the x axis between 0 and 3)
      const double along = std::clamp(x.x(), 0.0, 3.0);
      worst = std::max(worst, (x - Vec3(along, 0, 0)).norm());
    }
    EXPECT_LE(worst, delta * r0 * (1 + 1e-3)) << theta;
    EXPECT_GE(worst, delta * r0 * 0.99) << theta;
  }
}

std::string floor_scene(const std::string& start, const std::string& p) {
  return "name: t\nunits: in\nfriction: 0.5\nuncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.1, theta_f: "
         "0.1, step: 0.1}\ncspace: []\nbounds: {min: [-5, -5, 0], max: [5, 5, 5]}\nstart: {point: " +
         start + "}\ngoal: {point: " + start + "}\nmotions:\n  m: {spring: " + p +
         "}\nstrategies:\n  s: [m]\n";
}

// Start (3,0,0) on the floor of the box [-5,5]^2 x [0,5], p = (0,0,-5), eps_s = .1, theta_v = .1:
// |x0 − p| = sqrt(34) = 5.83095; + eps_s = 5.93095 (>= |x0 − p*|). Zones: the floor (depth 5 + .1, zone
// radius 5.1 tan .1 + .1 = .61 about p' = 0, inside the floor): 5.1 / cos .1 = 5.1256 < 5.93. The walls and
// the ceiling are farther than 5.93 + .1 from p (the nearest wall point (5,0,0) is sqrt(50) = 7.07 away):
// not reachable, so their zones do not count. The bound: 5.93095 + .1 = 6.03095.
TEST(SpringVelocity, ReachBoundHandValue) {
  auto task = load_task_from_string(floor_scene("[3, 0, 0]", "[0, 0, -5]"), "test");
  const ReachedSet start = ReachedSet::from_region(*task, task->task.start);
  EXPECT_NEAR(velocity_reach_bound(task->cspace, start, Vec3(0, 0, -5), task->task.uncertainty), 6.03095,
              1e-5);
}

// The model's dynamics, integrated directly: p* = p − b (|b| <= eps_s) fixed, the velocity direction within
// theta_v of p* − x (here: turned by theta_v or a random smaller angle about a random axis, redrawn now and
// then), Coulomb sliding on horizontal faces (slide along the tangential part of the velocity when it
// exceeds mu times the push into the face, else stick; leave when the velocity points up). Faces: the floor
// z = 0 and, optionally, the top z = 1 of a block |x|, |y| <= 1 (whose sides the paths never reach here).
struct Path {
  std::vector<Vec3> contact;  // contact points visited
  Vec3 end;
  bool stuck = false;
};

// `extreme`: the error turns the velocity by exactly theta toward a fixed axis drawn from +-y, +-z (the
// lateral and the lifting extreme spirals of App. B) half the time, else as below.
Path simulate(const Vec3& start, const Vec3& p, double eps, double theta, double mu, bool block,
              std::mt19937& rng, bool extreme = false) {
  std::uniform_real_distribution<double> unit(-1, 1), frac(0, 1);
  auto random_unit = [&] {
    Vec3 v;
    do v = Vec3(unit(rng), unit(rng), unit(rng));
    while (v.norm() > 1 || v.norm() < 1e-3);
    return v.normalized();
  };
  const Vec3 target = p - random_unit() * eps * std::cbrt(frac(rng));  // p* in the ball
  Vec3 axis = random_unit();
  double angle = frac(rng) < 0.5 ? theta : theta * frac(rng);
  bool fixed = false;
  if (extreme && frac(rng) < 0.5) {
    const Vec3 axes[] = {Vec3::UnitY(), -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()};
    axis = axes[static_cast<int>(4 * frac(rng)) % 4];
    angle = theta;
    fixed = true;
  }
  Path out;
  Vec3 x = start;
  const double h = 1e-3;
  auto on_top = [&](const Vec3& q) {
    return block && std::abs(q.z() - 1) < 1e-12 && std::abs(q.x()) <= 1 && std::abs(q.y()) <= 1;
  };
  auto on_floor = [&](const Vec3& q) { return std::abs(q.z()) < 1e-12; };
  for (int i = 0; i < 200'000; ++i) {
    if (!fixed && frac(rng) < 0.002) {  // the error may switch (§3.2.1)
      axis = random_unit();
      angle = frac(rng) < 0.5 ? theta : theta * frac(rng);
    }
    const Vec3 w = target - x;
    if (w.norm() < 1e-6) break;
    Vec3 perp = axis - axis.dot(w.normalized()) * w.normalized();
    if (perp.norm() < 1e-9) perp = Vec3::UnitX() - Vec3::UnitX().dot(w.normalized()) * w.normalized();
    const Vec3 v = std::cos(angle) * w.normalized() + std::sin(angle) * perp.normalized();
    if (on_top(x) || on_floor(x)) {
      out.contact.push_back(x);
      if (v.z() < 0) {  // pushes into the face
        const Vec3 vt(v.x(), v.y(), 0);
        if (vt.norm() <= mu * -v.z()) {
          out.stuck = true;
          break;
        }
        x += h * vt.normalized();  // off the block's top it is free from the next step
        continue;
      }
    }
    Vec3 next = x + h * v;
    if (next.z() <= 0) {  // lands on the floor
      next.z() = 0;
    } else if (block && x.z() >= 1 && next.z() < 1 && std::abs(next.x()) <= 1 && std::abs(next.y()) <= 1) {
      next.z() = 1;  // lands on the block's top
    }
    EXPECT_FALSE(block && next.z() > 0 && next.z() < 1 && std::abs(next.x()) < 1 && std::abs(next.y()) < 1)
        << "a path entered the block's side";
    x = next;
  }
  out.end = x;
  return out;
}

struct VelocityProjected {
  std::shared_ptr<const LoadedTask> task;
  SpringProjection projection;
};

VelocityProjected project_velocity(const std::string& yaml) {
  auto task = load_task_from_string(yaml, "test");
  const ReachedSet start = ReachedSet::from_region(*task, task->task.start);
  SpringProjection p =
      forward_project_spring(*task, start, task->task.motions.at(0).target, SpringModel::kVelocity);
  return {task, std::move(p)};
}

// Sliding on the floor from (3,0,0) toward p' = 0 (p = (0,0,-5)). Hand bounds on what the model allows:
// the in-plane distance to p*' never exceeds 3 + .1 (|p*' − p'| <= .1), so no point farther than 3.2 from
// the origin; the in-plane angle about p*' grows by at most the integral of tan(beta(s)) / s, beta(s) =
// asin(sin .1 sqrt(s^2 + 5.1^2) / s): for s >= 2 beta <= asin(.0998 (5.478) / 2) = .2769, so by s = 2 the
// angle is at most tan(.2769) ln(3.1 / 2) = .125: the point (0, 2, 0) (at a right angle) is out of reach,
// and so is (1.5, 1.2, 0) (1.2 off the axis at 1.92 from p*', angle .67). Must hold: the error-free path
// (3,0,0) -> (0,0,0) sticks at d = 5 mu = 2.5 (tangential / normal = d / 5 <= .5), so (2.5, 0, 0) terminates.
TEST(SpringVelocity, FloorSlideContainsTheModelsPathsAndExcludesWhatItCannotReach) {
  const VelocityProjected r = project_velocity(floor_scene("[3, 0, 0]", "[0, 0, -5]"));
  const SpringProjection& pr = r.projection;
  EXPECT_FALSE(pr.fallback);
  EXPECT_LT(pr.reached.distance(Vec3(2.5, 0, 0)), 1e-9);
  EXPECT_LT(pr.termination.distance(Vec3(2.5, 0, 0)), 1e-9);
  EXPECT_GT(pr.reached.distance(Vec3(0, 2, 0)), 0.5);
  EXPECT_GT(pr.reached.distance(Vec3(1.5, 1.2, 0)), 0.2);
  EXPECT_GT(pr.reached.distance(Vec3(-3.3, 0, 0)), 0.05);
  EXPECT_GT(pr.reached.distance(Vec3(3.3, 0, 0)), 0.05);
  std::mt19937 rng(7);
  for (int k = 0; k < 300; ++k) {
    const Path path = simulate(Vec3(3, 0, 0), Vec3(0, 0, -5), 0.1, 0.1, 0.5, false, rng);
    for (const Vec3& q : path.contact) ASSERT_LT(pr.reached.distance(q), 1e-6) << k;
    ASSERT_TRUE(path.stuck) << k;
    ASSERT_LT(pr.termination.distance(path.end), 1e-6) << k;
  }
}

std::string block_scene() {
  return "name: t\nunits: in\nfriction: 0.5\nuncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.1, theta_f: "
         "0.1, step: 0.1}\ncspace:\n  - box: {min: [-1, -1, 0], max: [1, 1, 1]}\nbounds: {min: [-5, -5, 0], "
         "max: [5, 5, 5]}\nstart: {point: [0, 0, 1]}\ngoal: {point: [0, 0, 1]}\nmotions:\n  m: {spring: [4, "
         "0, -1]}\nstrategies:\n  s: [m]\n";
}

// From the top of a block (0,0,1) toward p = (4,0,-1): the robot slides to the edge x = 1 (the pull (4,0,-2)
// presses into the top), flies off it and lands on the floor, where it slides toward p' = (4,0,0) and sticks
// within d <= 1 x mu = .5 of it (error-free: at (3.5, 0, 0), which must terminate). Out of reach: the floor
// behind the block (−2, 0, 0) (every path moves toward p*: x grows while |y| stays small), and (1.5, 3, 0),
// which is at .84 rad from the start about p (vectors (−2.5, 3, 1) and (−4, 0, 2)) while the flight's spiral
// angle is at most tan(.1) ln(4.57 / 4.03) = .013 and slides add at most a few tenths. Every path of the
// dynamics must lie in the prediction.
TEST(SpringVelocity, FlightOffABlockContainsTheModelsPathsAndExcludesWhatItCannotReach) {
  const VelocityProjected r = project_velocity(block_scene());
  const SpringProjection& pr = r.projection;
  const int floor = face_at(r.task->cspace, Vec3(0, 0, 1), Vec3(3, 0, 0));
  ASSERT_GE(floor, 0);
  EXPECT_FALSE(pr.fallback);
  EXPECT_TRUE(pr.reached.contains_atom(floor));
  EXPECT_LT(pr.termination.distance(Vec3(3.5, 0, 0)), 1e-9);
  EXPECT_GT(pr.reached.distance(Vec3(-2, 0, 0)), 0.5);
  EXPECT_GT(pr.reached.distance(Vec3(1.5, 3, 0)), 1.0);
  std::mt19937 rng(11);
  for (int k = 0; k < 200; ++k) {
    const Path path = simulate(Vec3(0, 0, 1), Vec3(4, 0, -1), 0.1, 0.1, 0.5, true, rng);
    for (const Vec3& q : path.contact) ASSERT_LT(pr.reached.distance(q), 1e-6) << k << " " << q.transpose();
    ASSERT_TRUE(path.stuck) << k;
    ASSERT_LT(pr.termination.distance(path.end), 1e-6) << k;
  }
}

// The hole task's error sizes (eps_s = .2, theta_v = .25), where the spiral regions (docs/verifier.md
// "Spiral regions") bound flights and slides more tightly than the tubes: every path of the model's dynamics,
// extreme spirals included (lateral and lifting), must still lie in the prediction. Floor: mu = .25, from
// (3, 0, 0) toward p = (0, 0, -2): slides (and hops: the pull is within theta_v of the floor there).
std::string wide_scene(const std::string& cspace, const std::string& start, const std::string& p, double mu,
                       double eps = 0.2) {
  const std::string e = std::to_string(eps);
  return "name: t\nunits: in\nfriction: " + std::to_string(mu) + "\nuncertainty: {eps_s: " + e +
         ", eps_p: 0.2, theta_v: 0.25, theta_f: 0.1, step: 0.2}\ncspace: " + cspace +
         "\nbounds: {min: [-5, -5, 0], max: [5, 5, 5]}\nstart: {point: " + start +
         "}\ngoal: {point: " + start + "}\nmotions:\n  m: {spring: " + p + "}\nstrategies:\n  s: [m]\n";
}

// 300 paths of the model's dynamics from `start` toward p (extreme spirals included): every contact point
// is reached and every sticking end terminates; returns how many stuck.
int count_contained_paths(const SpringProjection& pr, const Vec3& start, const Vec3& p, double eps, double mu,
                          bool block, unsigned seed) {
  std::mt19937 rng(seed);
  int stuck = 0;
  for (int k = 0; k < 300; ++k) {
    const Path path = simulate(start, p, eps, 0.25, mu, block, rng, true);
    for (const Vec3& q : path.contact) EXPECT_LT(pr.reached.distance(q), 1e-6) << k << " " << q.transpose();
    if (!path.stuck) continue;
    ++stuck;
    EXPECT_LT(pr.termination.distance(path.end), 1e-6) << k;
  }
  return stuck;
}

// eps_s = .2 (the hole's) and .02 (where the in-plane angle beta(d), not the p* error, shapes the slide).
TEST(SpringVelocity, WideErrorsFloorSlidesAndHopsStayInThePrediction) {
  for (const double eps : {0.2, 0.02}) {
    const VelocityProjected r = project_velocity(wide_scene("[]", "[3, 0, 0]", "[0, 0, -2]", 0.25, eps));
    EXPECT_FALSE(r.projection.fallback);
    EXPECT_GT(count_contained_paths(r.projection, Vec3(3, 0, 0), Vec3(0, 0, -2), eps, 0.25, false, 5), 100);
  }
}

// Flights off a block's top toward p = (4, 0, -1) with the hole's error sizes, lifting spirals included.
TEST(SpringVelocity, WideErrorsFlightsOffABlockStayInThePrediction) {
  const VelocityProjected r = project_velocity(
      wide_scene("\n  - box: {min: [-1, -1, 0], max: [1, 1, 1]}", "[0, 0, 1]", "[4, 0, -1]", 0.5));
  EXPECT_FALSE(r.projection.fallback);
  EXPECT_GT(count_contained_paths(r.projection, Vec3(0, 0, 1), Vec3(4, 0, -1), 0.2, 0.5, true, 13), 100);
}

// The CLI selects the model; the verdict for the cube's single sticking motion is reliable under both.
// Sticking at a vertex under the velocity model (SpringProjector::velocity_may_stick). The hole's corner v =
// (-1,-1,0) (rim of the near and left walls) touches faces with normals +x, +y, +z; mu = .48 (phi = .4474),
// theta_v = .25. Each face cone rotated by theta_v has half-angle .697; its ray (cos .697, −sin .697 / sqrt
// 2, −sin .697 / sqrt 2) = (.767, −.455, −.455) about +x and the two like it about +y and +z sum to −.143
// (1,1,1): the widened generators surround the origin, so spring_sticking_regions' weak region is everything.
// For p = (0,2,-1) the robot may stick at v iff some −F in the sum FC of the (unwidened) face cones lies
// within .25 of v − p* (p* within .2 of p: within .31 rad of v − p = (−1,−3,1)). w = (1,1,1)/sqrt 3 is .955
// rad from each normal, less than pi/2 − .4474 = 1.123, so w . r >= 0 on FC; (−1,−3,1) is acos(−3 / (3.317
// sqrt 3)) = 2.12 rad from w, i.e. .55 rad beyond that half-space's boundary, more than .31: no end at v. For
// p =
// (-2,-2,-1) (pulling into the corner: v − p = (1,1,1), the sum of the three normals) the robot may stay.
TEST(SpringVelocity, VertexStickingUsesTheForceConeNotWidenedGenerators) {
  auto task = load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/hole.yaml");
  const CSpace& c = task->cspace;
  int vertex = -1;
  for (std::size_t vi = 0; vi < c.vertices().size(); ++vi)
    if ((c.vertices()[vi].point - Vec3(-1, -1, 0)).norm() < 1e-12)
      vertex = static_cast<int>(c.faces().size() + c.edges().size() + vi);
  ASSERT_GE(vertex, 0);
  EXPECT_TRUE(spring_sticking_regions(c, vertex, task->task.uncertainty).weak.contains(Vec3(0, 2, -1)));
  ReachedSet start(c);
  start.add_vertex(vertex);
  const SpringProjection away = forward_project_spring(*task, start, Vec3(0, 2, -1), SpringModel::kVelocity);
  EXPECT_FALSE(away.termination.has_vertex(vertex));
  const SpringProjection into =
      forward_project_spring(*task, start, Vec3(-2, -2, -1), SpringModel::kVelocity);
  EXPECT_TRUE(into.termination.has_vertex(vertex));
}

// With the rollouts' stop rule (kappa .01): under Coulomb sticking alone (kappa 0) a slow non-progressive
// slide never ends, so termination is not proved (docs/verifier.md "Termination: sliding forever").
TEST(SpringVelocity, CubeStickIsReliableUnderTheVelocityModel) {
  auto task = load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/cube.yaml");
  const VerifyResult r =
      verify_strategy(*task, *task->task.find_strategy("stick"), {SpringModel::kVelocity, 0.01});
  EXPECT_TRUE(r.reliable) << r.failure;
  EXPECT_EQ(r.spring_model, SpringModel::kVelocity);
}

}  // namespace
}  // namespace cmt
