// Rollouts: reproducible for any thread count, the hole task's taught strategy works and its too-deep
// variant does not always, failures are recorded (unstable, time-out) instead of crashing, and the robot is
// gravity-compensated. See docs/rollouts.md.
#include "sim/rollout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "models/loaded_task.h"
#include "sim/calibration.h"
#include "sim/mujoco_guard.h"

namespace cmt {
namespace {

std::shared_ptr<const LoadedTask> builtin(const std::string& name) {
  return load_task(std::filesystem::path(CMT_SOURCE_DIR) / "models" / "tasks" / (name + ".yaml"));
}

const Strategy& strategy(const LoadedTask& t, const std::string& name) {
  const Strategy* s = t.task.find_strategy(name);
  EXPECT_NE(s, nullptr) << name;
  return *s;
}

// Bit-for-bit equality of two outcomes (every recorded number).
void expect_identical(const RolloutOutcome& a, const RolloutOutcome& b) {
  EXPECT_EQ(a.index, b.index);
  EXPECT_EQ(a.start, b.start);
  EXPECT_EQ(a.end, b.end);
  EXPECT_EQ(a.atom, b.atom);
  EXPECT_EQ(a.termination, b.termination);
  EXPECT_EQ(a.success, b.success);
  EXPECT_EQ(a.unstable, b.unstable);
  ASSERT_EQ(a.motions.size(), b.motions.size());
  for (std::size_t i = 0; i < a.motions.size(); ++i) {
    const MotionOutcome &x = a.motions[i], &y = b.motions[i];
    EXPECT_EQ(x.end, y.end);
    EXPECT_EQ(x.atom, y.atom);
    EXPECT_EQ(x.termination, y.termination);
    EXPECT_EQ(x.contact_force, y.contact_force);
    EXPECT_EQ(x.steps, y.steps);
    EXPECT_EQ(x.max_penetration, y.max_penetration);
    EXPECT_EQ(x.velocity_switches, y.velocity_switches);
  }
}

TEST(Rollout, ResultsAreBitIdenticalForAnyThreadCount) {
  const auto hole = builtin("hole");
  for (const SampleMode mode : {SampleMode::kUniform, SampleMode::kExtreme}) {
    SCOPED_TRACE(sample_mode_name(mode));
    SimOptions options;
    options.mode = mode;
    const auto scene = RolloutScene::build(hole, options);
    const auto one = run_rollouts(scene, strategy(*hole, "teach"), 12, 77, 1);
    const auto two = run_rollouts(scene, strategy(*hole, "teach"), 12, 77, 2);
    const auto three = run_rollouts(scene, strategy(*hole, "teach"), 12, 77, 3);
    ASSERT_EQ(one.size(), 12u);
    for (std::size_t i = 0; i < one.size(); ++i) {
      SCOPED_TRACE(i);
      expect_identical(one[i], two[i]);
      expect_identical(one[i], three[i]);
    }
    // A single rollout run on its own is the same as inside a batch: it depends on (seed, index) only.
    RolloutRunner runner(scene);
    expect_identical(runner.run(strategy(*hole, "teach"), 77, 5), one[5]);
    // Another seed gives other starts.
    const auto other = run_rollouts(scene, strategy(*hole, "teach"), 12, 78, 2);
    int same = 0;
    for (std::size_t i = 0; i < one.size(); ++i) same += one[i].start == other[i].start;
    EXPECT_LT(same, 3);
  }
}

// The far (+y) hole wall: the face with outward normal -y in the plane y = 1 (hole.yaml: p2 is 1 in behind
// it, halfway down, and the robot is meant to stick on it, Buckley §5.2 / Fig 6.10).
int far_wall(const CSpace& c) {
  for (const Face& f : c.faces())
    if (f.normal.isApprox(-Vec3::UnitY()) && std::abs(f.offset + 1) < 1e-12) return f.id;
  return -1;
}

TEST(Rollout, HoleTeachSucceedsInEveryRollout) {
  const auto hole = builtin("hole");
  const int wall = far_wall(hole->cspace);
  ASSERT_GE(wall, 0);
  for (const SampleMode mode : {SampleMode::kUniform, SampleMode::kExtreme}) {
    SCOPED_TRACE(sample_mode_name(mode));
    SimOptions options;
    options.mode = mode;
    const auto scene = RolloutScene::build(hole, options);
    const auto results = run_rollouts(scene, strategy(*hole, "teach"), 60, 1, 2);
    int on_wall = 0;
    for (const RolloutOutcome& r : results) {
      EXPECT_TRUE(r.success) << "rollout " << r.index << " from " << r.start.transpose() << " ended at "
                             << r.end.transpose();
      EXPECT_FALSE(r.unstable) << r.unstable_reason;
      ASSERT_EQ(r.motions.size(), 2u);
      EXPECT_EQ(r.motions[0].termination, Termination::kSticking);
      // The first motion sticks on the far wall (or, at worst, on one of its edges), inside the hole.
      const MotionOutcome& m = r.motions[0];
      on_wall += m.atom == wall;
      EXPECT_NEAR(m.end.y(), 1.0, scene->atom_tolerance()) << r.index;
      EXPECT_LT(m.end.z(), 0);
      EXPECT_GT(m.end.z(), -2);
      EXPECT_LT(m.max_penetration, scene->unstable_penetration());
    }
    EXPECT_GT(on_wall, 50);
  }
}

TEST(Rollout, HoleTeachTooDeepFailsInSome) {
  // p2_deep = (0, 2, -8) pulls so steeply that the robot may stick on the top face before the hole (task
  // file comment); p1 then rescues some of those, not all.
  const auto hole = builtin("hole");
  const auto scene = RolloutScene::build(hole);
  const auto results = run_rollouts(scene, strategy(*hole, "teach_too_deep"), 40, 1, 2);
  int failures = 0, stuck_on_top = 0;
  for (const RolloutOutcome& r : results) {
    failures += !r.success;
    EXPECT_FALSE(r.unstable) << r.unstable_reason;
    const MotionOutcome& m = r.motions.at(0);
    stuck_on_top += m.termination == Termination::kSticking &&
                    std::abs(m.end.z()) < scene->atom_tolerance() && m.end.y() < -1;
    if (!r.success) {
      EXPECT_NEAR(r.end.z(), 0, scene->atom_tolerance()) << "a failure ends on the top surface";
    }
  }
  EXPECT_GT(failures, 0);
  EXPECT_GT(stuck_on_top, 0);
}

TEST(Rollout, StartsAreSampledInTheStartRegion) {
  const auto hole = builtin("hole");
  const Region& start = hole->task.start;  // segment x in [-1, 1], y = -3, z = 0
  for (const SampleMode mode : {SampleMode::kUniform, SampleMode::kExtreme}) {
    Rng rng = rollout_stream(9, mode == SampleMode::kExtreme);
    int vertices = 0, left_half = 0;
    const int n = 4000;
    for (int i = 0; i < n; ++i) {
      const Vec3 p = sample_region(start, mode, rng);
      ASSERT_LE(distance_to_region(p, start), 1e-15);
      vertices += std::abs(std::abs(p.x()) - 1) == 0;
      left_half += p.x() < 0;
    }
    if (mode == SampleMode::kExtreme)
      EXPECT_NEAR(vertices / double(n), kExtremeBoundaryFraction / 2, 0.03);
    else
      EXPECT_EQ(vertices, 0);
    EXPECT_NEAR(left_half / double(n), 0.5, 0.03);
  }
  // Polygons: uniform by area (the hole bottom, a 2 x 2 square: a quarter of the samples per quadrant).
  const Region& goal = hole->task.goal.at(0);
  Rng rng = rollout_stream(10, 0);
  int quadrant = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 p = sample_region(goal, SampleMode::kUniform, rng);
    ASSERT_LE(distance_to_region(p, goal), 1e-12);
    quadrant += p.x() > 0 && p.y() > 0;
  }
  EXPECT_NEAR(quadrant / 4000.0, 0.25, 0.03);
}

TEST(Rollout, SeamsDoNotSwallowTheRobot) {
  // The start segment's ends (+-1, -3, 0) lie on the lines where the hole task's top surface is split
  // between C-space boxes; pushed down there, the robot must stay on the surface (docs/mujoco-scene.md
  // "Seams": without seam closing it sank 0.4 in in 0.4 s).
  const auto hole = builtin("hole");
  const auto scene = RolloutScene::build(hole);
  RolloutRunner runner(scene);
  for (const double x : {-1.0, 1.0}) {
    const Motion down{"down", Motion::Kind::kDamper, Vec3(0, 0, -1), {}};
    double lowest = 0;
    runner.drive(Vec3(x, -3, 0), down, 0.5,
                 [&](const StepState& s) { lowest = std::min(lowest, s.position.z()); });
    EXPECT_GT(lowest, -1e-4) << "x = " << x;
  }
}

TEST(Rollout, UnstableRolloutsAreRecordedNotThrown) {
  // A scene whose contact buffer holds a single contact: MuJoCo warns (contact buffer full) as soon as the
  // robot touches a box, which makes the rollout unstable.
  const auto hole = builtin("hole");
  SimOptions options;
  std::string xml = mjcf_xml(*hole, options.scene);
  const std::size_t at = xml.find("nconmax=\"");
  ASSERT_NE(at, std::string::npos);
  const std::size_t end = xml.find('"', at + 9);
  xml.replace(at, end - at + 1, "nconmax=\"1\"");
  const auto scene = RolloutScene::build(hole, MujocoModel::load_xml_string(xml), options);
  std::vector<RolloutOutcome> results;
  ASSERT_NO_THROW(results = run_rollouts(scene, strategy(*hole, "teach"), 4, 1, 2));
  for (const RolloutOutcome& r : results) {
    EXPECT_TRUE(r.unstable);
    EXPECT_FALSE(r.success);
    EXPECT_EQ(r.termination, Termination::kUnstable);
    EXPECT_NE(r.unstable_reason.find("contact buffer full"), std::string::npos) << r.unstable_reason;
  }
}

TEST(Rollout, TimeOutIsNoTerminationAndAFailure) {
  const auto hole = builtin("hole");
  SimOptions options;
  // No speed cap and a limit of 0.1 / lambda = 25 ms: shorter than the sticking rule's window.
  options.max_speed_per_scale = 1e9;
  options.spring_timeout_time_constants = 0.1;
  const auto scene = RolloutScene::build(hole, options);
  const auto results = run_rollouts(scene, strategy(*hole, "teach"), 3, 1, 1);
  for (const RolloutOutcome& r : results) {
    EXPECT_EQ(r.termination, Termination::kNone);
    EXPECT_FALSE(r.success);
    EXPECT_EQ(r.motions.size(), 1u) << "a motion that does not terminate ends the strategy";
  }
}

// Mean contact force and velocity of a motion driven from rest at `from`, over [settle, settle + window].
struct DriveMeans {
  Vec3 force = Vec3::Zero();     // contact force on the robot, N
  Vec3 velocity = Vec3::Zero();  // task units / s
  bool contact_every_step = true;
};
DriveMeans drive_means(const std::shared_ptr<const RolloutScene>& scene, const Vec3& from, const Motion& m,
                       double settle, double window) {
  RolloutRunner runner(scene);
  DriveMeans r;
  Vec3 x1 = from, x2 = from;
  long n = 0;
  runner.drive(from, m, settle + window, [&](const StepState& s) {
    if (s.time <= settle + 1e-9) {  // drive() reports times k dt; 1e-9 s is far below any step
      x1 = s.position;
      return;
    }
    r.force += s.force;
    ++n;
    r.contact_every_step = r.contact_every_step && s.contacts > 0;
    x2 = s.position;
  });
  r.force /= static_cast<double>(n);
  r.velocity = (x2 - x1) / window;
  return r;
}

// The hole scene with gravity on (the robot is compensated: sim/rollout.cc adds qfrc_bias to the servo
// force).
std::shared_ptr<const RolloutScene> heavy_scene(std::shared_ptr<const LoadedTask> task,
                                                const SimOptions& options) {
  const auto model = MujocoModel::load_xml_string(mjcf_xml(*task, options.scene));
  model->get()->opt.gravity[2] = -9.81;
  return RolloutScene::build(task, model, options);
}

// Forces that must agree to rounding: the compensation is exact to one rounding of qfrc_bias (1 ulp of
// 9.81 N = 1.8e-15 N) and, where the contact is continuous (no hops, so nothing chaotic amplifies it),
// measured flat / heavy differences stay below 1e-13 N. 1e-9 N is four orders above that and ten below the
// 9.81 N an uncompensated 1 kg robot adds to the normal load.
inline constexpr double kForceRoundingTolerance = 1e-9;  // N
// A robot sliding at the rollouts' damper speed in the admittance form bounces (docs/rollouts.md "Rollouts
// are chaotic at the 1e-3 in level": in contact on ~6 % of the steps), so its mean normal load over a
// window varies with any rounding-level perturbation: measured up to 0.45 % of the commanded normal load
// between flat and compensated-heavy runs over 1.5 s (hole top face, 1.2-2 phi, both forms, 1 and 3.6
// in/s), and up to 0.5 % between flat runs and Coulomb's value. 3 % is 6x that; uncompensated gravity adds
// 9.81 N, 200 % of the 4.8 N commanded here.
inline constexpr double kChaoticMeanLoadTolerance = 0.03;  // of the commanded normal load

TEST(Rollout, RobotIsGravityCompensated) {
  // In free space the compensated robot moves exactly as commanded: a horizontal damper motion does not sag
  // (uncompensated, 1 kg would sink at m g / b = 0.1 m/s, 0.05 m in 0.5 s).
  const auto hole = builtin("hole");
  const SimOptions options;
  const auto heavy = heavy_scene(hole, options);
  EXPECT_EQ(heavy->model()->get()->opt.gravity[2], -9.81);
  RolloutRunner runner(heavy);
  const Motion sideways{"sideways", Motion::Kind::kDamper, Vec3(1, 0, 0), {}};
  double lowest = 2, highest = 2;
  runner.drive(Vec3(-2, 0, 2), sideways, 0.5, [&](const StepState& s) {
    lowest = std::min(lowest, s.position.z());
    highest = std::max(highest, s.position.z());
  });
  EXPECT_LT(highest - lowest, 1e-9);

  // In contact, on the hole's top face (box B, z = 0, mu = .48), damper commands d = (sin a, 0, -cos a) at
  // a = 0.5 and 1.5 phi. The contact force must be what the gravity-free model says; an uncompensated robot
  // would press 9.81 N harder.
  const double mu = hole->task.friction, phi = std::atan(mu);
  const Vec3 on_face(2, 0, 0);
  auto push = [&](double ratio) {
    const double a = ratio * phi;
    return Motion{"push", Motion::Kind::kDamper, Vec3(std::sin(a), 0, -std::cos(a)), {}};
  };
  // Generalized damper gain b_eff (docs/rollouts.md "Controllers"): the servo's b_s in the impedance form,
  // b b_s / (b + b_s) in the admittance form (its loop through the sensed force).
  auto damper_gain = [](const RolloutScene& scene) {
    const ControllerParams& p = scene.controller_params();
    const double bs = p.servo_damping, b = p.damping();
    return scene.options().form == ControllerForm::kImpedance ? bs : b * bs / (b + bs);
  };

  // 1. Sticking (inside the friction cone), both velocity forms at the rollouts' damper speed: at rest the
  // contact balances the servo exactly, f = -b_eff V d, with gravity on or off.
  for (const ControllerForm form : {ControllerForm::kImpedance, ControllerForm::kAdmittance}) {
    SCOPED_TRACE(controller_form_name(form));
    SimOptions o = options;
    o.form = form;
    const auto flat = RolloutScene::build(hole, o), loaded = heavy_scene(hole, o);
    const Motion m = push(0.5);
    const DriveMeans a = drive_means(flat, on_face, m, 0.1, 0.2),
                     b = drive_means(loaded, on_face, m, 0.1, 0.2);
    const Vec3 expected = -damper_gain(*flat) * flat->controller_params().damper_speed * m.target;
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(a.force[k], expected[k], kForceRoundingTolerance) << k;
      EXPECT_NEAR(b.force[k], expected[k], kForceRoundingTolerance) << k;
    }
    const double v = flat->controller_params().damper_speed;
    EXPECT_LE(a.velocity.norm(), kMaxCreep * v);
    EXPECT_LE(b.velocity.norm(), kMaxCreep * v);
  }

