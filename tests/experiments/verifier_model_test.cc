// The verifier's velocity-direction bound per controller form (experiments/validation/verifier_model.h): the
// extra angle of the admittance form's sensed-force feedback against hand-computed values, the widened task
// it verifies on, and the forms that keep the task's theta_v. End to end: two_blocks `slide`, reliable for
// the impedance form, is unreliable for the admittance form (its concave edge may no longer stick).
#include "experiments/validation/verifier_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <utility>

#include "models/input_error.h"
#include "tests/experiments/cmt_runner.h"

namespace cmt {
namespace {

std::string room_yaml(double theta_v, double theta_f) {
  return "name: room\nunits: in\nfriction: 0.25\nuncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: " +
         std::to_string(theta_v) + ", theta_f: " + std::to_string(theta_f) +
         "}\ncspace: []\nbounds: {min: [-4, -4, 0], max: [4, 4, 4]}\nstart: {point: [0, 0, 4]}\n"
         "goal: {point: [0, 0, 4]}\nmotions:\n  m: {damper: [0, 0, -1]}\nstrategies:\n  s: [m]\n";
}

TEST(VerifierModel, ExtraAngleOfTheSensedForceFeedback) {
  // beta = asin(2 rho / (1 + rho) sin(theta_f / 2)), rho = 1/2: asin((2/3) sin(theta_f / 2)).
  // theta_f = .3 (cube, two_blocks): (2/3) sin .15 = (2/3) .1494381 = .0996254, asin -> .0997910.
  EXPECT_NEAR(sensed_force_extra_angle(0.3), 0.0997910, 1e-7);
  // theta_f = .05 (hole, tslot, peg_in_hole_real): (2/3) sin .025 = .0166649, asin -> .0166657.
  EXPECT_NEAR(sensed_force_extra_angle(0.05), 0.0166657, 1e-7);
  EXPECT_EQ(sensed_force_extra_angle(0), 0);
  // Never above rho / (1 + rho) theta_f = theta_f / 3, and at least the exact turn of the imparted force
  // when stuck: atan(rho sin .3 / (1 + rho cos .3)) = atan(.147760 / 1.477668) = .0996641.
  EXPECT_LE(sensed_force_extra_angle(0.3), 0.1);
  EXPECT_GE(sensed_force_extra_angle(0.3), 0.0996641);
  // A servo as stiff as the controller (rho = 1): asin(sin(theta_f / 2)) = theta_f / 2.
  EXPECT_NEAR(sensed_force_extra_angle(0.3, 1.0), 0.15, 1e-15);
}

TEST(VerifierModel, AdmittanceWidensThetaVInACopyOfTheTask) {
  const std::string yaml = room_yaml(0.1, 0.1);
  const auto task = load_task_from_string(yaml, "room.yaml");
  const VerifierModel m = make_verifier_model(task, ControllerForm::kAdmittance);
  // .1 + asin((2/3) sin .05) = .1 + asin(.0333194) = .1 + .0333256.
  EXPECT_NEAR(m.extra_angle, 0.0333256, 1e-7);
  EXPECT_DOUBLE_EQ(m.theta_v, 0.1 + m.extra_angle);
  EXPECT_EQ(m.task_theta_v, 0.1);
  EXPECT_EQ(m.theta_f, 0.1);
  ASSERT_NE(m.task, task);
  EXPECT_EQ(m.task->task.uncertainty.theta_v, m.theta_v);
  EXPECT_EQ(task->task.uncertainty.theta_v, 0.1);  // the loaded task is unchanged
  EXPECT_EQ(m.task->task.uncertainty.theta_f, 0.1);
  EXPECT_EQ(m.task->task.source_file, "room.yaml");
  EXPECT_EQ(m.task->cspace.faces().size(), task->cspace.faces().size());
  const nlohmann::json j = verifier_model_json(m);
  EXPECT_EQ(j["controller"], "admittance");
  EXPECT_EQ(j["theta_v"].get<double>(), m.theta_v);
  EXPECT_NE(j["reason"].get<std::string>().find("theta_f"), std::string::npos);
}

TEST(VerifierModel, ImpedanceAndExactForceKeepTheTasksThetaV) {
  const std::string yaml = room_yaml(0.1, 0.1);
  const auto task = load_task_from_string(yaml, "room.yaml");
  for (const ControllerForm form : {ControllerForm::kImpedance, ControllerForm::kPosition}) {
    const VerifierModel m = make_verifier_model(task, form);
    EXPECT_EQ(m.task, task);
    EXPECT_EQ(m.theta_v, 0.1);
    EXPECT_EQ(m.extra_angle, 0);
  }
  const std::string exact = room_yaml(0.1, 0);
  const VerifierModel m =
      make_verifier_model(load_task_from_string(exact, "room.yaml"), ControllerForm::kAdmittance);
  EXPECT_EQ(m.theta_v, 0.1);
}

TEST(VerifierModel, TheFormPicksTheSpringModel) {
  // The velocity forms drive toward p − b with the sensing offset b fixed during a motion: the velocity
  // model; the position form replans its via points from fresh sensed positions: Buckley's via-point model
  // (docs/verifier.md, "Velocity-form spring model").
  const std::string yaml = room_yaml(0.1, 0.1);
  const auto task = load_task_from_string(yaml, "room.yaml");
  const std::pair<ControllerForm, const char*> cases[] = {{ControllerForm::kImpedance, "velocity"},
                                                          {ControllerForm::kAdmittance, "velocity"},
                                                          {ControllerForm::kPosition, "via-point"}};
  for (const auto& [form, name] : cases) {
    const VerifierModel m = make_verifier_model(task, form);
    EXPECT_EQ(spring_model_name(m.spring_model), std::string(name));
    EXPECT_EQ(verifier_model_json(m)["spring_model"], name);
    // Every form's rollouts stop by the same 1 % rule, which the verifier must take in (its options carry
    // it; docs/verifier.md "Slow slides count as stops").
    EXPECT_EQ(m.verify_options().stop_relative_speed, 0.01);
    EXPECT_EQ(m.verify_options().spring_model, m.spring_model);
    EXPECT_EQ(verifier_model_json(m)["stop_relative_speed"], 0.01);
  }
}

TEST(VerifierModel, AWidenedAngleBeyondTheFormatIsBadInputNamingTheKey) {
  // 1.55 + asin((2/3) sin .05) = 1.583 >= pi/2.
  const std::string yaml = room_yaml(1.55, 0.1);
  try {
    make_verifier_model(load_task_from_string(yaml, "room.yaml"), ControllerForm::kAdmittance);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "room.yaml");
    EXPECT_EQ(e.key(), "uncertainty.theta_v");
    EXPECT_NE(e.reason().find("--controller impedance"), std::string::npos) << e.what();
    EXPECT_NE(e.reason().find("must be < pi/2 (1.5708) radians, got 1.58"), std::string::npos) << e.what();
  }
}

TEST(VerifierModel, AdmittanceOnTwoBlocksSlideIsVerifiedWithTheWidenedAngle) {
  // With theta_v = .25 the concave edge x = -1.5, z = 0 must stick: the summed cone reaches sqrt(2) tan phi
  // = .354 sideways, the velocity cone tan .25 = .255 (two_blocks.yaml: `slide` is reliable). Widened to
  // .25 + .0998 = .3498 (tan .3498 = .365 > .354) the robot may slide along the edge, which the verifier
  // can no longer rule out: unreliable (admittance rollouts that creep along the edge and time out are then
  // counterexamples, not soundness bugs; docs/validation.md).
  const test::Result r = test::run("validate " + test::task("two_blocks") +
                                   " --strategy slide -n 7 --seed 1 --mode extreme --controller admittance "
                                   "--search-budget 0 --threads 2 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["controller"], "admittance");
  EXPECT_EQ(j["verifier_model"]["task_theta_v"], 0.25);
  EXPECT_NEAR(j["verifier_model"]["theta_v"].get<double>(), 0.25 + 0.0997910, 1e-7);
  EXPECT_FALSE(j["reliable"].get<bool>());
  EXPECT_FALSE(j["soundness_bug"].get<bool>());
  EXPECT_EQ(j["outside"], 0);
  // The impedance form (the default) keeps theta_v = .25 and the proof: reliable.
  const test::Result i = test::run("validate " + test::task("two_blocks") +
                                   " --strategy slide -n 7 --seed 1 --mode extreme --threads 2 --json");
  ASSERT_EQ(i.status, 0) << i.out;
  const auto k = nlohmann::json::parse(i.out);
  EXPECT_EQ(k["controller"], "impedance");
  EXPECT_EQ(k["verifier_model"]["theta_v"], 0.25);
  EXPECT_TRUE(k["reliable"].get<bool>());
  EXPECT_EQ(k["successes"], 7);
}

}  // namespace
}  // namespace cmt
