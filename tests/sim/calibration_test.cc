// Physics calibration (docs/rollouts.md "Calibration"): the simulated robot against Coulomb's law, through
// the rollouts' own controllers and plant, on a face and in a concave edge, over the full case grid. The
// criteria are the issue's: stick/slide as Coulomb says, creep <= 1e-6 of the commanded speed, sliding speed
// within 2 % of the analytic value, penetration <= 1 % of the smallest built-in clearance.
#include "sim/calibration.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/loaded_task.h"
#include "sim/rollout.h"

namespace cmt {
namespace {

// The rollouts' scene (sim/rollout.h calibrated_scene()).
const CalibrationResult& result() {
  static const CalibrationResult r = calibrate_friction();
  return r;
}

std::string describe(const CalibrationCase& c) {
  return c.geometry + " " + c.motion + " " + controller_form_name(c.form) + " mu " + std::to_string(c.mu) +
         " alpha/" + c.reference + " " + std::to_string(c.ratio) + ": expected " + c.expected +
         ", observed " + c.observed + ", creep " + std::to_string(c.creep) + ", speed " +
         std::to_string(c.speed) + " (analytic " + std::to_string(c.analytic_speed) + "), penetration " +
         std::to_string(c.max_penetration) + ", loading creep " + std::to_string(c.loading_creep);
}

TEST(Calibration, CoversTheGrid) {
  const CalibrationResult& r = result();
  // 2 geometries x 3 mu x 8 ratios for damper and spring in 2 forms, springs in the position form, plus
  // the edge's threshold cases; the mu = 1 edge has no sum-cone threshold (its cone is a half-space).
  int face = 0, grid = 0;
  for (const CalibrationCase& c : r.cases) {
    face += c.geometry == "face";
    grid += c.reference == "phi";
  }
  EXPECT_EQ(face, 3 * 8 * 5);
  EXPECT_EQ(grid, 2 * 3 * 8 * 5);
  std::cout << "[ calibration ] " << r.cases.size() << " cases in " << r.seconds << " s; max creep "
            << r.max_creep << " (face " << r.max_face_creep << "), max speed error " << r.max_speed_error
            << " (face " << r.max_face_speed_error << ", edge " << r.max_edge_speed_error
            << "), max penetration " << r.max_penetration << " m, " << r.ambiguous << " ambiguous\n";
}

// The calibration's acceptance criteria, in the scene the rollouts use: every scored case meets every one.
TEST(Calibration, PassesInTheRolloutsScene) {
  for (const CalibrationCase& c : result().cases)
    if (c.expected != "ambiguous") {
      EXPECT_TRUE(c.passed) << describe(c);
    }
  EXPECT_TRUE(result().passed);
  EXPECT_LE(result().max_creep, kMaxCreep);
  EXPECT_LE(result().max_speed_error, kMaxSpeedError);
  EXPECT_LE(result().max_penetration, kMaxPenetration);
}

TEST(Calibration, EveryCaseSticksOrSlidesAsCoulombSays) {
  for (const CalibrationCase& c : result().cases) EXPECT_TRUE(c.agree) << describe(c);
  EXPECT_TRUE(result().agree);
}

TEST(Calibration, FaceMeetsEveryCriterion) {
  for (const CalibrationCase& c : result().cases) {
    if (c.geometry != "face") continue;
    EXPECT_LE(c.creep, kMaxCreep) << describe(c);
    EXPECT_LE(c.speed_error, kMaxSpeedError) << describe(c);
    EXPECT_LE(c.max_penetration, kMaxPenetration) << describe(c);
    if (c.form != ControllerForm::kPosition && c.expected == "slide") {
      EXPECT_GT(c.analytic_speed, 0) << describe(c);
    }
  }
}

TEST(Calibration, PenetrationStaysBelowOnePercentOfTheSmallestClearance) {
  for (const CalibrationCase& c : result().cases)
    EXPECT_LE(c.max_penetration, kMaxPenetration) << describe(c);
}

const CalibrationCase& find_case(const std::string& geometry, const std::string& motion, ControllerForm form,
                                 double mu, const std::string& reference, double ratio) {
  for (const CalibrationCase& c : result().cases)
    if (c.geometry == geometry && c.motion == motion && c.form == form && c.mu == mu &&
        c.reference == reference && c.ratio == ratio)
      return c;
  throw std::logic_error("no calibration case " + geometry + " " + motion + " " + reference);
}

// The concave edge (two faces at a right angle), impedance and admittance forms: every criterion in every
// scored case. In the stiff scene (stiff_scene(): d = 0.99 at every depth, 0.5 ms) this fails: each face's
// contact hopped off while sliding and the other face's friction wedged the robot into the edge (sliding up
// to 73 % off Coulomb, creep up to 3.5e-6; test StiffSceneFailsOnlyAtTheConcaveEdge). The soft surface layer
// of the rollouts' scene keeps both contacts active (docs/rollouts.md "Concave edges").
TEST(Calibration, ConcaveEdgeMeetsEveryCriterionInTheVelocityForms) {
  int scored = 0, sliding = 0;
  for (const CalibrationCase& c : result().cases) {
    if (c.geometry != "edge" || c.form == ControllerForm::kPosition || c.expected == "ambiguous") continue;
    ++scored;
    EXPECT_TRUE(c.agree) << describe(c);
    EXPECT_LE(c.creep, kMaxCreep) << describe(c);
    EXPECT_LE(c.speed_error, kMaxSpeedError) << describe(c);
    EXPECT_LE(c.max_penetration, kMaxPenetration) << describe(c);
    EXPECT_TRUE(c.passed) << describe(c);
    if (c.expected == "slide") {
      ++sliding;
      EXPECT_GT(c.analytic_speed, 0) << describe(c);  // the speed criterion was applied
    }
  }
  // Per mu: 8 grid angles + 2 below the kinetic threshold + 2 beyond the sum-cone threshold (none for
  // mu = 1, whose sum cone is a half-space) = 12, 12, 10; x 2 motions x 2 forms = 136, less the mu = 1
  // command at 1.5 phi = 1.178 rad, which lies between the kinetic threshold atan(sqrt 2) = 0.955 rad and the
  // half-space (ambiguous), in 4 motion/form pairs: 132 scored.
  EXPECT_EQ(scored, 132);
  // Sliding (alpha beyond the sum-cone threshold atan(sqrt 2 mu / sqrt(1 - mu^2))), per motion and form:
  // mu = .25 (threshold 0.350 rad, phi = 0.245): 1.05 and 1.1 of the threshold and 1.5 phi = 0.367 -> 3;
  // mu = .48 (threshold 0.659 rad, phi = 0.448): 1.05, 1.1 of it and 1.5 phi = 0.671 -> 3; mu = 1: none.
  // 6 x 2 motions x 2 forms = 24.
  EXPECT_EQ(sliding, 24);
}

// Hand-derived Coulomb speeds (damper of speed V = 1 in/s, mu = .48, phi = atan .48 = 0.447519 rad):
//   face, alpha = 1.5 phi = 0.671280 rad: V (sin alpha - mu cos alpha) = 0.621979 - 0.48 x 0.783027 =
//     0.246136 in/s;
//   edge, alpha = 1.1 x the sum-cone threshold atan(sqrt 2 mu / sqrt(1 - mu^2)) = 1.1 x 0.658554 = 0.724410
//     rad: V (sin alpha - sqrt 2 mu cos alpha) = 0.662694 - 0.678823 x 0.748891 = 0.154330 in/s;
//   edge, alpha = 0.95 x the kinetic threshold atan(sqrt 2 mu) = 0.566552 rad: tan alpha = 0.6361 <
//     sqrt 2 mu = 0.6788, so the two faces' kinetic friction exceeds the push along the edge: it sticks.
TEST(Calibration, DamperMatchesHandDerivedCoulombSpeeds) {
  for (const ControllerForm form : {ControllerForm::kImpedance, ControllerForm::kAdmittance}) {
    const CalibrationCase& face = find_case("face", "damper", form, 0.48, "phi", 1.5);
    EXPECT_NEAR(face.analytic_speed, 0.246136, 1e-6) << describe(face);
    EXPECT_NEAR(face.speed, 0.246136, kMaxSpeedError * 0.246136) << describe(face);
    const CalibrationCase& edge = find_case("edge", "damper", form, 0.48, "edge_cone", 1.1);
    EXPECT_EQ(edge.observed, "slide") << describe(edge);
    EXPECT_NEAR(edge.analytic_speed, 0.154330, 1e-6) << describe(edge);
    EXPECT_NEAR(edge.speed, 0.154330, kMaxSpeedError * 0.154330) << describe(edge);
    const CalibrationCase& stuck = find_case("edge", "damper", form, 0.48, "edge_kinetic", 0.95);
    EXPECT_EQ(stuck.observed, "stick") << describe(stuck);
    EXPECT_LE(std::abs(stuck.speed), kMaxCreep * kCalibrationSpeed) << describe(stuck);
  }
}

// The position form (springs through via points), face and edge: Coulomb's stick/slide from the travel
// along the tangent over the whole motion, and no creep at constant load, once the via plan is complete
// (sim/calibration.h). Scored cases per mu: the face's 8 grid angles; the edge's 8 + 2 + 2 (mu = 1: 8 + 2,
// less the ambiguous 1.5 phi): 20, 20, 17 = 57. Sliding: the face at 1.05-1.5 phi (4 per mu) and the edge
// beyond its sum-cone threshold (3 each for mu = .25 and .48, as in the velocity forms): 18.
TEST(Calibration, PositionFormSticksWithoutCreepAtConstantLoad) {
  int scored = 0, sliding = 0;
  for (const CalibrationCase& c : result().cases) {
    if (c.form != ControllerForm::kPosition || c.expected == "ambiguous") continue;
    ++scored;
    EXPECT_TRUE(c.agree) << describe(c);
    EXPECT_LE(c.creep, kMaxCreep) << describe(c);
    EXPECT_LE(c.max_penetration, kMaxPenetration) << describe(c);
    sliding += c.observed == "slide";
  }
  EXPECT_EQ(scored, 57);
  EXPECT_EQ(sliding, 18);
}

// The stiff scene (stiff_scene()) meets every criterion on a face but not in the concave edge: why the
// rollouts use the soft-surface-layer scene instead (docs/rollouts.md "Concave edges").
TEST(Calibration, StiffSceneFailsOnlyAtTheConcaveEdge) {
  const CalibrationResult r = calibrate_friction(
      {ControllerForm::kImpedance, ControllerForm::kAdmittance, ControllerForm::kPosition}, stiff_scene());
  EXPECT_TRUE(r.agree);
  EXPECT_FALSE(r.passed);
  EXPECT_LE(r.max_face_creep, kMaxCreep);
  EXPECT_LE(r.max_face_speed_error, kMaxSpeedError);
  EXPECT_GT(r.max_edge_speed_error, kMaxSpeedError);
  for (const CalibrationCase& c : r.cases)
    if (c.geometry == "face") {
      EXPECT_TRUE(c.passed) << describe(c);
    }
}

// The position form's slip in the concave edge while its via plan loads the contact (reported as
// `loading_creep`, up to 5.3e-4 of its via pace, not scored), and it is not a measurement artifact: it is
// measured along the edge (y), tangential to both faces. It is the slip a compliant contact must show under
// a growing load. Every via point raises the load by k_eff x step; the contact sinks a little deeper into
// both faces, and sinking into the floor is sliding along the wall (and vice versa). A sliding contact's
// (isotropic, elliptic-cone) friction points against its slip velocity, so while the wall slides by s along
// z it holds a push p along y only by slipping v_y as well: two faces, normal loads N each,
// p = 2 mu N v_y / sqrt(v_y^2 + s^2), i.e. v_y / s = r / sqrt(1 - r^2) with r = p / (2 mu N) =
// tan(alpha) / (sqrt 2 mu). Once the plan is complete and the load constant, nothing sinks and nothing
// slips: Coulomb's stick condition, a statement about a static load, is checked there (the calibration's
// creep criterion for this form, docs/rollouts.md "The position form in concave edges").
//
// kSlipRatioSlack: measured slip / sink is 1.21 x the two-face prediction above at mu = .25, alpha = .5 phi
// (0.45 vs 0.371 per via step, the same at every step); the prediction ignores that the cube's contacts
// are four per face at the corners of the contact patch. 1.5 bounds the excess without allowing a
// different mechanism (a slip unrelated to the sinking would not track it step by step).
inline constexpr double kSlipRatioSlack = 1.5;

TEST(Calibration, PositionFormEdgeLoadingSlipIsTheSlipOfTheSinkingContact) {
  const double mu = 0.25, alpha = 0.5 * std::atan(mu);
  SimOptions options;  // the rollouts' scene
  options.form = ControllerForm::kPosition;
  const double distance = kCalibrationSpeed / options.spring_rate;  // as in calibrate_friction
  // The calibration's floor and wall (sim/calibration.cc), via step a tenth of the spring's distance.
  const auto task = load_task_from_string(
      "name: edge\nunits: in\nfriction: 0.25\nuncertainty: {eps_s: 0, eps_p: 0, theta_v: 0, theta_f: 0, "
      "step: " +
          std::to_string(distance / 10) +
          "}\ncspace:\n  - box: {min: [-2, -4, -2], max: [4, 4, 0]}\n"
          "  - box: {min: [-4, -4, -2], max: [-2, 4, 4]}\nbounds: {min: [-4, -4, -2], max: [4, 4, 4]}\n"
          "start: {point: [1, 0, 0]}\ngoal: {point: [1, 0, 0]}\n",
      "edge.yaml");
  const auto scene = RolloutScene::build(task, options);
  RolloutRunner runner(scene);
  const Vec3 corner(-2, 0, 0);
  const Vec3 dir = std::cos(alpha) * Vec3(-1, 0, -1).normalized() + std::sin(alpha) * Vec3::UnitY();
  Motion m;
  m.name = "edge";
  m.kind = Motion::Kind::kSpring;
  m.target = corner + distance * dir;
  const double dt = scene->timestep(), via = scene->controller_params().via_time;
  const long per_via = std::lround(via / dt);
  std::vector<Vec3> at_via;  // position at every via-point time, task units
  Vec3 hold_start = Vec3::Zero(), hold_end = Vec3::Zero();
  const double hold_from = 2.0, hold_to = 2.5;  // the 10-point plan ends at 1.5 s: constant load
  long step = 0;
  runner.drive(corner, m, hold_to, [&](const StepState& st) {
    ++step;
    if (step % per_via == 0) at_via.push_back(st.position);
    if (step == std::lround(hold_from / dt)) hold_start = st.position;
    hold_end = st.position;
  });
  const double r = std::tan(alpha) / (std::sqrt(2.0) * mu);
  const double predicted = r / std::sqrt(1 - r * r);  // slip along the edge per unit of sinking
  // Via steps 2..6 (the first includes the initial loading from rest): the load grows, both faces sink,
  // and the robot slips along the edge by a fixed multiple of the sinking.
  ASSERT_GE(at_via.size(), 7u);
  for (std::size_t k = 2; k <= 6; ++k) {
    const Vec3 d = at_via[k] - at_via[k - 1];
    const double sink = -d.z();  // into the floor = along the wall; -d.x() is the same by symmetry
    EXPECT_GT(sink, 0) << k;
    EXPECT_NEAR(-d.x(), sink, 0.01 * sink) << k;
    EXPECT_GT(d.y(), 0) << k;
    EXPECT_GE(d.y() / sink, predicted) << k;
    EXPECT_LE(d.y() / sink, kSlipRatioSlack * predicted) << k;
  }
  // Constant load: no sinking, no slip (the creep criterion holds, relative to the via pace).
  const double pace = scene->controller_params().step / via;
  EXPECT_LE(std::abs(hold_end.y() - hold_start.y()) / (hold_to - hold_from), kMaxCreep * pace);
}

}  // namespace
}  // namespace cmt
