// Physics calibration (docs/rollouts.md "Calibration"): the simulated robot against Coulomb's law, through
// the rollouts' own controllers and plant, on a face and in a concave edge, over the full case grid. The
// criteria are the issue's: stick/slide as Coulomb says, creep <= 1e-6 of the commanded speed, sliding speed
// within 2 % of the analytic value, penetration <= 1 % of the smallest built-in clearance.
#include "sim/calibration.h"

#include <gtest/gtest.h>

#include <iostream>

namespace cmt {
namespace {

const CalibrationResult& result() {
  static const CalibrationResult r = calibrate_friction();
  return r;
}

std::string describe(const CalibrationCase& c) {
  return c.geometry + " " + c.motion + " " + controller_form_name(c.form) + " mu " + std::to_string(c.mu) +
         " alpha/" + c.reference + " " + std::to_string(c.ratio) + ": expected " + c.expected +
         ", observed " + c.observed + ", creep " + std::to_string(c.creep) + ", speed " +
         std::to_string(c.speed) + " (analytic " + std::to_string(c.analytic_speed) + "), penetration " +
         std::to_string(c.max_penetration);
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

// Not asserted here: the concave-edge speed and creep criteria. MuJoCo 2.2 does not meet them
// (docs/rollouts.md "Concave edges: a MuJoCo limitation": edge sliding runs up to 73 % off Coulomb, creep up
// to 3.5e-6 of the speed; no contact setting fixes it). `cmt calibrate-friction` checks every criterion and
// exits 1 while they fail; the open rollout issue tracks it. Stick/slide agreement at the edge is asserted
// above.

}  // namespace
}  // namespace cmt
