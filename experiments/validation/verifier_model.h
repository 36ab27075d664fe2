// Which velocity-direction bound the verifier must use so that its model covers the controller form the
// rollouts run (docs/validation.md "Controller forms and the verifier's theta_v").
//
// The verifier assumes that in contact the robot obeys a generalized damper f = b (xdot - v) whose command
// v lies within theta_v of the commanded one (for a spring: of x_c - x). The impedance form is exactly that:
// its drive is turned by the sampled velocity error (<= theta_v) and nothing else enters the servo. The
// admittance form (eq. 3.23 / 3.24) adds the SENSED contact force / b, and the sensed force is the true one
// turned by a rotation R of angle <= theta_f. Derivation of the extra angle (quasi-static, servo at rest):
//
//   servo:          f = b_s (xdot - v_cmd)                   (m xddot ~ 0; f = contact force on the robot)
//   command:        v_cmd = v_d [- lambda tau xdot] + R f / b
//                   (v_d = the drive turned by the velocity error, within theta_v of the command; the
//                   bracket is the spring's servo-lag compensation)
//   with rho = b_s / b (kAdmittanceServoRatio) and g = f / b_s this is (1 + rho) g = c xdot - v_eff with
//                   v_eff = v_d + rho (R - I) g,  c = 1 (damper) or 1 + lambda tau (spring),
//   i.e. f = b_s/(1+rho) (c xdot - v_eff): a generalized damper/spring with SCALAR damping whose command is
//   v_eff. Its error against v_d is |rho (R - I) g| <= 2 sin(theta_f / 2) |f| / b.
//   Contacts are passive (f . xdot <= 0: normal forces do no work on a sliding body, friction opposes it),
//   so (c xdot - v_eff) . c xdot <= 0, i.e. c xdot lies in the ball with diameter [0, v_eff], hence
//   |c xdot - v_eff| <= |v_eff| and |f| / b = rho |g| <= rho / (1 + rho) |v_eff|.
//   So |v_eff - v_d| <= s |v_eff| with s = 2 rho / (1 + rho) sin(theta_f / 2), and the angle between v_eff
//   and v_d is at most asin(s) (a vector within s|w| of w makes an angle <= asin s with it, s < 1).
//   Extra angle: beta = asin(2 rho / (1 + rho) sin(theta_f / 2)) <= rho / (1 + rho) theta_f (= theta_f / 3
//   at rho = 1/2); by the triangle inequality on the sphere v_eff lies within theta_v + beta of the command.
//   Tightness: stuck (xdot = 0) with the force error's axis perpendicular to f, the imparted force turns by
//   exactly atan(rho sin theta_f / (1 + rho cos theta_f)) (.09966 vs beta = .09979 at theta_f = .3).
//   The speed |v_eff| also varies (by a factor within 1 +- s); stick/slide and the paths depend on the
//   direction only (a positive factor re-times a motion), and in free space f = 0 so v_eff = v_d exactly.
//
// What is NOT proved: the servo transient (tau = 10 ms) and the one-step-late sensed force are neglected
// (impacts are outside the first-order model for every form); MuJoCo's soft contacts are passive only up to
// their ~1e-7 m penetration recovery. The position form (eq. 3.25) puts the force term inside the turned and
// speed-capped drive, so even theta_f = 0 does not give theta_v; no bound is derived for it here.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "controllers/controller.h"
#include "controllers/termination.h"
#include "models/loaded_task.h"
#include "verifier/spring_projection.h"
#include "verifier/verify.h"

