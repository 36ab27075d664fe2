// Model error (models/model_error.h; docs/task-format.md "model_error"): affine coordinates, validation with
// the key named, slices and critical values.
#include "models/model_error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>

#include "models/loaded_task.h"
#include "models/task_error.h"
#include "models/task_loader.h"

namespace cmt {
namespace {

// Donald's Example (1) in 3-D (models/tasks/step_offset.yaml, trimmed): B moves with alpha.
const char* kStepYaml = R"(
name: step
units: in
friction: 0.5
model_error:
  alpha: {interval: [-1, 1], nominal: 0.5}
uncertainty: {eps_s: 0.2, eps_p: 0.2, theta_v: 0.1, theta_f: 0.35}
cspace:
  - box: {min: [-4, -3, 0], max: [0, 3, 2]}
  - box: {min: [alpha, -3, 0], max: [alpha + 3, 3, 2]}
bounds: {min: [-6, -3, 0], max: [6, 3, 6]}
start: {point: [1.5, 0, 2]}
goal: {polygon: [[0, -3, 0], [0, 3, 0], [0, 3, 2], [0, -3, 2]]}
motions: {left: {damper: [-1, 0, -0.2]}}
strategies: {edr: [left]}
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void expect_error(const std::string& yaml, const std::string& key, const std::string& reason) {
  try {
    parse_task_string(yaml, "bad.yaml");
    ADD_FAILURE() << "no error; expected key '" << key << "'";
  } catch (const TaskError& e) {
    EXPECT_EQ(e.file(), "bad.yaml");
    EXPECT_NE(e.key().find(key), std::string::npos) << e.what();
    EXPECT_NE(e.reason().find(reason), std::string::npos) << e.what();
  }
}

TEST(ModelError, ParsesAffineExpressions) {
  const std::vector<ModelParameter> params = {{"w", 0, 1, 0.5, {}}, {"d", 0, 1, 0.5, {}}};
  const AffineValue a = parse_affine("-0.5*w + 2*d - 1", params);
  EXPECT_DOUBLE_EQ(a.constant, -1);
  EXPECT_EQ(a.coefficients, (std::vector<double>{-0.5, 2}));
  EXPECT_DOUBLE_EQ(parse_affine("w*3 - d", params).at({1, 2}), 1);
  EXPECT_DOUBLE_EQ(parse_affine("1e-1 + w", params).at({0.2, 0}), 0.3);
  EXPECT_DOUBLE_EQ(parse_affine("2*-w", params).at({1, 0}), -2);
  EXPECT_DOUBLE_EQ(parse_affine("2.e-3*w + 1E+1", params).at({1000, 0}), 12);
  EXPECT_DOUBLE_EQ(parse_affine(".5e1 - d", params).at({0, 1}), 4);
  const std::vector<ModelParameter> named = {{"w2e", 0, 1, 0.5, {}}};
  EXPECT_DOUBLE_EQ(parse_affine("w2e-1", named).at({3}), 2);  // a name ending in "2e" is not a mantissa
  EXPECT_DOUBLE_EQ(parse_affine(" -w ", params).at({0.25, 0}), -0.25);
  EXPECT_THROW(parse_affine("w + x", params), std::invalid_argument);
  EXPECT_THROW(parse_affine("w + ", params), std::invalid_argument);
  EXPECT_THROW(parse_affine("w * d", params), std::invalid_argument);
  EXPECT_THROW(parse_affine("", params), std::invalid_argument);
}

TEST(ModelError, ReadsTheNominalSliceAndOthers) {
  const Task nominal = parse_task_string(kStepYaml, "step.yaml");
  ASSERT_EQ(nominal.model_error.size(), 1u);
  EXPECT_EQ(nominal.model_error[0].name, "alpha");
  EXPECT_EQ(nominal.model_values, (std::vector<double>{0.5}));
  EXPECT_DOUBLE_EQ(nominal.cspace[1].box.min.x(), 0.5);
  EXPECT_DOUBLE_EQ(nominal.cspace[1].box.max.x(), 3.5);
  const Task slice = task_at(nominal, {-0.75});
  EXPECT_DOUBLE_EQ(slice.cspace[1].box.min.x(), -0.75);
  EXPECT_DOUBLE_EQ(slice.cspace[1].box.max.x(), 2.25);
  EXPECT_DOUBLE_EQ(slice.cspace[0].box.max.x(), 0);  // A does not move
  EXPECT_THROW(task_at(nominal, {1.5}), TaskError);  // outside the interval
  EXPECT_THROW(task_at(nominal, {}), TaskError);     // one value per parameter
}

TEST(ModelError, TheDefaultNominalIsTheMidpoint) {
  const Task t = parse_task_string(
      replaced(kStepYaml, "alpha: {interval: [-1, 1], nominal: 0.5}", "alpha: [0.2, 1]"), "step.yaml");
  EXPECT_DOUBLE_EQ(t.model_error[0].nominal, 0.6);
  EXPECT_DOUBLE_EQ(t.cspace[1].box.min.x(), 0.6);
}

TEST(ModelError, BadModelErrorNamesTheKey) {
  expect_error(replaced(kStepYaml, "[-1, 1]", "[1, -1]"), "model_error.alpha.interval", "must be <=");
  expect_error(replaced(kStepYaml, "[-1, 1]", "[-1, 1, 2]"), "model_error.alpha.interval", "[min, max]");
  expect_error(replaced(kStepYaml, "nominal: 0.5", "nominal: 2"), "model_error.alpha.nominal", "must lie in");
  expect_error(replaced(kStepYaml, "alpha: {", "Alpha: {"), "model_error.Alpha", "must match");
  expect_error(replaced(kStepYaml, "max: [alpha + 3,", "max: [beta + 3,"), "cspace[1].box.max[0]",
               "unknown model parameter 'beta'");
  // Only parts, bounds and goal regions may move: the start and the motions are the robot's own.
  expect_error(replaced(kStepYaml, "point: [1.5, 0, 2]", "point: [alpha + 1, 0, 2]"), "start.point[0]",
               "only parts, bounds and goal regions");
  expect_error(replaced(kStepYaml, "damper: [-1, 0, -0.2]", "damper: [-1, 0, alpha]"), "motions.left.damper",
               "only parts, bounds and goal regions");
  // Without model_error an expression is not a number.
  std::string no_model =
      replaced(kStepYaml, "model_error:\n  alpha: {interval: [-1, 1], nominal: 0.5}\n", "");
  expect_error(no_model, "cspace[1].box.min[0]", "expected a number");
}

// A discrete parameter (Donald's twin universe, J = {1, 2}): each value is a world; slices take them all at
// any resolution, with no critical values between them, and other values are not worlds.
TEST(ModelError, ADiscreteParameterSlicesAtItsValues) {
  const std::string yaml =
      replaced(kStepYaml, "alpha: {interval: [-1, 1], nominal: 0.5}", "alpha: {values: [-1, 0.5, 1]}");
  const Task t = parse_task_string(yaml, "step.yaml");
  ASSERT_TRUE(t.model_error[0].discrete());
  EXPECT_EQ(t.model_error[0].nominal, -1);  // the first value unless the file gives one
  EXPECT_EQ(t.model_error[0].min, -1);
  EXPECT_EQ(t.model_error[0].max, 1);
  EXPECT_DOUBLE_EQ(t.cspace[1].box.min.x(), -1);
  EXPECT_TRUE(critical_values(t, 0).empty());  // alpha = 0 is no world
  for (int resolution : {1, 2, 5, 40})
    EXPECT_EQ(slice_values(t, 0, resolution), (std::vector<double>{-1, 0.5, 1})) << resolution;
  EXPECT_DOUBLE_EQ(task_at(t, {0.5}).cspace[1].box.min.x(), 0.5);
  EXPECT_THROW(task_at(t, {0.0}), TaskError);  // inside [min, max] but not a value
  EXPECT_TRUE(t.model_error[0].admits(0.5));
  EXPECT_FALSE(t.model_error[0].admits(0.25));
  const Task nominal =
      parse_task_string(replaced(yaml, "[-1, 0.5, 1]}", "[-1, 0.5, 1], nominal: 1}"), "s.yaml");
  EXPECT_EQ(nominal.model_values, (std::vector<double>{1}));
}

TEST(ModelError, BadDiscreteParameterNamesTheKey) {
  const std::string yaml =
      replaced(kStepYaml, "alpha: {interval: [-1, 1], nominal: 0.5}", "alpha: {values: [-1, 1], nominal: 1}");
  expect_error(replaced(yaml, "[-1, 1]", "[1, -1]"), "model_error.alpha.values", "values must increase");
  expect_error(replaced(yaml, "[-1, 1]", "[1, 1]"), "model_error.alpha.values", "values must increase");
  expect_error(replaced(yaml, "[-1, 1]", "[]"), "model_error.alpha.values", "empty");
  expect_error(replaced(yaml, "nominal: 1", "nominal: 0"), "model_error.alpha.nominal", "one of the values");
  expect_error(replaced(yaml, "nominal: 1", "interval: [-1, 1]"), "model_error.alpha.interval",
               "unknown key");
}

TEST(ModelError, ADegenerateSliceIsATaskError) {
  // B's width is alpha + 1 - alpha... make it shrink to nothing at alpha = 1.
  const Task t =
      parse_task_string(replaced(kStepYaml, "max: [alpha + 3, 3, 2]", "max: [1, 3, 2]"), "step.yaml");
  EXPECT_THROW(task_at(t, {1.0}), TaskError);
  EXPECT_NO_THROW(task_at(t, {0.0}));
}

TEST(ModelError, CriticalValuesAreWhereCoordinatesMeet) {
  const Task t = parse_task_string(kStepYaml, "step.yaml");
  // B's left face x = alpha meets A's right face (and the goal's plane) x = 0 at alpha = 0; alpha + 3 meets
  // nothing inside (-1, 1).
  EXPECT_EQ(critical_values(t, 0), (std::vector<double>{0.0}));
  EXPECT_EQ(slice_values(t, 0, 5), (std::vector<double>{-1, -0.5, 0, 0.5, 1}));
  // With 2 values per parameter the critical value and the midpoints either side of it are added.
  EXPECT_EQ(slice_values(t, 0, 2), (std::vector<double>{-1, -0.5, 0, 0.5, 1}));
  EXPECT_EQ(slice_values(t, 0, 1), (std::vector<double>{-0.5, 0, 0.5}));
  EXPECT_EQ(model_slices(t, 3).size(), 5u);  // -1, -0.5, 0, 0.5, 1
}

TEST(ModelError, SlicesCoverEveryParameter) {
  const std::string two = replaced(replaced(kStepYaml, "alpha: {interval: [-1, 1], nominal: 0.5}",
                                            "alpha: {interval: [0.25, 1], nominal: 0.5}\n  h: [1, 3]"),
                                   "max: [alpha + 3, 3, 2]", "max: [alpha + 3, 3, h]");
  const Task t = parse_task_string(two, "step.yaml");
  ASSERT_EQ(t.model_error.size(), 2u);
  EXPECT_TRUE(critical_values(t, 0).empty());
  EXPECT_EQ(critical_values(t, 1), (std::vector<double>{2.0}));  // B's top meets A's at h = 2
  const auto slices = model_slices(t, 3);
  EXPECT_EQ(slices.size(), 3u * 5u);  // alpha: .25 .625 1; h: 1 1.5 2 2.5 3
  EXPECT_EQ(slices.front(), (std::vector<double>{0.25, 1}));
  EXPECT_EQ(slices.back(), (std::vector<double>{1, 3}));
}

// Physical parts: the C-obstacles are the environment grown by the robot, so B's C-obstacle [w - .5, w + 3.5]
// meets A's [-4.5, .5] where the robot stops fitting between them, at w = 1 (the raw part coordinates meet
// at w = 0, outside the interval).
TEST(ModelError, PhysicalTasksCompareCObstacleCoordinates) {
  const Task t = parse_task_string(R"(
name: fit
units: in
model_error: {w: [0.5, 2]}
uncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.1, theta_f: 0.1}
robot: [{box: {min: [-0.5, -0.5, 0], max: [0.5, 0.5, 1]}}]
environment:
  - box: {min: [-4, -3, -1], max: [0, 3, 0]}
  - box: {min: [w, -3, -1], max: [w + 3, 3, 0]}
bounds: {min: [-6, -3, -2], max: [6, 3, 4]}
start: {point: [-2, 0, 0]}
goal: {point: [-2, 0, 0]}
)",
                                   "fit.yaml");
  const std::vector<double> critical = critical_values(t, 0);
  EXPECT_NE(std::find(critical.begin(), critical.end(), 1.0), critical.end());
}

