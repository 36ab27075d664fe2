// End-to-end tests of `cmt rollout` and `cmt calibrate-friction`: JSON fields of docs/contracts.md, exit
// statuses, bad input, and results independent of the thread count.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "sim/mjcf_export.h"
#include "tests/experiments/cmt_runner.h"

namespace {

using cmt::test::Result;
using cmt::test::run;
using cmt::test::task;

TEST(CmtRollout, HoleTeachReportsTheContractFields) {
  const Result r = run("rollout " + task("hole") + " --strategy teach -n 8 --seed 3 --threads 2 --json");
  ASSERT_EQ(r.status, 0) << r.out;  // every rollout succeeded
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["rollouts"], 8);
  EXPECT_EQ(j["successes"], 8);
  EXPECT_EQ(j["unstable"], 0);
  ASSERT_EQ(j["outcomes"].size(), 8u);
  for (const auto& o : j["outcomes"]) {
    for (const char* key : {"start", "end", "atom", "termination", "success"})
      EXPECT_TRUE(o.contains(key)) << key;
    EXPECT_EQ(o["start"].size(), 3u);
    EXPECT_EQ(o["end"].size(), 3u);
    EXPECT_EQ(o["termination"], "sticking");
    EXPECT_EQ(o["kind"], "face");
    EXPECT_TRUE(o["success"].get<bool>());
    EXPECT_EQ(o["motions"].size(), 2u);
  }
}

TEST(CmtRollout, TooDeepFailsSomewhereAndExitsWithOne) {
  const Result r = run("rollout " + task("hole") + " --strategy teach_too_deep -n 30 --seed 1 --json");
  ASSERT_EQ(r.status, 1) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_LT(j["successes"].get<int>(), 30);
}

TEST(CmtRollout, OutcomesDoNotDependOnTheThreadCount) {
  const std::string base =
      "rollout " + task("hole") + " --strategy teach -n 6 --seed 11 --mode extreme --json";
  const auto a = nlohmann::json::parse(run(base + " --threads 1").out);
  const auto b = nlohmann::json::parse(run(base + " --threads 2").out);
  EXPECT_EQ(a["outcomes"].dump(), b["outcomes"].dump());
  EXPECT_EQ(a["mode"], "extreme");
}

TEST(CmtRollout, WritesCsvAndTrajectories) {
  const auto dir = std::filesystem::temp_directory_path() / ("cmt_rollout_cli_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto csv = dir / "r.csv", traj = dir / "t.csv";
  const Result r = run("rollout " + task("hole") + " --strategy teach -n 2 --seed 1 --csv " + csv.string() +
                       " --trajectories " + traj.string() + " --json");
  ASSERT_EQ(r.status, 0);
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("rollout,success,unstable,start_x", 0), 0u) << header;
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 4);  // 2 rollouts x 2 motions
  std::ifstream t(traj);
  int points = 0;
  while (std::getline(t, line)) ++points;
  EXPECT_GT(points, 100);
  std::filesystem::remove_all(dir);
}

TEST(CmtRollout, BadInputExitsWithTwoAndNamesTheKey) {
  struct Case {
    std::string args, key;
  };
  const std::vector<Case> cases = {
      {"--strategy nope -n 5", "strategies"},
      {"--strategy teach -n 0", "-n"},
      {"--strategy teach -n -3", "-n"},
      {"--strategy teach -n 5 --mode sideways", "--mode"},
      {"--strategy teach -n 5 --controller magic", "--controller"},
      {"--strategy teach -n 5 --threads -1", "--threads"},
  };
  for (const Case& c : cases) {
    const Result r = run("rollout " + task("hole") + " " + c.args + " --json");
    EXPECT_EQ(r.status, 2) << c.args;
    EXPECT_NE(r.out.find(c.key), std::string::npos) << c.args << ": " << r.out;
  }
  // The position-controller form implements springs only: a damper strategy is bad input.
  const Result d =
      run("rollout " + task("two_blocks") + " --strategy slide -n 2 --controller position --json");
  EXPECT_EQ(d.status, 2);
  EXPECT_NE(d.out.find("motions.v2"), std::string::npos) << d.out;
}

// The calibration passes in the rollouts' scene (exit 0) and reports every criterion; that the stiff scene
// fails it at the concave edge is Calibration.StiffSceneFailsOnlyAtTheConcaveEdge (tests/sim).
TEST(CmtCalibrateFriction, ReportsTheCriteria) {
  const Result r = run("calibrate-friction --json");
  EXPECT_EQ(r.status, 0);
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"cases", "agree", "passed", "max_creep", "max_loading_creep", "max_speed_error",
                          "max_penetration", "scene", "timestep"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_GT(j["cases"].size(), 200u);
  EXPECT_TRUE(j["cases"][0].contains("loading_creep"));
  EXPECT_TRUE(j["agree"].get<bool>());
  EXPECT_TRUE(j["passed"].get<bool>());
  EXPECT_EQ(j["scene"], "rollout");
  EXPECT_EQ(j["timestep"], cmt::kSoftLayerTimestep);

  EXPECT_EQ(run("calibrate-friction --scene bogus --json").status, 2);
  EXPECT_EQ(run("calibrate-friction --soft-layer --scene stiff --json").status, 2);
}

}  // namespace
