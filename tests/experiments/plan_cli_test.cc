// `cmt plan` end to end (docs/planner.md): Table 6.3's cube row, the hole's atom counts with the table's
// sensing errors, Buckley §6.3.1's one-motion cube plan with the verifier's verdict and rollouts, §6.3.2's
// with position-sensing termination, the cube with position- and force-sensing termination, and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

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

// §6.3.1: start a top edge, goal the bottom, sticking termination: one spring motion below the bottom that
// may stop only on the bottom face; the verifier finds the planned strategy reliable and every rollout
// reaches the goal; -o writes the task with the strategy, which loads.
TEST(CmtPlan, CubeHasAOneMotionPlanThatTheVerifierAndTheRolloutsConfirm) {
  const std::string out = testing::TempDir() + "/cube_planned.yaml";
  const Result r = run("plan " + task("cube") + " --check 40 --threads 2 --json -o " + out);
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j["found"].get<bool>());
  ASSERT_EQ(j["motions"].size(), 1u);
  EXPECT_LT(j["motions"][0]["commanded"][2].get<double>(), -1.0);  // behind the bottom's plane
  EXPECT_GT(j["motions"][0]["depth"].get<double>(), 0.0);
  EXPECT_FALSE(j["motions"][0]["cpositions"].empty());
  EXPECT_TRUE(std::filesystem::path(j["task_file"].get<std::string>()).is_absolute());  // for the report
  EXPECT_TRUE(std::filesystem::equivalent(j["task_file"].get<std::string>(), task("cube")));
  EXPECT_EQ(j["steps"][0]["state"], nlohmann::json::array({"e4"}));    // the top edge y = -1, z = 1
  EXPECT_EQ(j["steps"][0]["targets"], nlohmann::json::array({"f2"}));  // the bottom face
  EXPECT_TRUE(j["decision_free"].get<bool>());
  EXPECT_EQ(j["strategy"], nlohmann::json::array({"planned_1"}));
  EXPECT_TRUE(j["verified"]["reliable"].get<bool>());
  EXPECT_EQ(j["check"]["rollouts"], 40);
  EXPECT_EQ(j["check"]["successes"], 40);
  EXPECT_EQ(j["check"]["outside"], 0);
  const Result v = run("verify " + out + " --strategy planned --json");
  EXPECT_EQ(v.status, 0);
  EXPECT_TRUE(nlohmann::json::parse(v.out)["reliable"].get<bool>());
  // Planning the written task again takes names it does not use yet.
  const auto again = nlohmann::json::parse(run("plan " + out + " --json").out);
  EXPECT_EQ(again["strategy"], nlohmann::json::array({"planned_2_1"}));
  EXPECT_EQ(again["strategy_name"], "planned_2");
}

