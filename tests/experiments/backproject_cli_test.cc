// `cmt backproject` end to end (docs/teaching.md "Backprojections"): the two_blocks chains whose strong
// backprojection holds the start (task file comments: v2 slides from B's top into the gap; v3 may stick on
// B's top, from where v2 slides), the straight-down motion whose base holds B's top, physics from points of
// S, a spring, and bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "tests/experiments/cmt_runner.h"

namespace cmt::test {
namespace {

TEST(CmtBackproject, TwoBlocksChainsHoldTheStartAndDownDoesNot) {
  const Result slide = run("backproject " + task("two_blocks") + " --motions v2 --json");
  ASSERT_EQ(slide.status, 0) << slide.out;
  const auto j = nlohmann::json::parse(slide.out);
  EXPECT_TRUE(j["start_inside"].get<bool>());
  ASSERT_EQ(j["steps"].size(), 1u);
  EXPECT_EQ(j["steps"][0]["motion"], "v2");
  EXPECT_GT(j["steps"][0]["strong_area"].get<double>(), 24);  // B's top and the gap floor, 24 each
  // v1 (straight down, theta_v > atan mu) may stick anywhere on a horizontal face: B's top (the start) is in
  // its base.
  const Result down = run("backproject " + task("two_blocks") + " --motions v1 --json");
  EXPECT_EQ(down.status, 1) << down.out;
  const auto d = nlohmann::json::parse(down.out);
  EXPECT_FALSE(d["start_inside"].get<bool>());
  EXPECT_FALSE(d["start_outside"].empty());
  // The chain (v3, v2): S_v3(S_v2(goal)) holds B's top, where v3 may stop and v2 then slides into the gap.
  const Result chain = run("backproject " + task("two_blocks") + " --motions v3,v2 --json");
  ASSERT_EQ(chain.status, 0) << chain.out;
  const auto c = nlohmann::json::parse(chain.out);
  ASSERT_EQ(c["steps"].size(), 2u);
  EXPECT_EQ(c["steps"][0]["motion"], "v2");  // from the goal backwards
  EXPECT_EQ(c["steps"][1]["motion"], "v3");
  // The forward verifier's verdict from all of S_1 under the rollouts' model, with the pieces it finds
  // outside the goal when it does not certify S_1 (docs/teaching.md: the servo coast is not backprojected).
  ASSERT_TRUE(c["forward"]["reliable"].is_boolean());
  EXPECT_EQ(c["forward"]["reliable"].get<bool>(), c["forward"]["outside_goal"].empty());
}

TEST(CmtBackproject, RolloutsFromPointsOfTheStrongBackprojectionReachTheGoal) {
  const std::string dir = ::testing::TempDir() + "cmt_backproject_check";
  const Result r =
      run("backproject " + task("two_blocks") + " --motions v3,v2 --check 6 --points 8 --seed 5 --json " +
          "--check-dir " + dir + " --view " + dir + "/view");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  const auto& check = j["check"];
  ASSERT_EQ(check["points"].size(), 8u);
  EXPECT_EQ(check["rollouts"], 48);
  EXPECT_EQ(check["failures"], 0);
  EXPECT_EQ(check["outside"], 0);
  EXPECT_EQ(check["successes"].get<int>() + check["unstable"].get<int>(), 48);
  // The 3-D page: per motion B, W(B) and S.
  EXPECT_TRUE(std::filesystem::exists(dir + "/view/index.html"));
  EXPECT_EQ(j["view"], dir + "/view/index.html");
}

// A spring (Buckley §5.4.4, the via-point model): block_shadow's spring below the floor's centre. Its base
// is the jam at the block's far wall (verifier/spring_backprojection_test.cc derives it); the start x = -3
// slides to the centre and lies in S.
TEST(CmtBackproject, SpringStrongBackprojectionHoldsTheStart) {
  const Result r = run("backproject " + task("geometry/block_shadow") + " --motions down --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["start_inside"].get<bool>());
  ASSERT_EQ(j["steps"].size(), 1u);
  EXPECT_EQ(j["steps"][0]["model"], "via-point");
  EXPECT_FALSE(j["steps"][0]["free_rest"].get<bool>());
  EXPECT_GT(j["steps"][0]["base_area"].get<double>(), 0);
  // The room's surface is 8 x 8 x 2 + 8 x 4 x 4 = 256 in^2 plus the block's 5 in^2 of walls and top, less
  // its 1 in^2 footprint: S holds most of it, W at least the block's far wall (1 in^2).
  EXPECT_GT(j["steps"][0]["strong_area"].get<double>(), 150);
  EXPECT_GT(j["steps"][0]["weak_area"].get<double>(), 1);
}

TEST(CmtBackproject, UnknownMotionsAndSensingTerminationAreBadInput) {
  EXPECT_EQ(run("backproject " + task("two_blocks") + " --motions nope --json").status, 2);
  const Result sensing = run("backproject " + task("cube_sensing") + " --motions p1 --json");
  EXPECT_EQ(sensing.status, 2);
  EXPECT_EQ(nlohmann::json::parse(sensing.out)["error"]["key"], "motions.p1.terminate");
}

}  // namespace
}  // namespace cmt::test
