// `cmt edr` end to end (docs/edr.md) on Donald's Example (1), models/tasks/step_offset.yaml, under the
// rollouts' model: the verdicts, the JSON fields, bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/experiments/cmt_runner.h"

namespace cmt::test {
namespace {

TEST(CmtEdr, StepOffsetEdrIsReliableAndSteepIsNot) {
  const Result edr = run("edr " + task("step_offset") + " --strategy edr --json");
  ASSERT_EQ(edr.status, 0) << edr.out;
  const auto j = nlohmann::json::parse(edr.out);
  EXPECT_TRUE(j["edr_reliable"].get<bool>());
  EXPECT_EQ(j["model"], "rollouts");
  ASSERT_EQ(j["parameters"].size(), 1u);
  EXPECT_EQ(j["parameters"][0]["name"], "alpha");
  EXPECT_EQ(j["parameters"][0]["critical"], nlohmann::json::array({0.0}));
  ASSERT_EQ(j["slices"].size(), 5u);
  for (const auto& s : j["slices"]) {
    const double alpha = s["params"]["alpha"].get<double>();
    EXPECT_EQ(s["goal_empty"].get<bool>(), alpha <= 0) << alpha;
    ASSERT_TRUE(s["terminates"].get<bool>());
    EXPECT_EQ(s["success_area"].get<double>() > 0, alpha > 0) << alpha;
    if (alpha <= 0) EXPECT_GT(s["failure_area"].get<double>(), 0) << alpha;  // H wherever the goal vanishes
    EXPECT_TRUE(s.contains("strong_preimage_area") && s.contains("weak_preimage_area"));
    EXPECT_TRUE(s["distinguishable"].get<bool>());
  }
  EXPECT_TRUE(j["confusions"].empty());

  const Result steep = run("edr " + task("step_offset") + " --strategy steep --json");
  ASSERT_EQ(steep.status, 1) << steep.out;
  const auto k = nlohmann::json::parse(steep.out);
  EXPECT_FALSE(k["edr_reliable"].get<bool>());
  EXPECT_TRUE(k["reaches_goal"].get<bool>());
  ASSERT_FALSE(k["confusions"].empty());
  EXPECT_LE(k["confusions"][0]["distance"].get<double>(), 0.4);
}

TEST(CmtEdr, BadInputExitsTwo) {
  EXPECT_EQ(run("edr " + task("step_offset") + " --strategy nosuch --json").status, 2);
  EXPECT_EQ(run("edr " + task("step_offset") + " --strategy edr --resolution 0 --json").status, 2);
  // A slice whose start leaves the surface: B's top holds x = 3.2 only for alpha >= 0.2.
  std::ifstream in(task("step_offset"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "point: [1.5, 0, 2]";
  text.replace(text.find(from), from.size(), "point: [3.2, 0, 2]");
  const auto path = std::filesystem::temp_directory_path() / "cmt_edr_bad_start.yaml";
  std::ofstream(path) << text;
  const Result r = run("edr " + path.string() + " --strategy edr --json");
  EXPECT_EQ(r.status, 2);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace cmt::test
