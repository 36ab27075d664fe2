// Every validation rule of the task format has a case here: the error must name the file, the key path and
// the reason (docs/contracts.md "Task files").
#include "models/task_loader.h"

#include <gtest/gtest.h>

#include <regex>

#include "models/loaded_task.h"
#include "models/task_error.h"
#include "tests/models/test_tasks.h"

namespace cmt {
namespace {

using test::replace;

// Loads and expects a TaskError whose key path and reason contain the given fragments.
void expect_error(const std::string& yaml, const std::string& key, const std::string& reason) {
  try {
    load_task_from_string(yaml, "bad.yaml");
    ADD_FAILURE() << "no error; expected key '" << key << "' reason '" << reason << "'";
  } catch (const TaskError& e) {
    EXPECT_EQ(e.file(), "bad.yaml");
    EXPECT_NE(e.key().find(key), std::string::npos) << "key was: " << e.key() << " (" << e.what() << ")";
    EXPECT_NE(e.reason().find(reason), std::string::npos) << "reason was: " << e.reason();
    EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos);
  }
}

TEST(TaskLoader, LoadsTheHole) {
  auto task = load_task_from_string(test::kHoleYaml, "hole.yaml");
  const Task& t = task->task;
  EXPECT_EQ(t.name, "hole");
  EXPECT_EQ(t.units, LengthUnit::kInch);
  EXPECT_DOUBLE_EQ(t.uncertainty.step, 0.2);  // defaults to eps_p (models/task_ranges.h)
  EXPECT_EQ(t.cspace.size(), 4u);
  EXPECT_DOUBLE_EQ(t.cspace[0].friction, 0.48);
  ASSERT_NE(t.find_strategy("teach"), nullptr);
  EXPECT_EQ(t.find_strategy("teach")->motions, (std::vector<std::string>{"p2", "p1"}));
  EXPECT_EQ(t.find_motion("p1")->kind, Motion::Kind::kSpring);
}

TEST(TaskLoader, NormalizesDamperAndReadsPartFriction) {
  std::string y = replace(test::kHoleYaml, "p1: {spring: [0, 0, -2.4]}", "p1: {damper: [0, 0, -2]}");
  y = replace(y, "max: [-1, 6, 0]}", "max: [-1, 6, 0], friction: 0.3}");
  auto task = load_task_from_string(y, "x.yaml");
  EXPECT_EQ(task->task.find_motion("p1")->target, Vec3(0, 0, -1));
  EXPECT_DOUBLE_EQ(task->task.cspace[0].friction, 0.3);
  EXPECT_DOUBLE_EQ(task->task.cspace[1].friction, 0.48);
}

TEST(TaskLoader, GoalMayBeAList) {
  const std::string y = replace(
      test::kHoleYaml, "goal: {polygon: [[-1, -1, -2], [1, -1, -2], [1, 1, -2], [-1, 1, -2]]}",
      "goal:\n  - point: [0, 0, -2]\n  - polygon: [[-1, -1, -2], [1, -1, -2], [1, 1, -2], [-1, 1, -2]]");
  auto task = load_task_from_string(y, "x.yaml");
  EXPECT_EQ(task->task.goal.size(), 2u);
}

TEST(TaskLoader, MalformedYaml) { expect_error("name: [unclosed", "name", "malformed YAML"); }

TEST(TaskLoader, UnknownKey) {
  expect_error(replace(test::kHoleYaml, "friction: 0.48", "friction: 0.48\nfrction: 0.3"), "frction",
               "unknown key");
  expect_error(replace(test::kHoleYaml, "theta_f: 0.05}", "theta_f: 0.05, eps_x: 1}"), "uncertainty.eps_x",
               "unknown key");
}

TEST(TaskLoader, MissingKey) {
  expect_error(replace(test::kHoleYaml, "name: hole\n", ""), "name", "missing required key");
  expect_error(replace(test::kHoleYaml, "eps_s: 0.2, ", ""), "uncertainty.eps_s", "missing required key");
  expect_error(replace(test::kHoleYaml, "start: {segment: [[-4, -3, 0], [-2, -3, 0]]}\n", ""), "start",
               "missing required key");
}

TEST(TaskLoader, WrongType) {
  expect_error(replace(test::kHoleYaml, "friction: 0.48", "friction: high"), "friction", "expected a number");
  expect_error(replace(test::kHoleYaml, "p1: {spring: [0, 0, -2.4]}", "p1: {spring: [0, 0]}"),
               "motions.p1.spring", "expected 3 numbers");
  expect_error(replace(test::kHoleYaml, "units: in", "units: feet"), "units", "must be one of in, mm, m");
}

TEST(TaskLoader, ReadsTheTasksOwnAxes) {
  const auto task = load_task_from_string(
      replace(test::kHoleYaml, "start:", "axes: [[0, 1, 0], [-1, 0, 0], [0, 0, 1]]\nstart:"), "hole.yaml");
  Eigen::Matrix3d expected;
  expected << 0, -1, 0, 1, 0, 0, 0, 0, 1;  // columns: the task's x, y and z axes
  EXPECT_EQ(task->task.axes, expected);
  EXPECT_TRUE(load_task_from_string(test::kHoleYaml, "hole.yaml")->task.axes.isIdentity());
}

TEST(TaskLoader, BadAxes) {
  const auto with_axes = [](const std::string& axes) {
    return replace(test::kHoleYaml, "start:", "axes: " + axes + "\nstart:");
  };
  expect_error(with_axes("[[1, 0, 0], [0, 1, 0]]"), "axes", "expected three axes");
  expect_error(with_axes("[[1, 0, 0], [0, 1], [0, 0, 1]]"), "axes[1]", "expected a world axis");
  expect_error(with_axes("[[1, 0, 0], [0, 0.5, 0], [0, 0, 1]]"), "axes[1][1]", "each entry is 0, 1 or -1");
  expect_error(with_axes("[[1, 0, 0], [0, 1, 0], [0, 0, -1]]"), "axes", "right-handed");
  expect_error(with_axes("[[1, 0, 0], [1, 0, 0], [0, 0, 1]]"), "axes", "right-handed");
}

TEST(TaskLoader, DegenerateBox) {
  expect_error(replace(test::kHoleYaml, "max: [-1, 6, 0]}", "max: [-1, 6, -2]}"), "cspace[0].box",
               "degenerate box: min z");
}

TEST(TaskLoader, CoplanarConvexPart) {
  expect_error(replace(test::kHoleYaml, "cspace:\n",
                       "cspace:\n  - convex: {vertices: [[0,0,3],[1,0,3],[0,1,3],[1,1,3]]}\n"),
               "cspace[0].convex.vertices", "non-coplanar");
  expect_error(
      replace(test::kHoleYaml, "cspace:\n", "cspace:\n  - convex: {vertices: [[0,0,3],[1,0,3],[0,1,3]]}\n"),
      "cspace[0].convex.vertices", "at least 4");
}

TEST(TaskLoader, VelocityAngleTooLarge) {
  expect_error(replace(test::kHoleYaml, "theta_v: 0.25", "theta_v: 1.5708"), "uncertainty.theta_v", "< pi/2");
}

TEST(TaskLoader, NegativeFrictionAndBounds) {
  expect_error(replace(test::kHoleYaml, "friction: 0.48", "friction: -0.1"), "friction", ">= 0");
  expect_error(replace(test::kHoleYaml, "eps_p: 0.2", "eps_p: -0.2"), "uncertainty.eps_p", ">= 0");
  expect_error(replace(test::kHoleYaml, "max: [-1, 6, 0]}", "max: [-1, 6, 0], friction: -1}"),
               "cspace[0].box.friction", ">= 0");
}

TEST(TaskLoader, RegionNotOnContactSurface) {
  expect_error(replace(test::kHoleYaml, "[[-4, -3, 0], [-2, -3, 0]]", "[[-4, -3, 0.5], [-2, -3, 0.5]]"),
               "start", "not on the contact surface");
  // A segment whose ends touch the surface but whose middle crosses the hole.
  expect_error(replace(test::kHoleYaml, "[[-4, -3, 0], [-2, -3, 0]]", "[[-3, 0, 0], [3, 0, 0]]"), "start",
               "not on the contact surface");
  expect_error(replace(test::kHoleYaml, "[-1, 1, -2]]}", "[-1, 1, -1.9]]}"), "goal", "");
}

TEST(TaskLoader, StrategyNamingUnknownMotion) {
  expect_error(replace(test::kHoleYaml, "teach: [p2, p1]", "teach: [p2, p3]"), "strategies.teach[1]",
               "unknown motion 'p3'");
}

TEST(TaskLoader, EmptyFreeSpace) {
  const std::string y =
      replace(test::kHoleYaml, "cspace:\n", "cspace:\n  - box: {min: [-7, -7, -3], max: [7, 7, 5]}\n");
  expect_error(y, "bounds", "free space is empty");
}

TEST(TaskLoader, BadName) {
  expect_error(replace(test::kHoleYaml, "name: hole", "name: Hole!"), "name", "[a-z0-9_-]+");
}

TEST(TaskLoader, MissingFile) { EXPECT_THROW(load_task("/nonexistent/task.yaml"), TaskError); }

// Termination sets (docs/task-format.md "terminate"; Buckley §3.1.2 types 2 and 3).
const std::string kP1 = "p1: {spring: [0, 0, -2.4]}";

TEST(TaskLoader, ReadsTerminationSets) {
  const std::string y = replace(test::kHoleYaml, kP1,
                                "p1:\n    spring: [0, 0, -2.4]\n    terminate:\n"
                                "      position: {box: {min: [-1, -1, -2.1], max: [1, 1, -1.9]}}\n"
                                "      force: {direction: [0, 0, 2], angle: 0.3}");
  auto task = load_task_from_string(y, "t.yaml");
  const MotionTermination& t = task->task.find_motion("p1")->terminate;
  ASSERT_EQ(t.position.size(), 1u);
  EXPECT_EQ(t.position[0].min, Vec3(-1, -1, -2.1));
  EXPECT_EQ(t.position[0].max, Vec3(1, 1, -1.9));
  ASSERT_EQ(t.force.size(), 1u);
  EXPECT_EQ(t.force[0].direction, Vec3(0, 0, 1));  // normalized
  EXPECT_DOUBLE_EQ(t.force[0].angle, 0.3);
  EXPECT_TRUE(t.any());
  EXPECT_FALSE(task->task.find_motion("p2")->terminate.any());  // not given: sticking only
}

TEST(TaskLoader, TerminationSetsMayBeLists) {
  const std::string y = replace(test::kHoleYaml, kP1,
                                "p1:\n    spring: [0, 0, -2.4]\n    terminate:\n      position:\n"
                                "        - box: {min: [-1, -1, -2.1], max: [1, 1, -1.9]}\n"
                                "        - box: {min: [2, -1, -0.1], max: [3, 1, 0.1]}\n      force:\n"
                                "        - {direction: [0, 0, 1], angle: 0.3}\n"
                                "        - {direction: [1, 0, 0], angle: 1.5707963267948966}");
  auto task = load_task_from_string(y, "t.yaml");
  const MotionTermination& t = task->task.find_motion("p1")->terminate;
  EXPECT_EQ(t.position.size(), 2u);
  EXPECT_EQ(t.force.size(), 2u);
}

TEST(TaskLoader, PlanarTerminationBoxSpansTheClipSlab) {
  // In 2-D the box is [x, z]; its y range is the planar clip slab, like `bounds` (task_loader.h).
  const std::string planar = R"(
name: planar_t
dimension: 2
friction: 0.25
uncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.25, theta_f: 0.1}
cspace: []
bounds: {min: [-4, 0], max: [4, 3]}
start: {point: [-2, 0]}
goal: {point: [2, 0]}
motions:
  v1: {damper: [1, -0.2], terminate: {position: {box: {min: [1, -1], max: [3, 1]}}, force: {direction: [0, 1], angle: 0.5}}}
)";
  auto task = load_task_from_string(planar, "planar.yaml");
  const MotionTermination& t = task->task.find_motion("v1")->terminate;
  ASSERT_EQ(t.position.size(), 1u);
  EXPECT_EQ(t.position[0].min, Vec3(1, -kPlanarClipHalfDepth, -1));
  EXPECT_EQ(t.position[0].max, Vec3(3, kPlanarClipHalfDepth, 1));
  EXPECT_EQ(t.force.at(0).direction, Vec3(0, 0, 1));
}