  // 2. Sliding with a continuous contact: the impedance form at the calibration speed (1 in/s) stays in
  // contact on every step, so the motion is not chaotic and gravity on / off agree to rounding. The mean
  // normal load is the servo's b_s V cos a (no normal motion), and the sliding speed Coulomb's
  // V (sin a - mu cos a) (sim/calibration.h criterion: within 2 %).
  {
    SimOptions o = options;
    o.form = ControllerForm::kImpedance;
    o.damper_speed_per_scale = kCalibrationSpeed / hole->cspace.scale();
    const auto flat = RolloutScene::build(hole, o), loaded = heavy_scene(hole, o);
    const Motion m = push(1.5);
    const double v = flat->controller_params().damper_speed, alpha = 1.5 * phi;
    const DriveMeans a = drive_means(flat, on_face, m, 0.1, 0.5),
                     b = drive_means(loaded, on_face, m, 0.1, 0.5);
    ASSERT_TRUE(a.contact_every_step);
    ASSERT_TRUE(b.contact_every_step);
    const double normal = damper_gain(*flat) * v * std::cos(alpha);
    EXPECT_NEAR(a.force.z(), normal, kForceRoundingTolerance);
    EXPECT_NEAR(b.force.z(), normal, kForceRoundingTolerance);
    EXPECT_NEAR(b.force.x(), a.force.x(), kForceRoundingTolerance);
    const double coulomb = v * (std::sin(alpha) - mu * std::cos(alpha));
    EXPECT_NEAR(a.velocity.x(), coulomb, kMaxSpeedError * coulomb);
    EXPECT_NEAR(b.velocity.x(), coulomb, kMaxSpeedError * coulomb);
  }

