#include "experiments/validation/verifier_model.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "models/input_error.h"
#include "models/task_ranges.h"
#include "sim/rollout.h"

namespace cmt {

double sensed_force_extra_angle(double theta_f, double servo_ratio) {
  return std::asin(2 * servo_ratio / (1 + servo_ratio) * std::sin(theta_f / 2));
}

double rollout_contact_lift(const LoadedTask& task) {
  const SimOptions sim;
  const MjcfOptions& scene = sim.scene;
  double mu_max = 0;
  for (const Face& f : task.cspace.faces()) mu_max = std::max(mu_max, f.friction);
  const double speed = std::max(sim.damper_speed_per_scale, sim.max_speed_per_scale) * task.cspace.scale();
  return scene.robot_mass / scene.damping * mu_max * speed;
}

double rollout_servo_coast(const LoadedTask& task) {
  const SimOptions sim;
  const double speed = std::max(sim.damper_speed_per_scale, sim.max_speed_per_scale) * task.cspace.scale();
  return sim.scene.robot_mass / sim.scene.damping * speed;
}

double rollout_spring_lag() {
  const SimOptions sim;
  return sim.spring_rate * sim.scene.robot_mass / sim.scene.damping;
}

VerifyOptions rollout_verify_options(const LoadedTask& task) {
  return {SpringModel::kVelocity, kStopRelativeSpeed, rollout_contact_lift(task), rollout_servo_coast(task),
          rollout_spring_lag()};
}

VerifierModel make_verifier_model(std::shared_ptr<const LoadedTask> task, ControllerForm form) {
  VerifierModel m;
  m.task = task;
  m.contact_lift = rollout_contact_lift(*task);
  m.servo_coast = rollout_servo_coast(*task);
  m.spring_lag = rollout_spring_lag();
  m.form = form;
  m.task_theta_v = task->task.uncertainty.theta_v;
  m.theta_f = task->task.uncertainty.theta_f;
  m.theta_v = m.task_theta_v;
  switch (form) {
    case ControllerForm::kImpedance:
      m.reason = "impedance form: no sensed force enters the command, so theta_v bounds the velocity error";
      return m;
    case ControllerForm::kPosition:
      m.spring_model = SpringModel::kViaPoint;
      m.reason =
          "position form: no bound derived (its sensed-force term sits inside the turned, speed-capped "
          "drive); the task's theta_v is used, so the prediction need not cover this form";
      return m;
    case ControllerForm::kAdmittance:
      break;
  }
  m.extra_angle = sensed_force_extra_angle(m.theta_f);
  if (m.extra_angle == 0) {
    m.reason =
        "admittance form with theta_f = 0: the sensed force is exact, theta_v bounds the velocity error";
    return m;
  }
  m.theta_v = m.task_theta_v + m.extra_angle;
  std::ostringstream why;
  why.precision(6);
  why << "admittance form: the sensed force (direction error <= theta_f = " << m.theta_f
      << ") fed back through 1/b turns the velocity in contact by up to asin(2 rho/(1+rho) sin(theta_f/2)) = "
      << m.extra_angle << " more (rho = b_s/b = " << kAdmittanceServoRatio
      << "; experiments/validation/verifier_model.h), so the verifier uses theta_v + that = " << m.theta_v;
  m.reason = why.str();

  if (m.theta_v >= kMaxThetaV)
    throw InputError(
        task->task.source_file, "uncertainty.theta_v",
        "the admittance form needs the verifier to use theta_v + " + std::to_string(m.extra_angle) +
            " (theta_f error fed back) = " + std::to_string(m.theta_v) + ", which the task format refuses: " +
            theta_v_range_reason(m.theta_v) + "; use --controller impedance");
  // The C-space does not depend on the uncertainty: the copy keeps it as built.
  auto widened = std::make_shared<LoadedTask>(*task);
  widened->task.uncertainty.theta_v = m.theta_v;
  m.task = std::move(widened);
  return m;
}

nlohmann::json verifier_model_json(const VerifierModel& m) {
  return {{"controller", controller_form_name(m.form)},
          {"task_theta_v", m.task_theta_v},
          {"theta_f", m.theta_f},
          {"extra_angle", m.extra_angle},
          {"theta_v", m.theta_v},
          {"spring_model", spring_model_name(m.spring_model)},
          {"stop_relative_speed", m.stop_relative_speed},
          {"contact_lift", m.contact_lift},
          {"servo_coast", m.servo_coast},
          {"spring_lag", m.spring_lag},
          {"reason", m.reason}};
}

}  // namespace cmt