TEST(ModelError, ASliceMayLoseItsGoalButNotItsStart) {
  const Task t = parse_task_string(kStepYaml, "step.yaml");
  // At alpha = 0 the blocks touch and A's right face (the goal) is gone: a slice without goal loads.
  EXPECT_NO_THROW(load_task_slice(t, {0.0}));
  EXPECT_NO_THROW(load_task_slice(t, {-1.0}));
  // The whole task at such a value does not (its goal is off the surface).
  EXPECT_THROW(load_task_from_string(replaced(kStepYaml, "nominal: 0.5", "nominal: 0"), "step.yaml"),
               TaskError);
  // With model error the nominal goal may lie partly off the surface (hole_width gives the widest hole's
  // bottom): the part on a face counts; none at all is an error naming the goal.
  const std::string hole = std::string(CMT_SOURCE_DIR) + "/models/tasks/hole_width.yaml";
  EXPECT_NO_THROW(load_task(hole));
  const std::string closed = replaced(read_file(hole), "nominal: 2}", "nominal: 0.75}");
  try {
    load_task_from_string(closed, "closed.yaml");
    ADD_FAILURE() << "a goal nowhere on the surface loaded";
  } catch (const TaskError& e) {
    EXPECT_EQ(e.key(), "goal") << e.what();
  }
  // The start must stay on the surface: on B's top only while B is under it.
  const Task far =
      parse_task_string(replaced(kStepYaml, "point: [1.5, 0, 2]", "point: [3.2, 0, 2]"), "s.yaml");
  EXPECT_NO_THROW(load_task_slice(far, {0.5}));
  EXPECT_THROW(load_task_slice(far, {-0.5}), TaskError);
}

}  // namespace
}  // namespace cmt
