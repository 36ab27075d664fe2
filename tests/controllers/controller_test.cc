// Controllers: each form computes what Buckley's equations say from the sensed state (§3.4: 3.23, 3.24,
// 3.25), and the position form follows AML SMOVE (App. C): via points every step, replanning on a
// contact-to-free transition, stopping on two consecutive forces opposing the motion.
#include "controllers/controller.h"

#include <gtest/gtest.h>

namespace cmt {
namespace {

ControllerParams params() {
  ControllerParams p;
  p.servo_damping = 2.0;  // N per unit/s
  p.servo_time_constant = 0.01;
  p.damper_speed = 3.0;
  p.spring_rate = 4.0;
  p.max_speed = 10.0;
  p.step = 0.5;
  p.position_gain = 20;
  p.via_time = 0.15;
  return p;
}

Motion damper(const Vec3& direction) { return {"v", Motion::Kind::kDamper, direction.normalized(), {}}; }
Motion spring(const Vec3& target) { return {"p", Motion::Kind::kSpring, target, {}}; }

Sensed sensed(double t, const Vec3& x, const Vec3& v = Vec3::Zero(), const Vec3& f = Vec3::Zero()) {
  Sensed s;
  s.time = t;
  s.position = x;
  s.velocity = v;
  s.force = f;
  return s;
}

TEST(Controller, DamperImpedanceCommandsTheVelocityAlone) {
  const ControllerParams p = params();
  auto c = make_controller(damper(Vec3(0, 0, -1)), ControllerForm::kImpedance, p, Vec3::Zero());
  const ServoCommand cmd = c->update(sensed(0.3, Vec3(1, 2, 3), Vec3(0, 0, -1), Vec3(0, 0, 5)));
  EXPECT_EQ(cmd.drive, Vec3(0, 0, -3));
  EXPECT_EQ(cmd.feedback, Vec3::Zero());
  EXPECT_EQ(c->reference_speed(), 3);
}

TEST(Controller, DamperAdmittanceAddsSensedForceOverB) {
  // Eq. 3.23: xdot = xdot_c + f_r / b, b = b_s / kAdmittanceServoRatio.
  const ControllerParams p = params();
  auto c = make_controller(damper(Vec3(1, 0, -1)), ControllerForm::kAdmittance, p, Vec3::Zero());
  const Vec3 f(0, 0, 8);
  const ServoCommand cmd = c->update(sensed(0, Vec3::Zero(), Vec3::Zero(), f));
  EXPECT_TRUE(cmd.drive.isApprox(3 * Vec3(1, 0, -1).normalized()));
  EXPECT_TRUE(cmd.feedback.isApprox(f * kAdmittanceServoRatio / p.servo_damping));
  // In contact at rest the loop settles where the servo's force b_s (v_cmd - 0) balances the reaction:
  // f = -b_s (xdot_c + f / b), i.e. f = -b_eff xdot_c with b_eff = b b_s / (b + b_s).
  const double b = p.damping(), bs = p.servo_damping;
  Vec3 force = Vec3::Zero();
  for (int i = 0; i < 60; ++i) {
    const ServoCommand k = c->update(sensed(0, Vec3::Zero(), Vec3::Zero(), force));
    force = -bs * (k.drive + k.feedback);  // a rigid wall along every direction: xdot = 0
  }
  EXPECT_TRUE(force.isApprox(-(b * bs / (b + bs)) * 3 * Vec3(1, 0, -1).normalized(), 1e-9));
}

TEST(Controller, SpringPullsTowardTheCommandedPositionFromTheSensedOne) {
  const ControllerParams p = params();
  const Vec3 target(1, 0, -1);
  auto imp = make_controller(spring(target), ControllerForm::kImpedance, p, Vec3::Zero());
  auto adm = make_controller(spring(target), ControllerForm::kAdmittance, p, Vec3::Zero());
  const Vec3 x(0.5, 0.2, -0.5), v(0.1, 0, 0), f(0, 0, 2);
  const ServoCommand a = imp->update(sensed(0, x, v, f));
  EXPECT_TRUE(a.drive.isApprox(p.spring_rate * (target - x)));  // eq. 3.15 / 3.24, time scaled by lambda
  EXPECT_TRUE(a.feedback.isApprox(-p.spring_rate * p.servo_time_constant * v));
  const ServoCommand b = adm->update(sensed(0, x, v, f));
  EXPECT_TRUE(b.feedback.isApprox(-p.spring_rate * p.servo_time_constant * v + f / p.damping()));
  EXPECT_NEAR(imp->reference_speed(), p.spring_rate * target.norm(), 1e-12);
  // Far away the drive is capped at the servo's top speed, direction kept.
  const ServoCommand far = imp->update(sensed(0, Vec3(-100, 0, 0)));
  EXPECT_NEAR(far.drive.norm(), p.max_speed, 1e-12);
  EXPECT_TRUE(far.drive.normalized().isApprox((target - Vec3(-100, 0, 0)).normalized()));
}

TEST(Controller, SpringLagCompensationPutsTheSlowPoleAtLambda) {
  // Free space, 1-D: servo m xddot = b_s (v_cmd - xdot) with tau = m / b_s. Integrate finely and compare
  // with the first-order model x_c - x(t) = (x_c - x0) e^(-lambda t) once the fast mode has died.
  ControllerParams p = params();
  p.max_speed = 1e300;
  const Vec3 target(1, 0, 0);
  auto c = make_controller(spring(target), ControllerForm::kImpedance, p, Vec3::Zero());
  double x = 0, v = 0;
  const double dt = 1e-5, tau = p.servo_time_constant;
  for (double t = 0; t < 0.5; t += dt) {
    const ServoCommand k = c->update(sensed(t, Vec3(x, 0, 0), Vec3(v, 0, 0)));
    const double v_cmd = k.drive.x() + k.feedback.x();
    v += dt * (v_cmd - v) / tau;
    x += dt * v;
  }
  // Two poles, -lambda and -1/tau: x_c - x = A e^(-lambda t) + B e^(-t/tau); at 0.5 s e^(-50) is gone.
  const double a = 1 / (1 - p.spring_rate * tau);  // amplitude of the slow mode for a start at rest
  EXPECT_NEAR(1 - x, a * std::exp(-p.spring_rate * 0.5), 1e-4 * std::exp(-p.spring_rate * 0.5));
}

TEST(Controller, PositionFormIssuesViaPointsEveryStep) {
  const ControllerParams p = params();
  const Vec3 start(0, 0, 0), goal(0, 2.2, 0);  // 5 via points of 0.44 <= step 0.5
  auto c = make_controller(spring(goal), ControllerForm::kPosition, p, start);
  EXPECT_FALSE(c->plan_complete());
  // First via point right away: the drive pulls toward start + (goal - start) / 5.
  ServoCommand k = c->update(sensed(0, start));
  EXPECT_TRUE(k.drive.isApprox(p.position_gain * Vec3(0, 0.44, 0)));
  // Still the first via point until via_time has passed.
  k = c->update(sensed(0.1, Vec3(0, 0.4, 0)));
  EXPECT_TRUE(k.drive.isApprox(p.position_gain * Vec3(0, 0.04, 0)));
  for (int i = 1; i < 5; ++i) k = c->update(sensed(i * p.via_time, Vec3(0, 0.44 * i, 0)));
  EXPECT_TRUE(c->plan_complete());
  EXPECT_TRUE(k.drive.isApprox(p.position_gain * Vec3(0, 0.44, 0)));
  // The sensed force shifts the target by f / k (eq. 3.25).
  const Vec3 f(0, 0, 3);
  k = c->update(sensed(10, goal, Vec3::Zero(), f));
  EXPECT_TRUE(k.drive.isApprox(p.position_gain * f / p.stiffness()));
}

TEST(Controller, PositionFormReplansOnContactToFree) {
  const ControllerParams p = params();
  const double guard = kGuardForceSteps * p.effective_stiffness() * p.step;
  auto c = make_controller(spring(Vec3(0, 5, 0)), ControllerForm::kPosition, p, Vec3::Zero());
  c->update(sensed(0, Vec3::Zero(), Vec3::Zero(), Vec3(0, 0, 10 * guard)));  // in contact
  c->update(sensed(p.via_time, Vec3(0, 0.5, 0), Vec3::Zero(), Vec3(0, 0, 10 * guard)));
  EXPECT_EQ(c->replans(), 0);
  // Free now: replan from the sensed position (1, 1, 1); the next via point is 1/ceil(|P - S| / step) of the
  // way from there.
  const Vec3 s(1, 1, 1);
  const ServoCommand k = c->update(sensed(2 * p.via_time, s));
  EXPECT_EQ(c->replans(), 1);
  const Vec3 d = Vec3(0, 5, 0) - s;
  const int segments = static_cast<int>(std::ceil(d.norm() / p.step));
  EXPECT_TRUE(k.drive.isApprox(p.position_gain * d / segments));
}

TEST(Controller, PositionFormStopsOnTwoConsecutiveOpposingForces) {
  const ControllerParams p = params();
  const double stick = kStickForceSteps * p.effective_stiffness() * p.step;
  auto c = make_controller(spring(Vec3(0, 5, 0)), ControllerForm::kPosition, p, Vec3::Zero());
  const Vec3 opposing(0, -1.01 * stick, 0);  // against the motion direction +y
  c->update(sensed(0, Vec3::Zero(), Vec3::Zero(), opposing));
  EXPECT_FALSE(c->stopped_by_force());  // one reading is not enough
  c->update(sensed(0.5 * p.via_time, Vec3::Zero(), Vec3::Zero(), opposing));
  EXPECT_FALSE(c->stopped_by_force());  // read once per via step only
  c->update(sensed(p.via_time, Vec3::Zero(), Vec3::Zero(), Vec3(0, -0.9 * stick, 0)));
  EXPECT_FALSE(c->stopped_by_force());
  c->update(sensed(2 * p.via_time, Vec3::Zero(), Vec3::Zero(), opposing));
  EXPECT_FALSE(c->stopped_by_force());
  c->update(sensed(3 * p.via_time, Vec3::Zero(), Vec3::Zero(), opposing));
  EXPECT_TRUE(c->stopped_by_force());
}

TEST(Controller, PositionFormIsForSpringsOnly) {
  EXPECT_THROW(make_controller(damper(Vec3(0, 0, -1)), ControllerForm::kPosition, params(), Vec3::Zero()),
               std::invalid_argument);
}

TEST(Controller, FormNamesRoundTrip) {
  for (ControllerForm f :
       {ControllerForm::kImpedance, ControllerForm::kAdmittance, ControllerForm::kPosition})
    EXPECT_EQ(parse_controller_form(controller_form_name(f)), f);
  EXPECT_FALSE(parse_controller_form("velocity").has_value());
}

}  // namespace
}  // namespace cmt
