// Sensing termination end to end (Buckley §3.1.2 type 2, §4.5): a task motion's `terminate` sets reach the
// rollout engine (RolloutScene fills SimOptions::terminations from the task), the simulated robot stops
// inside the position box grown by eps_s, and every end lies in the verifier's predicted termination set.
#include <gtest/gtest.h>

#include <cmath>

#include "models/loaded_task.h"
#include "sim/rollout.h"
#include "tests/verifier/sensing_tasks.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

TEST(SensingRollout, DamperStopsInThePositionBoxAndInThePrediction) {
  // tests/verifier/sensing_tasks.h: the damper slides along +x on the floor (every admissible velocity has
  // a +x component: azimuths within .142 rad of +x), pressing into it, so it is in contact throughout. P_s is
  // x in [0, 1], |y| <= 3, |z| <= .5; the slide stays within |y| <= 1 + 5.6 tan .142 = 1.8 there, so every
  // rollout enters P_s's x range inside its y range. With |sensed - true| <= eps_s = .1 the type-2 rule fires
  // at the first step with sensed x >= 0: true x >= -.1, and true x <= .1 + one step's travel (3 in/s x
  // .25 ms = 7.5e-4 in; 1e-3 allowed) because the robot moves in +x only.
  const auto task = load_task_from_string(
      test::sensing_room("{position: {box: {min: [0, -3, -0.5], max: [1, 3, 0.5]}}}"), "sensing_room");
  // The impedance form, as the validation suite runs (README): in the admittance form a robot sliding on a
  // face hops off it by up to ~4e-3 in here (measured, 40 rollouts), more than the atom tolerance (1e-4 x
  // scale = 1.5e-3 in), and a sensing termination, unlike sticking, stops it mid-slide, possibly mid-hop.
  SimOptions options;
  options.form = ControllerForm::kImpedance;
  const auto scene = RolloutScene::build(task, options);  // no terminations given: the task's own are used
  ASSERT_EQ(scene->options().terminations.count("m"), 1u);
  const VerifyResult prediction = verify_strategy(*task, *task->task.find_strategy("s"));
  ASSERT_EQ(prediction.steps.size(), 1u);
  const VerifyStep& step = prediction.steps[0];

  const auto results = run_rollouts(scene, *task->task.find_strategy("s"), 8, 1, 2);
  ASSERT_EQ(results.size(), 8u);
  for (const RolloutOutcome& r : results) {
    ASSERT_FALSE(r.unstable) << r.index << ": " << r.unstable_reason;
    EXPECT_EQ(r.termination, Termination::kPosition) << r.index;
    EXPECT_GE(r.end.x(), -0.1) << r.index;
    EXPECT_LE(r.end.x(), 0.1 + 1e-3) << r.index;
    EXPECT_LE(std::abs(r.end.y()), 3.1) << r.index;
    EXPECT_NEAR(r.end.z(), 0, scene->atom_tolerance()) << r.index;
    // Inside the prediction, with the tolerance the validation uses for contact ends (the robot sits up to
    // ~1e-6 in off the face: docs/mujoco-scene.md).
    EXPECT_LE(step.termination.distance(r.end), scene->atom_tolerance())
        << r.index << " " << r.end.transpose();
    EXPECT_LE(step.sensing->distance(r.end), scene->atom_tolerance()) << r.index;
  }
}

TEST(SensingRollout, CallerSetsOverrideTheTasks) {
  // An explicit SimOptions::terminations entry wins over the task's (tests and experiments may replace it):
  // an empty spec leaves sticking only, so the robot slides on to the edge x = 5 and sticks there.
  const auto task = load_task_from_string(
      test::sensing_room("{position: {box: {min: [0, -3, -0.5], max: [1, 3, 0.5]}}}"), "sensing_room");
  SimOptions options;
  options.terminations["m"] = TerminationSpec{};
  const auto scene = RolloutScene::build(task, options);
  const auto results = run_rollouts(scene, *task->task.find_strategy("s"), 2, 1, 2);
  for (const RolloutOutcome& r : results) {
    EXPECT_EQ(r.termination, Termination::kSticking) << r.index;
    EXPECT_NEAR(r.end.x(), 5, scene->atom_tolerance()) << r.index;
  }
}

}  // namespace
}  // namespace cmt
