// `cmt plan --states` end to end (docs/planner.md): Table 6.3's cube row, the hole's atom counts with the
// table's sensing errors, and bad input.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/experiments/cmt_runner.h"

namespace cmt::test {
namespace {

TEST(CmtPlan, CubeStatesAreTable63sRow) {
  const Result r = run("plan " + task("cube") + " --states --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["atoms"], 26);
  EXPECT_EQ(j["faces"], 6);
  EXPECT_EQ(j["primitive_states"], 258);
  EXPECT_EQ(j["by_size"]["1"], 26);
  EXPECT_EQ(j["by_size"]["1"].get<int>() + j["by_size"]["2"].get<int>(), 122);
  EXPECT_FALSE(j["truncated"].get<bool>());
  const auto three =
      nlohmann::json::parse(run("plan " + task("cube") + " --states --max-atoms 3 --json").out);
  EXPECT_EQ(three["primitive_states"], 226);
  const auto listed =
      nlohmann::json::parse(run("plan " + task("cube") + " --states --max-atoms 1 --list --json").out);
  ASSERT_EQ(listed["states"].size(), 26u);
  EXPECT_EQ(listed["states"][0].size(), 1u);
  const auto capped =
      nlohmann::json::parse(run("plan " + task("cube") + " --states --max-states 10 --json").out);
  EXPECT_TRUE(capped["truncated"].get<bool>());
  EXPECT_EQ(capped["primitive_states"], 10);
}

TEST(CmtPlan, HoleWithTable63sErrorsHasTheThesissAtomCounts) {
  const Result r =
      run("plan " + task("hole") + " --states --friction 0.25 --theta-f 0.3 --max-atoms 1 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["faces"], 14);
  EXPECT_EQ(j["atoms"], 66);
  EXPECT_EQ(j["friction"], 0.25);
  EXPECT_EQ(j["theta_f"], 0.3);
  EXPECT_EQ(j["primitive_states"], 66);
}

TEST(CmtPlan, WithoutStatesOrWithABadOverrideItIsBadInput) {
  EXPECT_EQ(run("plan " + task("cube") + " --json").status, 2);
  const Result r = run("plan " + task("cube") + " --states --theta-f 4 --json");
  EXPECT_EQ(r.status, 2);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["error"]["key"], "uncertainty.theta_f");
}

}  // namespace
}  // namespace cmt::test
