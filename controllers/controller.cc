#include "controllers/controller.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cmt {

const char* controller_form_name(ControllerForm form) {
  switch (form) {
    case ControllerForm::kImpedance:
      return "impedance";
    case ControllerForm::kAdmittance:
      return "admittance";
    case ControllerForm::kPosition:
      return "position";
  }
  return "?";
}

std::optional<ControllerForm> parse_controller_form(const std::string& text) {
  for (ControllerForm f :
       {ControllerForm::kImpedance, ControllerForm::kAdmittance, ControllerForm::kPosition})
    if (text == controller_form_name(f)) return f;
  return std::nullopt;
}

namespace {

Vec3 cap(const Vec3& v, double max_norm) {
  const double n = v.norm();
  return n > max_norm ? Vec3(v * (max_norm / n)) : v;
}

// Fraction of the force the reference speed imparts against the servo above which a sensed force means
// contact (velocity forms).
constexpr double kContactForceFraction = 0.01;

// Generalized damper, Buckley §3.2; impedance form (force law 3.9 through the servo) or admittance (3.23).
class Damper : public MotionController {
 public:
  Damper(const Vec3& direction, bool admittance, const ControllerParams& p)
      : velocity_(p.damper_speed * direction), admittance_(admittance), b_(p.damping()) {
    reference_speed_ = p.damper_speed;
    guard_force_ = kContactForceFraction * p.servo_damping * p.damper_speed;
  }
  ServoCommand update(const Sensed& s) override {
    ServoCommand c;
    c.drive = velocity_;                         // xdot_c
    if (admittance_) c.feedback = s.force / b_;  // + f_r / b (eq. 3.23)
    return c;
  }

 private:
  Vec3 velocity_;
  bool admittance_;
  double b_;
};

// Generalized spring, Buckley §3.3; impedance form (3.13 through the servo) or admittance (3.24).
class Spring : public MotionController {
 public:
  Spring(const Vec3& target, bool admittance, const ControllerParams& p, const Vec3& sensed_start)
      : target_(target),
        admittance_(admittance),
        b_(p.damping()),
        rate_(p.spring_rate),
        lead_(p.spring_rate * p.servo_time_constant),
        max_speed_(p.max_speed) {
    reference_speed_ = std::min(p.max_speed, p.spring_rate * (target - sensed_start).norm());
    guard_force_ = kContactForceFraction * p.servo_damping * reference_speed_;
  }
  ServoCommand update(const Sensed& s) override {
    ServoCommand c;
    c.drive = cap(rate_ * (target_ - s.position), max_speed_);  // x_c - xhat, time scaled by lambda
    c.feedback = -lead_ * s.velocity;             // servo lag compensation (pole at exactly -lambda)
    if (admittance_) c.feedback += s.force / b_;  // + f_r / b (eq. 3.24)
    return c;
  }

 private:
  Vec3 target_;
  bool admittance_;
  double b_, rate_, lead_, max_speed_;
};

// Generalized spring through a position controller with via points: Buckley eq. 3.25 and App. C (SMOVE).
class ViaPointSpring : public MotionController {
 public:
  ViaPointSpring(const Vec3& target, const ControllerParams& p, const Vec3& sensed_start,
                 std::function<Vec3()> positioning_error)
      : goal_(target),
        p_(p),
        k_(p.stiffness()),
        lead_(p.position_gain * p.servo_time_constant),
        positioning_error_(std::move(positioning_error)) {
    const double k_eff = p.effective_stiffness();
    guard_force_ = kGuardForceSteps * k_eff * p.step;
    stick_force_ = kStickForceSteps * k_eff * p.step;
    plan(sensed_start);
    reference_speed_ = p.step / p.via_time;  // the pace of the via points
  }

  ServoCommand update(const Sensed& s) override {
    // End of a via step (AML: MOVE has completed): read the force, apply the termination and replanning rules
    // of SMOVE, then issue the next via point.
    if (s.time >= next_via_time_) {
      next_via_time_ += p_.via_time;
      const Vec3 f = s.force;
      const bool was_contact = force_old_.norm() > guard_force_;
      const bool opposing = f.dot(fdir_) >= stick_force_ && force_old_.dot(fdir_) >= stick_force_;
      if (opposing && !stopped_) stopped_ = true;  // "two consecutive forces which oppose motion"
      if (!plan_complete() && was_contact && f.norm() <= guard_force_) {
        plan(s.position);  // contact -> free: replan from the sensed position
        ++replans_;
      }
      force_old_ = f;
      if (!plan_complete()) {
        ++i_;
        via_ = start_ + static_cast<double>(i_) * increment_;
        if (i_ == segments_) via_ = goal_;
        error_ = positioning_error_ ? positioning_error_() : Vec3::Zero();
      }
    }
    const Vec3 target = via_ + s.force / k_ + error_;  // eq. 3.25: x = x_c + f_r / k
    ServoCommand c;
    c.drive = cap(p_.position_gain * (target - s.position), p_.max_speed);
    c.feedback = -lead_ * s.velocity;
    return c;
  }

  bool stopped_by_force() const override { return stopped_; }
  bool plan_complete() const override { return i_ >= segments_; }
  int replans() const override { return replans_; }

 private:
  void plan(const Vec3& from) {
    start_ = from;
    via_ = from;
    const double length = (goal_ - from).norm();
    segments_ = std::max(1, static_cast<int>(std::ceil(length / p_.step)));
    increment_ = (goal_ - from) / segments_;
    fdir_ = length > 0 ? Vec3(-(goal_ - from) / length) : Vec3::Zero();
    i_ = 0;
  }

  Vec3 goal_;
  ControllerParams p_;
  double k_, lead_, stick_force_ = 0;
  std::function<Vec3()> positioning_error_;
  Vec3 start_ = Vec3::Zero(), via_ = Vec3::Zero(), increment_ = Vec3::Zero(), fdir_ = Vec3::Zero();
  Vec3 error_ = Vec3::Zero(), force_old_ = Vec3::Zero();
  int segments_ = 1, i_ = 0, replans_ = 0;
  double next_via_time_ = 0;
  bool stopped_ = false;
};

}  // namespace

std::unique_ptr<MotionController> make_controller(const Motion& motion, ControllerForm form,
                                                  const ControllerParams& params, const Vec3& sensed_start,
                                                  std::function<Vec3()> positioning_error) {
  if (motion.kind == Motion::Kind::kDamper) {
    if (form == ControllerForm::kPosition)
      throw std::invalid_argument(
          "motion '" + motion.name +
          "': the position-controller form implements springs only (Buckley eq. 3.25)");
    return std::make_unique<Damper>(motion.target, form == ControllerForm::kAdmittance, params);
  }
  if (form == ControllerForm::kPosition)
    return std::make_unique<ViaPointSpring>(motion.target, params, sensed_start,
                                            std::move(positioning_error));
  return std::make_unique<Spring>(motion.target, form == ControllerForm::kAdmittance, params, sensed_start);
}

}  // namespace cmt