namespace cmt {

// beta above: the extra velocity-direction angle of a velocity form that feeds back a sensed force with
// direction error <= theta_f through gain ratio rho = b_s / b.
double sensed_force_extra_angle(double theta_f, double servo_ratio = kAdmittanceServoRatio);

// The contact lift of the rollouts' scene for a task (VerifyOptions::contact_lift, docs/verifier.md "Contact
// lift"): MuJoCo's convex contact gives slip a separating normal velocity of up to mu x the slip speed
// (docs/mujoco-scene.md "Sliding hops"); once the contact lets go, the first-order servo m xddot = −b (xdot −
// v_c) takes the normal velocity w0 back toward the command's normal component v_n <= 0 (a command with v_n >
// 0 leaves the face anyway: a flight) with time constant m / b, so the robot rises at most (m / b) w0 <= (m /
// b) mu_max V, V the fastest commanded speed (damper speed or spring top speed, SimOptions, a fraction of the
// scene scale per second) and mu_max the largest friction coefficient of the task's faces. Impedance form;
// the admittance form's force feedback adds to the rebound (its measured hops stay below the bound, the docs
// say by how much).
double rollout_contact_lift(const LoadedTask& task);

// The servo coast of the rollouts' scene for a task (VerifyOptions::servo_coast, docs/verifier.md "Servo
// coast"): free of contact the servo m xddot = b (v_c - xdot) relaxes the velocity toward the command with
// time constant tau = m / b, so where the first-order model changes a damper's velocity at once (an impact,
// leaving a face) the robot keeps its old one for about tau and moves on up to tau |xdot| <= tau V, V the
// larger of the damper speed and the spring's top speed (SimOptions, fractions of the scene scale per
// second).
double rollout_servo_coast(const LoadedTask& task);

// lambda tau of the rollouts' springs (VerifyOptions::spring_lag): their rate (SimOptions::spring_rate) times
// the servo's time constant m / b.
double rollout_spring_lag();

// The options that model the rollouts' impedance-form scene: velocity springs, the rollouts' stop rule,
// contact lift and servo coast of the scene.
VerifyOptions rollout_verify_options(const LoadedTask& task);

// What the verifier runs on for a controller form.
struct VerifierModel {
  std::shared_ptr<const LoadedTask> task;  // the task itself, or a copy with uncertainty.theta_v widened
  ControllerForm form = ControllerForm::kImpedance;
  double task_theta_v = 0;  // uncertainty.theta_v of the task file (what the rollouts sample)
  double theta_f = 0;       // uncertainty.theta_f of the task file
  double extra_angle = 0;   // beta (0 unless the form is admittance)
  double theta_v = 0;       // what the verifier used: task_theta_v + extra_angle
  // The spring trajectory model that covers the form: the velocity forms keep the sensing offset fixed during
  // a motion (SpringModel::kVelocity, proved sound for them); the position form replans from a fresh sensed
  // position at every breakaway, Buckley's via-point model (kViaPoint).
  SpringModel spring_model = SpringModel::kVelocity;
  // The rollouts' sticking rule also fires on slides slower than this fraction of the reference speed
  // (controllers/termination.h); the verifier's termination sets take such slow slides in (VerifyOptions).
  double stop_relative_speed = kStopRelativeSpeed;
  // A robot sliding into a concave edge may meet the other face this far from it (rollout_contact_lift).
  double contact_lift = 0;
  // How far the servo's lag may carry a damper on at an impact or past a rim (rollout_servo_coast).
  double servo_coast = 0;
  // A spring's coast is also at most this times its distance to the target (rollout_spring_lag).
  double spring_lag = 0;
  std::string reason;  // in words, for the JSON

  VerifyOptions verify_options() const {
    return {spring_model, stop_relative_speed, contact_lift, servo_coast, spring_lag};
  }
};

// For the admittance form with theta_f > 0, `task` copied with uncertainty.theta_v = theta_v + beta; throws
// InputError(file, "uncertainty.theta_v", reason) when the widened angle leaves the task format's range
// (< pi/2, kMaxThetaV in models/task_ranges.h).
VerifierModel make_verifier_model(std::shared_ptr<const LoadedTask> task, ControllerForm form);

// {controller, task_theta_v, theta_f, extra_angle, theta_v, spring_model, stop_relative_speed, contact_lift,
// servo_coast, spring_lag, reason}.
nlohmann::json verifier_model_json(const VerifierModel& model);

}  // namespace cmt
