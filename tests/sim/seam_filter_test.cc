// Seam contact filter (sim/seam_filter.h): a robot sliding across a physical seam between two environment
// boxes, or flush with a wall while resting on a coplanar neighbour, is not stopped by a ghost contact, and
// a real concave edge is unchanged.
#include "sim/seam_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "models/loaded_task.h"
#include "sim/calibration.h"
#include "sim/rollout.h"

namespace cmt {
namespace {

std::shared_ptr<const LoadedTask> builtin(const std::string& name) {
  return load_task(std::filesystem::path(CMT_SOURCE_DIR) / "models" / "tasks" / (name + ".yaml"));
}

// Mean speed along the top face (x-y) over the second half of a 0.16 s damper drive from rest.
double face_speed(const std::shared_ptr<const RolloutScene>& scene, const Vec3& start, const Vec3& dir) {
  RolloutRunner runner(scene);
  const Motion m{"slide", Motion::Kind::kDamper, dir, {}};
  Vec3 mid = start, end = start;
  runner.drive(start, m, 0.16, [&](const StepState& s) {
    if (s.time <= 0.08 + 1e-9) mid = s.position;
    end = s.position;
  });
  return (end - mid).head<2>().norm() / 0.08;
}

// A damper from `start` (C-space, on tslot's top) toward `dir` (mu = .48, alpha from the inward normal -z):
// with the filter it slides at Coulomb's V (sin alpha - mu cos alpha) within kMaxSpeedError; without it the
// ghost contact holds it (below kSlideThreshold of V).
void expect_slides_only_with_the_filter(const Vec3& start, const Vec3& dir) {
  const auto tslot = builtin("tslot");
  const double mu = 0.48, alpha = std::acos(dir.dot(-Vec3::UnitZ()));
  SimOptions options;
  options.form = ControllerForm::kImpedance;
  const auto filtered = RolloutScene::build(tslot, options);
  const double v = filtered->controller_params().damper_speed;
  const double coulomb = v * (std::sin(alpha) - mu * std::cos(alpha));
  EXPECT_NEAR(face_speed(filtered, start, dir), coulomb, kMaxSpeedError * coulomb);
  options.scene.seam_filter_relative = 0;
  const auto raw = RolloutScene::build(tslot, options);
  EXPECT_LT(face_speed(raw, start, dir), kSlideThreshold * v);
}

// tslot (physical form): the crossbar [x - 2, x + 2] x [y - 1, y + 1] on the lip at C-space (1, -3.35, 0) has
// its right end exactly on the seam x = 3 between the front lip [-3, 3] x [-8, -2] and the right lip [3, 8] x
// [-8, 8] (the whole crossbar lies at y < -2, where the front lip covers the right lip's face x = 3).
// Commanded at alpha = 0.717 rad from the face normal (phi = atan .48 = 0.448) toward +x, -y, Coulomb says it
// slides at V (sin alpha - mu cos alpha). `cmt check-sticking` (seed 7, trial 700) found it stuck: MuJoCo put
// a contact with normal -x on the right lip's internal face x = 3, because the crossbar overlapped it by less
// than it had sunk into the lip.
TEST(SeamFilter, RobotSlidesAcrossAPhysicalSeamAsCoulombSays) {
  expect_slides_only_with_the_filter(Vec3(1, -3.3456529039197758, 0),
                                     Vec3(0.583184829559215, -0.30321768744108485, -0.7536275529695486));
}

// tslot, C-space (-1, -2.43, 0) (check-sticking seed 7, trial 100): the crossbar [-3, 1] x [-3.43, -1.43]
// rests on the front lip (y < -2) and hangs over the entry hole (y > -2) with its left end flush with the
// hole's wall x = -3 of the left lip. It overlaps that wall by 8e-9 m, less than it has sunk into the lip top
// (3.6e-8 m), so MuJoCo took the wall's normal (+x). In C-space the point lies on the flat top face (the
// front lip's C-obstacle covers the left lip's face there), and moved 2 tau out of the wall the crossbar
// still rests on the front lip, whose top is coplanar with the left lip's: the filter drops the wall contact.
// Commanded at alpha = 0.521 rad (> phi = 0.448) toward -x, -y, Coulomb says it slides at V (sin alpha - mu
// cos alpha) = 0.081 V.
TEST(SeamFilter, RobotFlushWithAWallSlidesOnTheFaceItRestsOn) {
  expect_slides_only_with_the_filter(Vec3(-1, -2.4291200376125888, 0),
                                     Vec3(-0.24383383696211847, -0.4339940678248832, -0.8672913057589945));
}

// Where no face is internal the filter drops nothing: the calibration's floor and wall (whose concave edge is
// a real one: the floor contacts in the corner lie a penetration depth inside the wall's footprint) give the
// same numbers, bit for bit, with and without it.
TEST(SeamFilter, ChangesNothingAtARealConcaveEdge) {
  MjcfOptions with = SimOptions{}.scene, without = with;
  ASSERT_GT(with.seam_filter_relative, 0);
  without.seam_filter_relative = 0;
  const CalibrationResult a = calibrate_friction({ControllerForm::kImpedance}, with);
  const CalibrationResult b = calibrate_friction({ControllerForm::kImpedance}, without);
  ASSERT_EQ(a.cases.size(), b.cases.size());
  for (std::size_t i = 0; i < a.cases.size(); ++i) {
    EXPECT_EQ(a.cases[i].speed, b.cases[i].speed) << i;
    EXPECT_EQ(a.cases[i].max_penetration, b.cases[i].max_penetration) << i;
  }
}

// A slot narrower than tau between two boxes that do not abut (campaign task 1518, `cmt soundness-campaign`
// seed 3): wall A's face x = 40 and box B's face x = 40.05 across a 0.05 mm slot above the floor z = 30. A
// damper pressing into A's wall while descending the slot slides down it (alpha = 78.7 deg from the wall's
// inward normal, mu = .1) and stops on the floor at A's wall. A's wall is a real face: the robot moved 2 tau
// out of it overlaps B, but B does not reach A's face, so the filter keeps the contact and the robot never
// sinks into A (it sank 0.057 mm in task 1518 when B counted as covering A's face).
TEST(SeamFilter, KeepsTheWallsOfASlotNarrowerThanItsTolerance) {
  const auto slot = load_task_from_string(R"(
name: narrow_slot
units: mm
friction: 0.1
uncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.05, theta_f: 0.05}
cspace:
  - box: {min: [0, 0, 0], max: [40, 60, 60]}
  - box: {min: [40.05, 0, 0], max: [100, 60, 50]}
  - box: {min: [0, 0, 0], max: [100, 60, 30]}
bounds: {min: [0, 0, 0], max: [100, 60, 100]}
start: {point: [40, 30, 45]}
goal:
  - {polygon: [[40, 0, 30], [40.05, 0, 30], [40.05, 60, 30], [40, 60, 30]]}
motions: {down: {damper: [-0.2, 0, -1]}}
strategies: {s: [down]}
)",
                                          "narrow_slot");
  SimOptions options;
  options.form = ControllerForm::kImpedance;
  const auto scene = RolloutScene::build(slot, options);
  const double s = scene->meters_per_unit();
  const double tau = options.scene.seam_filter_relative * slot->cspace.scale();  // task units
  ASSERT_GT(tau, 2 * 0.05) << "the slot must be narrow enough for the filter to consider it";
  RolloutRunner runner(scene);
  const Motion m{"down", Motion::Kind::kDamper, Vec3(-0.2, 0, -1).normalized(), {}};
  double min_x = 1e9;
  Vec3 end = Vec3::Zero();
  runner.drive(Vec3(40.025, 30, 45), m, 2.0, [&](const StepState& st) {
    min_x = std::min(min_x, st.position.x());
    end = st.position;
  });
  const double contact = kAtomRelativeTolerance * slot->cspace.scale();
  EXPECT_GT(min_x, 40 - contact) << "sank " << (40 - min_x) * s << " m into the wall";
  EXPECT_NEAR(end.z(), 30, contact) << "stopped above the slot's floor";
}