  // 3. Sliding as in the rollouts (admittance form, the rollouts' damper speed): the robot bounces and the
  // motion is chaotic, so only means agree: over 1.5 s the mean normal load is b_eff V cos a, gravity on or
  // off, within kChaoticMeanLoadTolerance of it, and the sliding speed Coulomb's within 2 %.
  {
    const auto flat = RolloutScene::build(hole, options);
    const Motion m = push(1.5);
    const double v = flat->controller_params().damper_speed, alpha = 1.5 * phi;
    const DriveMeans a = drive_means(flat, on_face, m, 0.1, 1.5),
                     b = drive_means(heavy, on_face, m, 0.1, 1.5);
    const double normal = damper_gain(*flat) * v * std::cos(alpha);
    EXPECT_NEAR(a.force.z(), normal, kChaoticMeanLoadTolerance * normal);
    EXPECT_NEAR(b.force.z(), normal, kChaoticMeanLoadTolerance * normal);
    EXPECT_NEAR(b.force.z(), a.force.z(), kChaoticMeanLoadTolerance * normal);
    const double coulomb = v * (std::sin(alpha) - mu * std::cos(alpha));
    EXPECT_NEAR(a.velocity.x(), coulomb, kMaxSpeedError * coulomb);
    EXPECT_NEAR(b.velocity.x(), coulomb, kMaxSpeedError * coulomb);
  }
}

