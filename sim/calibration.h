// Friction calibration (docs/rollouts.md "Calibration"): the simulated robot, through the same controllers
// and plant as the rollouts, against Coulomb's law on one face and in one concave edge (two faces at a right
// angle), for damper and spring commands at angles alpha from the inward normal, alpha / phi in
// kCalibrationRatios, mu in kCalibrationFrictions, phi = atan(mu).
//
// Expected behaviour (Coulomb, first-order robot, Buckley §3.2-3.3):
//   face: stick iff alpha <= phi; sliding speed V (sin alpha - mu cos alpha) for a damper of speed V, and
//         for a spring the tangential excess e = t - mu n (t, n: tangential and normal parts of x_c - x)
//         decays as e' = -lambda e.
//   edge (right-angle concave edge, command in the plane of the inward bisector and the edge direction,
//         normal share a = cos(alpha) / sqrt 2 into each face): sliding needs tan alpha > sqrt 2 mu (the
//         kinetic friction of both faces), and no static solution exists once tan alpha >
//         sqrt 2 mu / sqrt(1 - mu^2) (the Minkowski sum of the two face cones, which includes wedging; for
//         mu >= 1 the sum is a half-space and every command into the edge sticks). In between, sticking and
//         sliding are both Coulomb solutions (the generalized damper model, whose edge cone is the sum, says
//         stick): such cases are reported as "ambiguous" and not counted in the agreement. Sliding speed
//         V (sin alpha - sqrt 2 mu cos alpha).
// Beyond the grid, the edge also gets commands at 0.9 and 0.95 of the kinetic threshold and at 1.05 and 1.1
// of the sum-cone threshold, where the edge is tested hardest.
#pragma once

#include <string>
#include <vector>

#include "controllers/controller.h"
#include "sim/rollout.h"

namespace cmt {

inline constexpr double kCalibrationRatios[] = {0.5, 0.8, 0.9, 0.95, 1.05, 1.1, 1.2, 1.5};
inline constexpr double kCalibrationFrictions[] = {0.25, 0.48, 1.0};
// Criteria (the issue's): creep while sticking <= 1e-6 of the commanded speed; sliding speed within 2 % of
// the analytic value; penetration <= 1 % of the smallest clearance of the built-in tasks, which is
// peg_in_hole_real's .025 in per side (models/tasks/peg_in_hole_real.yaml) = 6.35e-4 m.
inline constexpr double kMaxCreep = 1e-6;
inline constexpr double kMaxSpeedError = 0.02;
inline constexpr double kSmallestBuiltinClearance = 0.025 * 0.0254;  // m
inline constexpr double kMaxPenetration = 0.01 * kSmallestBuiltinClearance;
// A case is observed sliding when its tangential speed exceeds this fraction of the commanded speed: far
// above any creep allowed (1e-6) and far below the slowest sliding of the grid (1.2 % at mu = .25, 1.05 phi).
inline constexpr double kSlideThreshold = 1e-3;
// Measuring windows, s. Velocity forms: creep (sticking) or speed (sliding) over kVelocityWindow after
// kVelocitySettle (10 servo time constants: the start transient has decayed to e^-10).
inline constexpr double kVelocitySettle = 0.1;
inline constexpr double kVelocityWindow = 0.2;
// Position form. Coulomb's stick condition is a statement about a static load, and while the via plan runs
// the load grows at every via point: a compliant contact sinks a little deeper each time, and in a concave
// edge sinking into one face is sliding along the other, which a sliding contact's friction allows only
// with a slip along the edge too (slip / sink = r / sqrt(1 - r^2), r = tan(alpha) / (sqrt 2 mu); test
// Calibration.PositionFormEdgeLoadingSlipIsTheSlipOfTheSinkingContact, docs/rollouts.md "The position form in
// concave edges"). So its creep is measured at constant load: over kPositionWindow once the plan is complete
// (its last via point has run for via_time) and kPositionSettleTimeConstants servo time constants 1 / g have
// passed (the load is then within e^-10 of its final value). Stick/slide is decided from the mean
// tangential speed over the whole motion (from rest at the start), so a slide that ends while the plan runs
// is still seen. The slip while the load grows is reported, not scored, as `loading_creep`: over
// kPositionLoadingWindow after kPositionLoadingStart (via points 4-7 of 10), relative to the via
// pace.
inline constexpr double kPositionSettleTimeConstants = 10;
inline constexpr double kPositionWindow = 0.5;
inline constexpr double kPositionLoadingStart = 0.5;
inline constexpr double kPositionLoadingWindow = 0.5;
// Commanded speed of the calibration, in/s (the scene is in inches): the damper speed, and the spring's
// initial speed lambda |x_c - x|. Penetration grows linearly with it (measured; reported per unit speed).
inline constexpr double kCalibrationSpeed = 1.0;

struct CalibrationCase {
  std::string geometry;  // "face" or "edge"
  std::string motion;    // "damper" or "spring"
  ControllerForm form = ControllerForm::kAdmittance;
  double mu = 0;
  double ratio = 0;          // alpha / phi (grid) or alpha / threshold (edge boundary cases)
  std::string reference;     // what `ratio` is relative to: "phi", "edge_kinetic", "edge_cone"
  double alpha = 0;          // radians from the inward normal
  std::string expected;      // "stick", "slide" or "ambiguous"
  std::string observed;      // "stick" or "slide"
  double command_speed = 0;  // in/s at the start of the measuring window
  double creep = 0;          // sticking: tangential speed / command speed (position form: at constant load)
  double loading_creep = 0;  // position form, sticking: the same while the via plan loads the contact
                             // (information, not a criterion)
  // Measured tangential speed, in/s: velocity forms over the measuring window; position form the mean over
  // the whole motion (what stick/slide is decided from).
  double speed = 0;
  double analytic_speed = 0;
  double speed_error = 0;      // |speed / analytic - 1| (sliding cases with an analytic value)
  double max_penetration = 0;  // m
  bool agree = true;           // stick/slide as expected (ambiguous cases: always)
  bool passed = true;          // agree and within the creep / speed / penetration criteria
};

struct CalibrationResult {
  std::vector<CalibrationCase> cases;
  bool agree = true;   // every non-ambiguous case sticks or slides as Coulomb says
  bool passed = true;  // every criterion met in every case
  double max_creep = 0;
  double max_speed_error = 0;       // over sliding cases with an analytic speed (impedance, admittance)
  double max_face_speed_error = 0;  // the same, face cases only
  double max_edge_speed_error = 0;  // edge cases only
  double max_loading_creep = 0;     // position form, while its via plan loads the contact (not scored)
  double max_face_creep = 0;
  double max_edge_creep = 0;
  double max_penetration = 0;  // m
  int ambiguous = 0;
  double seconds = 0;
};

// Runs every case (about 300; several seconds) in the given MuJoCo scene (default: the rollouts' scene,
// calibrated_scene(); stiff_scene() fails the concave edge). `forms` defaults to all three controller forms
// (the position form only for springs, and without a speed criterion: its speed is the pace of its via
// points).
CalibrationResult calibrate_friction(std::vector<ControllerForm> forms = {ControllerForm::kImpedance,
                                                                          ControllerForm::kAdmittance,
                                                                          ControllerForm::kPosition},
                                     const MjcfOptions& scene = SimOptions{}.scene);

}  // namespace cmt