// A convex C-space part standing on the bounds' floor (a ramp over [0, 10] x [0, 4], its top falling from 4
// to 1): its bottom facet lies on the bounds, so the exporter grows it 2h into the outside before eroding,
// as it grows boxes (docs/mujoco-scene.md "Seams"). A damper along the floor into the ramp's side x = 0
// (alpha = 73.3 deg from the floor's inward normal, pressing into the side) stops at the side: without the
// growth the cube, 2h tall, fitted the slot between the floor's wall geom and the eroded ramp and slid under
// it.
TEST(SeamFilter, AConvexPartOnTheFloorLeavesNoSlotUnderIt) {
  const auto ramp = load_task_from_string(R"(
name: ramp
units: in
friction: 0.3
uncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.1, theta_f: 0.05}
cspace:
  - convex: {vertices: [[0, 0, 0], [10, 0, 0], [10, 4, 0], [0, 4, 0], [0, 0, 4], [10, 0, 1], [10, 4, 1], [0, 4, 4]]}
bounds: {min: [-4, -2, 0], max: [12, 6, 6]}
start: {point: [-2, 2, 0]}
goal: {point: [0, 2, 0]}
motions: {v1: {damper: [1, 0, -0.3]}}
strategies: {s: [v1]}
)",
                                          "ramp");
  SimOptions options;
  options.form = ControllerForm::kImpedance;
  RolloutRunner runner(RolloutScene::build(ramp, options));
  const Motion m{"v1", Motion::Kind::kDamper, Vec3(1, 0, -0.3).normalized(), {}};
  Vec3 end = Vec3::Zero();
  runner.drive(Vec3(-2, 2, 0), m, 2.0, [&](const StepState& st) { end = st.position; });
  const double contact = kAtomRelativeTolerance * ramp->cspace.scale();
  EXPECT_NEAR(end.x(), 0, contact) << "ended at " << end.transpose();
  EXPECT_NEAR(end.z(), 0, contact) << "ended at " << end.transpose();
}

}  // namespace
}  // namespace cmt