TEST(Rollout, SensedPositionTerminationStopsInTheSet) {
  // Cube task (Buckley §6.3.2 style): spring toward (0, 0, -3) from a top edge; with P_s = the bottom slab
  // z <= -0.9 the motion ends by type 2 (contact and sensed position in P_s) as soon as it lands.
  const auto cube = builtin("cube");
  SimOptions options;
  PositionSet ps;
  ps.add_box({Vec3(-2, -2, -2), Vec3(2, 2, -0.9 + cube->task.uncertainty.eps_s)});
  TerminationSpec spec;
  spec.sensed_position = ps;
  options.terminations["p1"] = spec;
  const auto scene = RolloutScene::build(cube, options);
  const auto results = run_rollouts(scene, strategy(*cube, "stick"), 8, 1, 2);
  for (const RolloutOutcome& r : results) {
    EXPECT_EQ(r.termination, Termination::kPosition) << r.index;
    EXPECT_NEAR(r.end.z(), -1, 0.05) << r.index;
  }
}

TEST(Rollout, ApplyingTheRecordedForcesWithMjStepReplaysTheRollout) {
  // The engine's step (mj_step1, controller, mj_step2) is MuJoCo's step: replaying its applied forces with
  // plain mj_step gives the same trajectory bit for bit (the benchmark's baseline relies on this).
  const auto hole = builtin("hole");
  const auto scene = RolloutScene::build(hole);
  RolloutRunner runner(scene);
  std::vector<Vec3> applied;
  runner.record_applied_forces(&applied);
  const RolloutOutcome r = runner.run(strategy(*hole, "teach"), 5, 0);
  ASSERT_FALSE(applied.empty());
  MujocoData data(scene->model());
  const mjModel* m = scene->model()->get();
  mjData* d = data.get();
  mj_resetData(m, d);
  for (int k = 0; k < 3; ++k) d->qpos[k] = r.start[k] * scene->meters_per_unit();
  for (const Vec3& f : applied) {
    for (int k = 0; k < 3; ++k) d->qfrc_applied[k] = f[k];
    mujoco_call([&] { mj_step(m, d); });
  }
  const Vec3 end = Vec3(d->qpos[0], d->qpos[1], d->qpos[2]) / scene->meters_per_unit();
  EXPECT_EQ(end, r.end);
}

}  // namespace
}  // namespace cmt