TEST(TaskLoader, BadTerminationSets) {
  const auto with = [](const std::string& terminate) {
    return replace(test::kHoleYaml, kP1, "p1: {spring: [0, 0, -2.4], terminate: " + terminate + "}");
  };
  expect_error(with("{positon: {box: {min: [0, 0, 0], max: [1, 1, 1]}}}"), "motions.p1.terminate.positon",
               "unknown key (allowed here: force, position)");
  expect_error(with("{}"), "motions.p1.terminate", "give position");
  expect_error(with("{position: {box: {min: [0, 0, 0], max: [1, 0, 1]}}}"),
               "motions.p1.terminate.position.box", "degenerate box: min y = 0 must be < max y = 0");
  expect_error(with("{position: {sphere: 1}}"), "motions.p1.terminate.position.sphere", "unknown key");
  expect_error(with("{position: []}"), "motions.p1.terminate.position", "the list is empty");
  expect_error(
      with("{position: [{box: {min: [0, 0, 0], max: [1, 1, 1]}}, {box: {min: [0, 0], max: [1, 1]}}]}"),
      "motions.p1.terminate.position[1].box.min", "expected 3 numbers");
  expect_error(with("{force: {direction: [0, 0, 1], angle: 0}}"), "motions.p1.terminate.force.angle",
               "must be in (0, pi/2]");
  expect_error(with("{force: {direction: [0, 0, 1], angle: 1.6}}"), "motions.p1.terminate.force.angle",
               "must be in (0, pi/2]");
  expect_error(with("{force: {direction: [0, 0, 1], angle: -0.1}}"), "motions.p1.terminate.force.angle",
               "must be in (0, pi/2]");
  expect_error(with("{force: {direction: [0, 0, 0], angle: 0.2}}"), "motions.p1.terminate.force.direction",
               "zero vector");
  expect_error(with("{force: {direction: [0, 0, 1]}}"), "motions.p1.terminate.force.angle",
               "missing required key");
  expect_error(with("{force: {direction: [0, 0, 1], angle: 0.2, axis: 1}}"),
               "motions.p1.terminate.force.axis", "unknown key");
  expect_error(with("null"), "motions.p1.terminate", "expected a mapping");
  expect_error(replace(test::kHoleYaml, kP1, "p1: {terminate: {force: {direction: [0, 0, 1], angle: 0.2}}}"),
               "motions.p1", "exactly one of spring, damper");
  expect_error(replace(test::kHoleYaml, kP1, "p1: {spring: [0, 0, -2.4], damper: [0, 0, 1]}"), "motions.p1",
               "exactly one of spring, damper");
}

TEST(TaskLoader, PlanarTask) {
  const std::string planar = R"(
name: planar_step
dimension: 2
friction: 0.25
uncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.25, theta_f: 0.1}
cspace:
  - box: {min: [-4, -2], max: [0, 0]}
  - box: {min: [0, -2], max: [4, -1]}
bounds: {min: [-4, -2], max: [4, 3]}
start: {point: [-2, 0]}
goal: {point: [2, -1]}
motions:
  v1: {damper: [1, -1]}
strategies:
  s: [v1]
)";
  auto task = load_task_from_string(planar, "planar.yaml");
  const CSpace& c = task->cspace;
  // Polygonal free space: top wall, left wall, right wall, step top (z=0), step riser (x=0), floor (z=-1).
  EXPECT_EQ(c.faces().size(), 6u);
  EXPECT_EQ(c.edges().size(), 6u);  // the polygon's corners, extruded along y
  EXPECT_EQ(c.vertices().size(), 0u);
  for (const Face& f : c.faces()) EXPECT_NEAR(f.normal.y(), 0.0, 1e-15);
}

}  // namespace
}  // namespace cmt
