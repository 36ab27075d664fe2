// Generalized damper and spring controllers, implemented the way Buckley §3.4 proposes for a real robot
// (L950-964), on a robot whose only actuator is a velocity servo. A controller maps sensed state (sensed
// position, velocity and contact force) to a velocity command; it knows nothing of MuJoCo.
//
// The plant (sim/rollout.h): a mass m with a velocity servo of gain b_s (force b_s (v_cmd - v)), so the servo
// follows a velocity command with time constant tau = m / b_s. The command sent is
//     v_cmd = R_v(drive) + feedback,
// where R_v is the velocity-direction error (error_model.h), applied to what the motion commands (drive) and
// not to the controller's feedback terms: in contact the force the robot imparts then errs by the velocity
// error, as Buckley's analysis assumes (§3.3.3).
//
// Forms (ControllerForm):
//   impedance:  drive = xdot_c (damper) or lambda (x_c - xhat) (spring); no force feedback. The servo's own
//               damping then is the generalized damper f_r = b_s (xdot - xdot_c) as a force law (eq. 3.9).
//   admittance: Buckley eq. 3.23 / 3.24: the desired actual velocity xdot_c + f_r/b (damper) or
//               x_c - xhat + f_r/b (spring), f_r the sensed reaction force. With the servo, contact obeys
//               f_r = b_eff (xdot - xdot_c), b_eff = b b_s / (b + b_s); the loop through the (one step late)
//               sensed force converges only if b_s < b (ratio kAdmittanceServoRatio).
//   position:   Buckley eq. 3.25 / 6.1 and App. C (AML SMOVE): via points every `step` along the line from
//               the sensed start to the commanded position, each sent as the target x_c + f_r/k of a position
//               servo (drive = g (target - xhat)); the plan is rebuilt from the sensed position on a
//               contact-to-free transition, and the motion stops when two consecutive via steps sense a force
//               opposing the motion above 3 k step (AML STICK_FORCE = 3 MOVEINC x NOM_STIFFNESS).
// Both spring forms add -lambda tau xdot (-g tau xdot) to the feedback: the servo lag would otherwise make
// the closed loop's slow pole lambda (1 + lambda tau); with the term it is exactly lambda (docs/rollouts.md).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "models/task.h"

namespace cmt {

enum class ControllerForm { kImpedance, kAdmittance, kPosition };
const char* controller_form_name(ControllerForm form);
std::optional<ControllerForm> parse_controller_form(const std::string& text);

// Admittance form: servo gain b_s = this x the controller's b. The sensed-force loop multiplies an error by
// -b_s/b per control step, so it must be < 1; 1/2 settles to 1e-6 in 20 steps (docs/rollouts.md, measured:
// 1 oscillates and creeps at 5e-6 of the commanded speed).
inline constexpr double kAdmittanceServoRatio = 0.5;
// Position form: servo stiffness K_s = g b_s = this x the spring stiffness k (same loop argument per step).
inline constexpr double kPositionServoRatio = 0.5;
// AML App. C constants as multiples of the via step at the effective stiffness: GUARD_FORCE (contact) =
// 0.1 MOVEINC x k, STICK_FORCE = 3 MOVEINC x k.
inline constexpr double kGuardForceSteps = 0.1;
inline constexpr double kStickForceSteps = 3.0;

struct ControllerParams {
  double servo_damping = 1;        // b_s, N s per task unit (the robot's velocity servo gain)
  double servo_time_constant = 0;  // tau = m / b_s, s
  double damper_speed = 1;         // |xdot_c|, task units / s (Buckley §3.2: unit commanded velocities)
  double spring_rate = 1;  // lambda = k / b, 1/s: free-space spring velocity lambda (x_c - x) (eq. 3.15)
  // Largest speed a spring (or the position servo) commands, task units / s: a velocity servo has a top
  // speed. Capping |drive| keeps its direction, so trajectories keep their shape (only their timing
  // changes) and stick/slide is unaffected (it depends on the direction alone, Buckley §3.1.1); it bounds
  // impact speeds, hence penetration (docs/rollouts.md).
  double max_speed = 1e300;
  // Position form.
  double step = 0.2;          // via-point spacing, task units (uncertainty.step)
  double position_gain = 20;  // g, 1/s
  double via_time = 0.15;     // s per via point (AML MOVE runs to completion)

  double damping() const { return servo_damping / kAdmittanceServoRatio; }                  // b
  double stiffness() const { return position_gain * servo_damping / kPositionServoRatio; }  // k
  // Stiffness of the position form about a via point when stuck: k K_s / (k + K_s).
  double effective_stiffness() const {
    const double ks = position_gain * servo_damping;
    return stiffness() * ks / (stiffness() + ks);
  }
};

struct Sensed {
  double time = 0;               // s since the motion started
  Vec3 position = Vec3::Zero();  // sensed position: true + sensing offset, task units
  Vec3 velocity = Vec3::Zero();  // sensed velocity, task units / s
  Vec3 force = Vec3::Zero();     // sensed reaction force on the robot (true, turned by theta_f error), N
};

struct ServoCommand {
  Vec3 drive = Vec3::Zero();     // what the motion commands; the velocity error turns it
  Vec3 feedback = Vec3::Zero();  // the controller's feedback terms
};

class MotionController {
 public:
  virtual ~MotionController() = default;
  virtual ServoCommand update(const Sensed& sensed) = 0;
  // The command speed at the start of the motion, task units / s: the scale of the sticking monitor.
  double reference_speed() const { return reference_speed_; }
  // A force scale for "in contact" decisions, N: AML GUARD_FORCE for the position form, 1% of the force the
  // reference speed imparts against the servo otherwise.
  double guard_force() const { return guard_force_; }
  // Set when the controller's own rule ended the motion (position form: AML force rule).
  virtual bool stopped_by_force() const { return false; }
  // Position form: every via point has been issued (after that it holds the commanded position).
  virtual bool plan_complete() const { return true; }
  virtual int replans() const { return 0; }

 protected:
  double reference_speed_ = 0;
  double guard_force_ = 0;
};

// `positioning_error` is called once per via point (position form only) and returns the error with which the
// position servo reaches it (within eps_p).
std::unique_ptr<MotionController> make_controller(const Motion& motion, ControllerForm form,
                                                  const ControllerParams& params, const Vec3& sensed_start,
                                                  std::function<Vec3()> positioning_error = {});

}  // namespace cmt
