// Accepted numeric ranges and sizes (models/task_ranges.h, docs/task-format.md "Accepted ranges and sizes"),
// and the YAML document rules (models/yaml_document.h): every rejected input names the file, the key and the
// reason; what is accepted loads.
#include "models/task_ranges.h"

#include <gtest/gtest.h>

#include <cmath>

#include "models/loaded_task.h"
#include "models/task_error.h"
#include "models/yaml_document.h"
#include "tests/models/test_tasks.h"

namespace cmt {
namespace {

using test::replace;

TaskError load_error(const std::string& yaml) {
  try {
    load_task_from_string(yaml, "t.yaml");
  } catch (const TaskError& e) {
    EXPECT_EQ(e.file(), "t.yaml");
    return e;
  }
  ADD_FAILURE() << "no error";
  return TaskError("", "", "");
}

void expect_rejected(const std::string& yaml, const std::string& key, const std::string& reason_part) {
  const TaskError e = load_error(yaml);
  EXPECT_EQ(e.key(), key) << e.what();
  EXPECT_NE(e.reason().find(reason_part), std::string::npos) << e.what();
}

// A damper straight down onto a slab; `box` is the slab's C-space box.
std::string slab_task(const std::string& box) {
  return "name: slab\nuncertainty: {eps_s: 0.02, eps_p: 0.02, theta_v: 0.05, theta_f: 0.05}\n"
         "cspace: [{box: " +
         box +
         "}]\nbounds: {min: [-2, -2, -2], max: [2, 2, 2]}\nstart: {point: [0, 0, 0]}\n"
         "goal: {point: [0.5, 0, 0]}\nmotions: {m: {damper: [0, 0, -1]}}\nstrategies: {s: [m]}\n";
}

TEST(TaskRanges, SubnormalThinPartIsRejected) {
  // The box below underflows every product of its sides (its face normals became NaN downstream).
  expect_rejected(slab_task("{min: [-1, -1, -1e-320], max: [1, 1, 0]}"), "cspace[0].box", "thick");
  // Below 1e-5 of the scene size (the bounds' diagonal 4 sqrt 3 = 6.93): 5e-5 is too thin, 1e-4 loads.
  expect_rejected(slab_task("{min: [-1, -1, -5e-5], max: [1, 1, 0]}"), "cspace[0].box", "thick");
  EXPECT_NO_THROW(load_task_from_string(slab_task("{min: [-1, -1, -1e-4], max: [1, 1, 0]}"), "t.yaml"));
}

TEST(TaskRanges, PartWidthOfATetrahedron) {
  // The corner tetrahedron's slimmest slab lies on its slanted facet x + y + z = 1, 1/sqrt 3 from the origin.
  ConvexPart tetra;
  tetra.shape = ConvexPart::Shape::kConvex;
  tetra.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  EXPECT_NEAR(part_width(tetra, 3), 1 / std::sqrt(3.0), 1e-12);
  // In the x, z plane of a planar task the triangle (0,0), (1,0), (0,1) is 1/sqrt 2 wide.
  EXPECT_NEAR(part_width(tetra, 2), 1 / std::sqrt(2.0), 1e-12);
  tetra.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};  // flat
  EXPECT_EQ(part_width(tetra, 3), 0.0);
}

TEST(TaskRanges, HugeCoordinatesAreRejectedWhereTheyAre) {
  expect_rejected(replace(test::kHoleYaml, "max: [6, 6, 4]", "max: [6, 6, 1e308]"), "bounds.max[2]",
                  "exceeds the largest accepted coordinate");
  expect_rejected(replace(test::kHoleYaml, "p1: {spring: [0, 0, -2.4]}", "p1: {spring: [1e200, 0, 0]}"),
                  "motions.p1.spring[0]", "exceeds the largest accepted coordinate");
  // Within the coordinate range but 5.5e3 scene sizes (18) away: a spring that far is a damper.
  expect_rejected(replace(test::kHoleYaml, "p1: {spring: [0, 0, -2.4]}", "p1: {spring: [1e5, 0, 0]}"),
                  "motions.p1.spring", "scene sizes");
  EXPECT_NO_THROW(load_task_from_string(
      replace(test::kHoleYaml, "p1: {spring: [0, 0, -2.4]}", "p1: {spring: [1e4, 0, 0]}"), "t.yaml"));
}

TEST(TaskRanges, ErrorBoundsBeyondTheSceneAreRejected) {
  expect_rejected(replace(test::kHoleYaml, "eps_s: 0.2", "eps_s: 1e308"), "uncertainty.eps_s",
                  "exceeds the scene size");
  expect_rejected(replace(test::kHoleYaml, "eps_p: 0.2", "eps_p: 19"), "uncertainty.eps_p",
                  "exceeds the scene size");
  expect_rejected(replace(test::kHoleYaml, "theta_f: 0.05}", "theta_f: 0.05, step: 1e-9}"),
                  "uncertainty.step", "below");
}

TEST(TaskRanges, PerfectPositioningGetsAStepFromTheScene) {
  // Bounds (-6..6, -6..6, -2..4): diagonal 18; the default step is 1 % of it.
  const auto task = load_task_from_string(
      replace(replace(test::kHoleYaml, "eps_s: 0.2", "eps_s: 0"), "eps_p: 0.2", "eps_p: 0"), "t.yaml");
  EXPECT_DOUBLE_EQ(task->task.uncertainty.step, 0.18);
  EXPECT_DOUBLE_EQ(load_task_from_string(test::kHoleYaml, "t.yaml")->task.uncertainty.step, 0.2);
}

TEST(TaskRanges, FrictionAndDirections) {
  expect_rejected(replace(test::kHoleYaml, "friction: 0.48", "friction: 1e300"), "friction", "exceeds 100");
  expect_rejected(replace(test::kHoleYaml, "p2: {spring: [1.4, 0, -1]}", "p2: {damper: [1e-320, 0, 0]}"),
                  "motions.p2.damper", "zero vector");
}

TEST(TaskRanges, SceneFarFromTheOrigin) {
  // A scene 3e-3 across, 1e6 from the origin: 3.3e8 scene sizes off (doubles there resolve 1e-10, which is
  // not below its contact tolerance of 3e-9 by the margin the limit keeps).
  const std::string far =
      "name: far\nuncertainty: {eps_s: 0, eps_p: 0, theta_v: 0.05, theta_f: 0.05}\n"
      "cspace: []\nbounds: {min: [999998, -1e-3, -1e-3], max: [999998.001, 1e-3, 1e-3]}\n"
      "start: {point: [999998, 0, 0]}\ngoal: {point: [999998.001, 0, 0]}\n";
  expect_rejected(far, "bounds", "from the origin");
}

TEST(TaskRanges, SizeLimits) {
  std::string motions = "motions:\n";
  for (std::size_t i = 0; i <= kMaxMotions; ++i)
    motions += "  m" + std::to_string(i) + ": {damper: [0, 0, -1]}\n";
  expect_rejected(
      replace(test::kHoleYaml,
              "motions:\n  p1: {spring: [0, 0, -2.4]}\n  p2: {spring: [1.4, 0, -1]}\nstrategies:\n"
              "  teach: [p2, p1]\n",
              motions),
      "motions", "too many motions");
  std::string list = "[p1";
  for (std::size_t i = 0; i < kMaxStrategyNodes; ++i) list += ", p1";
  expect_rejected(replace(test::kHoleYaml, "teach: [p2, p1]", "teach: " + list + "]"),
                  "strategies.teach[1000]", "too many motions in one strategy");
}

TEST(YamlDocument, SyntaxErrorNamesKeyAndPlace) {
  try {
    load_task_from_string("name: x\nuncertainty:\n  eps_s: [1, 2\n  eps_p: 3\n", "t.yaml");
    ADD_FAILURE() << "no error";
  } catch (const TaskError& e) {
    // yaml-cpp notices the unclosed list where the next key starts.
    EXPECT_EQ(e.key(), "uncertainty.eps_p") << e.what();
    EXPECT_EQ(e.where().line, 4) << e.what();
    EXPECT_NE(std::string(e.what()).find("line "), std::string::npos);
    EXPECT_NE(e.reason().find("malformed YAML"), std::string::npos);
  }
  EXPECT_EQ(enclosing_key_path("a:\n  b:\n    - c: 1\n      d: [\n  e: 2\n", 4), "a.b.d");
  EXPECT_EQ(enclosing_key_path("a:\n  b:\n    - c: 1\n      d: [\n  e: 2\n", 5), "a.e");
  EXPECT_EQ(enclosing_key_path("[1, 2\n", 1), "");
}

TEST(YamlDocument, DeepNestingAndSecondDocumentAreNamed) {
  const std::string deep = "name: x\ndescription: " + std::string(1200, '[') + std::string(1200, ']') + "\n";
  try {
    load_task_from_string(deep, "t.yaml");
    ADD_FAILURE() << "no error";
  } catch (const TaskError& e) {
    EXPECT_EQ(e.key(), "description") << e.what();
    EXPECT_NE(e.reason().find("nested too deeply"), std::string::npos) << e.what();
  }
  expect_rejected(test::kHoleYaml + "---\nname: other\n", "", "more than one YAML document");
  EXPECT_NO_THROW(load_task_from_string("%YAML 1.2\n---\n" + test::kHoleYaml + "...\n# end\n", "t.yaml"));
  EXPECT_EQ(second_document_line("# c\n---\na: 1\n---\nb: 2\n"), 4);
  EXPECT_EQ(second_document_line("a: 1\n...\nb: 2\n"), 3);
  EXPECT_EQ(second_document_line("a: |\n  ---\n  text\n"), 0);  // indented: inside a block scalar
  // A stray comma before the first key made yaml-cpp's LoadAll loop for ever (found by cmt-fuzz).
  expect_rejected(",name: x\nunits: in\n", "", "no value could be read");
}

}  // namespace
}  // namespace cmt
