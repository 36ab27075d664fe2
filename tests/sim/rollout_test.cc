// Rollouts: reproducible for any thread count, the hole task's taught strategy works and its too-deep
// variant does not always, failures are recorded (unstable, time-out) instead of crashing, and the robot is
// gravity-compensated. See docs/rollouts.md.
#include "sim/rollout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "models/loaded_task.h"
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

TEST(Rollout, RobotIsGravityCompensated) {
  // A scene with gravity on. In free space the compensated robot moves exactly as commanded: a horizontal
  // damper motion does not sag (uncompensated, 1 kg would sink at m g / b = 0.1 m/s, 0.05 m in 0.5 s).
  const auto hole = builtin("hole");
  SimOptions options;
  const auto model = MujocoModel::load_xml_string(mjcf_xml(*hole, options.scene));
  model->get()->opt.gravity[2] = -9.81;
  const auto heavy = RolloutScene::build(hole, model, options);
  EXPECT_EQ(heavy->model()->get()->opt.gravity[2], -9.81);
  RolloutRunner runner(heavy);
  const Motion sideways{"sideways", Motion::Kind::kDamper, Vec3(1, 0, 0), {}};
  double lowest = 2, highest = 2;
  runner.drive(Vec3(-2, 0, 2), sideways, 0.5, [&](const StepState& s) {
    lowest = std::min(lowest, s.position.z());
    highest = std::max(highest, s.position.z());
  });
  EXPECT_LT(highest - lowest, 1e-9);
  // Whole rollouts end where the gravity-free ones do: the same atoms, and end points within the atom
  // tolerance (rounding differences of the compensation are amplified by the contacts' hops, then settled
  // by the sticking rule's 1 % residual speed, so they are not bit-identical).
  const auto flat = RolloutScene::build(hole, options);
  const auto a = run_rollouts(flat, strategy(*hole, "teach"), 8, 3, 2);
  const auto b = run_rollouts(heavy, strategy(*hole, "teach"), 8, 3, 2);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].success, b[i].success);
    ASSERT_EQ(a[i].motions.size(), b[i].motions.size());
    for (std::size_t k = 0; k < a[i].motions.size(); ++k) {
      EXPECT_LT((a[i].motions[k].end - b[i].motions[k].end).norm(), flat->atom_tolerance()) << i << " " << k;
      EXPECT_EQ(a[i].motions[k].atom, b[i].motions[k].atom);
    }
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