// §6.3.2: start a bottom edge, goal the interior of the bottom (models/tasks/cube_sensing.yaml: the bottom
// inset by eps_s, which holds no atom's closure), position-sensing termination: one spring motion below the
// bottom with the goal's sensed-position set P_s = the goal shrunk by eps_s, 2 eps_s thick (goal_stops.h);
// it stops only in the goal (a goal stop), the verifier agrees, and in every one of 1000 rollouts it
// reaches the goal, stopped by sensing. -o writes the motion with its `terminate: position` set.
TEST(CmtPlan, CubeSensingHasAOneMotionPlanWithItsSensedPositionSet) {
  const std::string out = testing::TempDir() + "/cube_sensing_planned.yaml";
  const Result r = run("plan " + task("cube_sensing") +
                       " --termination position --check 1000 --seed 7 --threads 2 --json -o " + out);
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j["found"].get<bool>()) << r.out;
  EXPECT_EQ(j["termination"], "position");
  ASSERT_EQ(j["spositions"].size(), 1u);
  const auto& box = j["spositions"][0];
  for (int k = 0; k < 2; ++k) {  // the goal [-.8, .8]^2 shrunk by eps_s (and a margin of ~1e-6 x scale)
    EXPECT_NEAR(box["min"][k].get<double>(), -0.6, 1e-4);
    EXPECT_NEAR(box["max"][k].get<double>(), 0.6, 1e-4);
    EXPECT_LT(box["max"][k].get<double>(), 0.6);
  }
  EXPECT_DOUBLE_EQ(box["min"][2].get<double>(), -1.2);
  EXPECT_DOUBLE_EQ(box["max"][2].get<double>(), -0.8);
  ASSERT_EQ(j["motions"].size(), 1u);
  EXPECT_EQ(j["motions"][0]["spositions"], j["spositions"]);
  EXPECT_LT(j["motions"][0]["commanded"][2].get<double>(), -1.0);    // behind the bottom's plane
  EXPECT_EQ(j["steps"][0]["state"], nlohmann::json::array({"e2"}));  // the bottom edge y = -1
  EXPECT_EQ(j["steps"][0]["targets"], nlohmann::json::array({"goal"}));
  EXPECT_TRUE(j["verified"]["reliable"].get<bool>());
  EXPECT_EQ(j["check"]["rollouts"], 1000);
  EXPECT_EQ(j["check"]["successes"], 1000);
  EXPECT_EQ(j["check"]["outside"], 0);
  // The written motion carries P_s; its rollouts stop by sensing.
  const Result rollouts = run("rollout " + out + " --strategy planned -n 20 --seed 3 --json");
  ASSERT_EQ(rollouts.status, 0) << rollouts.out;
  const auto ro = nlohmann::json::parse(rollouts.out);
  EXPECT_EQ(ro["successes"], 20);
  for (const auto& o : ro["outcomes"]) EXPECT_EQ(o["termination"], "position") << o;
  // With sticking termination the goal stop by sticking near the bottom's centre plans it too, without P_s.
  const Result sticking = run("plan " + task("cube_sensing") + " --threads 2 --json");
  ASSERT_EQ(sticking.status, 0) << sticking.out;
  const auto s = nlohmann::json::parse(sticking.out);
  EXPECT_EQ(s["termination"], "sticking");
  EXPECT_TRUE(s["spositions"].empty());
  EXPECT_EQ(s["steps"][0]["targets"], nlohmann::json::array({"goal"}));
  EXPECT_TRUE(s["verified"]["reliable"].get<bool>());
}

// §6.3.3: the hole from the start segment on the top face. The first motion comes from the start projection
// (the verifier from the segment itself: the simulation from the whole top face may leave it over its flat
// edges), the second from a chain projection; the chain is verified, and every rollout reaches the goal.
// Type 3 (§6.7.6) on the cube of §6.3.1: the motion stops on sensing a position in P_s and a force in F_s.
// F_s is the bottom's friction cone widened by theta_f (about +z, half angle atan .25 + .3), which no wall's
// widened cone meets, so P_s covers the whole bottom (goal_stops.h). The plan stops in the goal by sticking
// on the bottom or by sensing; the verifier agrees, every rollout reaches the goal, and the rollouts of the
// written strategy stop by sensing the force.
TEST(CmtPlan, CubeForceSensingStopsAnywhereOnTheBottom) {
  const std::string out = testing::TempDir() + "/cube_force_planned.yaml";
  const Result r =
      run("plan " + task("cube") + " --termination force --check 100 --seed 7 --threads 2 --json -o " + out);
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j["found"].get<bool>()) << r.out;
  EXPECT_EQ(j["termination"], "force");
  ASSERT_EQ(j["sforces"].size(), 1u);
  EXPECT_EQ(j["sforces"][0]["direction"], nlohmann::json::array({0.0, 0.0, 1.0}));
  EXPECT_NEAR(j["sforces"][0]["angle"].get<double>(), std::atan(0.25) + 0.3, 1e-6);  // + a 1e-7 margin
  ASSERT_EQ(j["spositions"].size(), 1u);
  for (int k = 0; k < 2; ++k) {  // the whole bottom [-1, 1]^2, less a margin of ~1e-6 x scale
    EXPECT_NEAR(j["spositions"][0]["min"][k].get<double>(), -1.0, 1e-4);
    EXPECT_NEAR(j["spositions"][0]["max"][k].get<double>(), 1.0, 1e-4);
  }
  ASSERT_EQ(j["motions"].size(), 1u);
  EXPECT_EQ(j["motions"][0]["sforces"], j["sforces"]);
  for (const auto& atom : j["steps"][0]["targets"]) EXPECT_TRUE(atom == "f2" || atom == "goal") << atom;
  EXPECT_TRUE(j["verified"]["reliable"].get<bool>());
  EXPECT_EQ(j["check"]["rollouts"], 100);
  EXPECT_EQ(j["check"]["successes"], 100);
  EXPECT_EQ(j["check"]["outside"], 0);
  const Result rollouts = run("rollout " + out + " --strategy planned -n 20 --seed 3 --json");
  ASSERT_EQ(rollouts.status, 0) << rollouts.out;
  const auto ro = nlohmann::json::parse(rollouts.out);
  EXPECT_EQ(ro["successes"], 20);
  for (const auto& o : ro["outcomes"]) EXPECT_EQ(o["termination"], "force") << o;
}

TEST(CmtPlan, HoleHasATwoMotionPlanFromTheStartProjectionThatTheRolloutsConfirm) {
  const Result r = run("plan " + task("hole") + " --check 60 --seed 7 --threads 2 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j["found"].get<bool>()) << r.out;
  ASSERT_EQ(j["motions"].size(), 2u);
  EXPECT_EQ(j["motions"][0]["source"], "start projection");
  EXPECT_TRUE(j["motions"][0]["cpositions"].empty());
  EXPECT_GE(j["start_projections"].get<int>(), 1);
  EXPECT_EQ(j["steps"][0]["state"], nlohmann::json::array({"f5"}));  // the start face
  // The first motion leaves the start face (it stops in one sensed state, not in the goal).
  EXPECT_FALSE(j["steps"][0]["targets"].empty());
  for (const auto& atom : j["steps"][0]["targets"]) EXPECT_NE(atom, "f5");
  EXPECT_EQ(j["steps"][0]["heads"].size(), 1u);
  // The second motion continues the projection from its own stops on the far wall: Buckley's p1, beneath
  // the hole (a contact seed behind the bottom face), which may stop only on the bottom.
  EXPECT_EQ(j["motions"][1]["source"], "chain projection");
  EXPECT_GE(j["chain_projections"].get<int>(), 1);
  EXPECT_EQ(j["steps"][1]["state"], j["steps"][0]["heads"][0]);
  EXPECT_EQ(j["steps"][1]["targets"], nlohmann::json::array({"f8"}));  // the bottom face
  EXPECT_LT(j["motions"][1]["commanded"][2].get<double>(), -2.0);      // beneath the bottom's plane
  EXPECT_TRUE(j["decision_free"].get<bool>());
  EXPECT_TRUE(j["verified"]["reliable"].get<bool>());
  EXPECT_EQ(j["check"]["rollouts"], 60);
  EXPECT_EQ(j["check"]["successes"], 60);
  EXPECT_EQ(j["check"]["outside"], 0);
}

// §6.3.5, the double hole (the T-slot): a two-motion decision-free plan. The first motion, from the start
// projection, stops on the first hole's far wall; from there the simulation's cells reach no goal, and the
// second motion is a chain projection at a seed behind the goal face's floor edge. The chain is verified and
// every rollout reaches the goal.
TEST(CmtPlan, TslotHasATwoMotionPlanThroughAChainProjection) {
  const Result r = run("plan " + task("tslot") + " --check 20 --seed 7 --threads 2 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j["found"].get<bool>()) << r.out;
  ASSERT_EQ(j["motions"].size(), 2u);
  EXPECT_EQ(j["motions"][0]["source"], "start projection");
  EXPECT_EQ(j["motions"][1]["source"], "chain projection");
  EXPECT_EQ(j["steps"][1]["state"], j["steps"][0]["heads"][0]);
  EXPECT_LT(j["motions"][1]["commanded"][2].get<double>(), -5.0);  // below the second hole's floor
  EXPECT_GT(j["motions"][1]["commanded"][1].get<double>(), 3.0);   // beyond the goal face
  EXPECT_TRUE(j["decision_free"].get<bool>());
  EXPECT_TRUE(j["verified"]["reliable"].get<bool>());
  EXPECT_EQ(j["check"]["successes"], 20);
  EXPECT_EQ(j["check"]["outside"], 0);
}

// §6.3.4 in simulation: the cube's planned motion commanded at each vertex of its cell (every rollout reaches
// the goal), then at the vertices of the cell grown by eps_p, each outside it by eps_p.
TEST(CmtPlan, CubeMotionReachesTheGoalFromEveryVertexOfItsCell) {
  const Result r = run("plan " + task("cube") + " --extremes 10 --grow 1 --seed 3 --threads 2 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  const auto& e = j["extremes"];
  EXPECT_TRUE(e["vertices_all_succeed"].get<bool>());
  EXPECT_EQ(e["rollouts_per_point"], 10);
  ASSERT_EQ(e["motions"].size(), 1u);
  const auto& m = e["motions"][0];
  EXPECT_EQ(m["motion"], "planned_1");
  EXPECT_TRUE(m["claims_cell"].get<bool>());
  const auto& cell = j["motions"][0]["cpositions"];
  ASSERT_EQ(cell.size(), 1u);
  EXPECT_EQ(m["vertices"]["points"].size(), cell[0]["vertices"].size());
  for (const auto& p : m["vertices"]["points"]) {
    EXPECT_EQ(p["rollouts"], 10);
    EXPECT_EQ(p["successes"], 10) << p;
    EXPECT_EQ(p["outside"], 0) << p;
  }
  ASSERT_EQ(m["grown"].size(), 1u);
  EXPECT_EQ(m["grown"][0]["factor"], 1.0);
  const double eps_p = e["eps_p"].get<double>();
  EXPECT_GE(m["grown"][0]["points"].size(), cell[0]["vertices"].size());
  for (const auto& p : m["grown"][0]["points"]) {
    double violation = -1e300;  // the largest violation of a half-space of the cell: at least eps_p
    for (const auto& h : cell[0]["halfspaces"]) {
      double dot = 0;
      for (int k = 0; k < 3; ++k) dot += h[k].get<double>() * p["commanded"][k].get<double>();
      violation = std::max(violation, dot - h[3].get<double>());
    }
    EXPECT_GE(violation, eps_p * (1 - 1e-9)) << p;
    EXPECT_EQ(p["rollouts"], 10);
  }
}

// A goal .3 in wide has no sensed-position set (shrunk by eps_s = .2 on each side nothing is left): no plan,
// exit 1, with the reason.
TEST(CmtPlan, PositionTerminationWithoutASensedPositionSetFindsNothing) {
  const std::string file = testing::TempDir() + "/cube_small_goal.yaml";
  {
    std::ifstream in(task("cube_sensing"));
    std::stringstream text;
    text << in.rdbuf();
    std::string yaml = text.str();
    const std::string goal = "[[-0.8, -0.8, -1], [0.8, -0.8, -1], [0.8, 0.8, -1], [-0.8, 0.8, -1]]";
    ASSERT_NE(yaml.find(goal), std::string::npos);
    yaml.replace(yaml.find(goal), goal.size(),
                 "[[-0.15, -0.15, -1], [0.15, -0.15, -1], [0.15, 0.15, -1], [-0.15, 0.15, -1]]");
    std::ofstream(file) << yaml;
  }
  const Result r = run("plan " + file + " --termination position --json");
  EXPECT_EQ(r.status, 1) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j["found"].get<bool>());
  EXPECT_TRUE(j["spositions"].empty());
  EXPECT_NE(j["reason"].get<std::string>().find("no sensed-position set"), std::string::npos) << j["reason"];
}

TEST(CmtPlan, AnUnknownTerminationOrABadOverrideIsBadInput) {
  EXPECT_EQ(run("plan " + task("cube") + " --termination sensing --json").status, 2);
  const Result planar = run("plan " + task("planar_blocks") + " --json");
  EXPECT_EQ(planar.status, 2);
  EXPECT_EQ(nlohmann::json::parse(planar.out)["error"]["key"], "dimension");
  const Result r = run("plan " + task("cube") + " --states --theta-f 4 --json");
  EXPECT_EQ(r.status, 2);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["error"]["key"], "uncertainty.theta_f");
}

}  // namespace
}  // namespace cmt::test
