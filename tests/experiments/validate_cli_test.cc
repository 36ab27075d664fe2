// End-to-end tests of `cmt validate` (docs/validation.md): the docs/contracts.md fields, real outcomes on the
// built-in two_blocks and cube tasks, counterexamples that replay with `cmt rollout`, the counterexample
// search, results independent of the thread count, the sticking table, and bad input.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/experiments/cmt_runner.h"

namespace {

using cmt::test::Result;
using cmt::test::run;
using cmt::test::task;
using nlohmann::json;

// Runs a replay command line printed by validate ("cmt rollout ...") with the built binary; returns the
// rollout it replays (the last one).
json replay(const std::string& command) {
  EXPECT_EQ(command.rfind("cmt rollout ", 0), 0u) << command;
  const Result r = run(command.substr(4) + " --threads 1 --json");
  EXPECT_NE(r.status, 2) << command;
  return json::parse(r.out)["outcomes"].back();
}

// Without the fields that depend on the thread count or the clock.
json timeless(json j) {
  j.erase("seconds");
  j.erase("threads");
  j["prediction"].erase("seconds");
  return j;
}

TEST(CmtValidate, CubeStickIsSoundAndEveryRolloutSucceeds) {
  // The verifier proves `stick` reliable (tests/verifier Verify.CubeSpringStickIsReliable): every rollout
  // must succeed and every end lie in the predicted termination set (the floor's weak sticking disk).
  const Result r = run("validate " + task("cube") + " --strategy stick -n 60 --seed 1 --threads 2 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const json j = json::parse(r.out);
  for (const char* key : {"reliable", "rollouts", "successes", "outside", "soundness", "coverage"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_TRUE(j["reliable"].get<bool>());
  EXPECT_FALSE(j["verifier_timed_out"].get<bool>());
  EXPECT_EQ(j["rollouts"], 60);
  EXPECT_EQ(j["successes"], 60);
  EXPECT_EQ(j["unstable"], 0);
  EXPECT_EQ(j["outside"], 0);
  EXPECT_EQ(j["ends_checked"], 60);  // one motion per rollout
  EXPECT_DOUBLE_EQ(j["soundness"].get<double>(), 1.0);
  EXPECT_FALSE(j["soundness_bug"].get<bool>());
  EXPECT_TRUE(j["counterexample"].is_null());
  EXPECT_FALSE(j.contains("search"));  // reliable: nothing to search for
  // The prediction is the floor disk, an area: coverage is a fraction of it, r = sqrt(3 A / (60 pi)).
  ASSERT_EQ(j["steps"].size(), 1u);
  EXPECT_EQ(j["steps"][0]["measure"], "area");
  const double area = j["steps"][0]["predicted"].get<double>();
  EXPECT_NEAR(j["coverage_radius"].get<double>(), std::sqrt(3 * area / (60 * M_PI)), 1e-12);
  EXPECT_GT(j["coverage"].get<double>(), 0);
  EXPECT_LE(j["coverage"].get<double>(), 1);
  // 1e-4 of the cube's scale (the diagonal of [-1,1]^3, 2 sqrt 3).
  EXPECT_NEAR(j["contact_tolerance"].get<double>(), 1e-4 * 2 * std::sqrt(3.0), 1e-15);
}

TEST(CmtValidate, TwoBlocksSlideIsSoundWithALengthPrediction) {
  // `slide` is reliable and ends in the concave edge x = -1.5, z = 0 (and its corner vertices): a 1-D
  // prediction (length 8, the edge across the y walls at +-4, as intervals that may leave gaps of rounding
  // size between them), so coverage is measured along it, its radius from the predicted length.
  const Result r =
      run("validate " + task("two_blocks") + " --strategy slide -n 40 --seed 1 --threads 2 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const json j = json::parse(r.out);
  EXPECT_TRUE(j["reliable"].get<bool>());
  EXPECT_EQ(j["successes"], 40);
  EXPECT_EQ(j["outside"], 0);
  EXPECT_DOUBLE_EQ(j["soundness"].get<double>(), 1.0);
  EXPECT_EQ(j["steps"][0]["measure"], "length");
  const double length = j["steps"][0]["predicted"].get<double>();
  EXPECT_NEAR(length, 8, 1e-9);
  EXPECT_NEAR(j["coverage_radius"].get<double>(), 3 * length / (2 * 40), 1e-12);
}

TEST(CmtValidate, TwoBlocksDownReportsACounterexampleThatReplays) {
  // `down` is unreliable (theta_v > atan mu: the robot may stick on B's top, outside the goal). The
  // prediction must still be sound; a failing rollout is the counterexample and its command line replays it.
  const Result r =
      run("validate " + task("two_blocks") + " --strategy down -n 40 --seed 1 --threads 2 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const json j = json::parse(r.out);
  EXPECT_FALSE(j["reliable"].get<bool>());
  EXPECT_EQ(j["outside"], 0);
  EXPECT_FALSE(j["soundness_bug"].get<bool>());
  ASSERT_FALSE(j["counterexample"].is_null());
  const json& cx = j["counterexample"];
  EXPECT_EQ(cx["how"], "rollouts");
  EXPECT_FALSE(cx["success"].get<bool>());
  const json replayed = replay(cx["replay"].get<std::string>());
  EXPECT_EQ(replayed["index"], cx["index"]);
  EXPECT_FALSE(replayed["success"].get<bool>());
  EXPECT_EQ(replayed["end"], cx["end"]);  // bit for bit: the same seed and index
}

TEST(CmtValidate, TwoBlocksConditionalProbeIsSoundOnEveryBranch) {
  // `tilt` (v3 alone) may stick on B's top: unreliable, and a failing rollout replays. `probe` senses after
  // v3 and runs v2 only outside the gap (docs/verifier.md "Conditional strategies"): reliable, every rollout
  // succeeds, and every motion end, on either branch, lies in the prediction for its strategy node.
  const Result tilt =
      run("validate " + task("two_blocks") + " --strategy tilt -n 40 --seed 1 --threads 2 --json");
  ASSERT_EQ(tilt.status, 0) << tilt.out;
  const json t = json::parse(tilt.out);
  EXPECT_FALSE(t["reliable"].get<bool>());
  EXPECT_EQ(t["outside"], 0);
  ASSERT_FALSE(t["counterexample"].is_null());
  EXPECT_FALSE(replay(t["counterexample"]["replay"].get<std::string>())["success"].get<bool>());

  const Result r =
      run("validate " + task("two_blocks") + " --strategy probe -n 40 --seed 1 --threads 2 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const json j = json::parse(r.out);
  EXPECT_TRUE(j["reliable"].get<bool>());
  EXPECT_EQ(j["successes"], 40);
  EXPECT_EQ(j["outside"], 0);
  EXPECT_EQ(j["unpredicted"], 0);
  EXPECT_DOUBLE_EQ(j["soundness"].get<double>(), 1.0);
  EXPECT_FALSE(j["soundness_bug"].get<bool>());
  // One end per v3, one more per rollout that took the else branch: ends_checked = 40 + (else count), with
  // both branches taken.
  const int checked = j["ends_checked"].get<int>();
  EXPECT_GT(checked, 40);
  EXPECT_LT(checked, 80);

  // The verifier's tree in `cmt verify`: step 0 = v3 (node 0) with two branches, branch 0 a reachable stop,
  // branch 1 leading to step 1 = v2 (node 1).
  const Result v = run("verify " + task("two_blocks") + " --strategy probe --json");
  ASSERT_EQ(v.status, 0) << v.out;
  const json p = json::parse(v.out);
  ASSERT_EQ(p["steps"].size(), 2u);
  const json& s0 = p["steps"][0];
  EXPECT_EQ(s0["motion"], "v3");
  EXPECT_EQ(s0["node"], 0);
  EXPECT_EQ(s0["parent"], -1);
  ASSERT_EQ(s0["branches"].size(), 2u);
  EXPECT_TRUE(s0["branches"][0]["reachable"].get<bool>());
  EXPECT_EQ(s0["branches"][0]["step"], -1);
  EXPECT_EQ(s0["branches"][1]["step"], 1);
  EXPECT_FALSE(s0.contains("unmatched"));  // it has an else branch
  const json& s1 = p["steps"][1];
  EXPECT_EQ(s1["motion"], "v2");
  EXPECT_EQ(s1["node"], 1);
  EXPECT_EQ(s1["parent"], 0);
  EXPECT_EQ(s1["branch"], 1);
}

TEST(CmtValidate, PlanarBlocksSlideIsSoundAndCoveredInThePlane) {
  // planar_blocks (dimension 2): `slide` ends in the corner (-1.5, 0), a point in the plane (a line across
  // the phantom slab in 3-D): every planar rollout reaches it, so coverage, measured in the plane, is 1.
  const Result r =
      run("validate " + task("planar_blocks") + " --strategy slide -n 60 --seed 1 --threads 2 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const json j = json::parse(r.out);
  EXPECT_TRUE(j["reliable"].get<bool>());
  EXPECT_EQ(j["successes"], 60);
  EXPECT_EQ(j["outside"], 0);
  EXPECT_DOUBLE_EQ(j["soundness"].get<double>(), 1.0);
  ASSERT_EQ(j["steps"].size(), 1u);
  EXPECT_EQ(j["steps"][0]["measure"], "points");
  EXPECT_EQ(j["steps"][0]["predicted"], 1.0);
  EXPECT_DOUBLE_EQ(j["coverage"].get<double>(), 1.0);
  // Output in the plane: 2-vectors.
  EXPECT_EQ(j["prediction"]["steps"][0]["termination"][0]["polygon"][0].size(), 2u);
}

// A block [-1,1]^2 x [0,1] on a floor; the goal is its top, the robot is pushed straight down from `start`
// (on the top). With theta_v > atan .25 = .2450 the verifier must say the robot may slide off the top onto
// the floor (outside the goal): unreliable.
std::string block_task(const std::string& name, double theta_v, double theta_f, const std::string& start) {
  const auto file = std::filesystem::temp_directory_path() /
                    ("cmt_validate_" + name + "_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(file) << "name: " << name << "\nunits: in\nfriction: 0.25\n"
                      << "uncertainty: {eps_s: 0.2, eps_p: 0.2, theta_v: " << theta_v
                      << ", theta_f: " << theta_f
                      << "}\ncspace:\n  - box: {min: [-1, -1, 0], max: [1, 1, 1]}\n"
                         "bounds: {min: [-3, -3, 0], max: [3, 3, 3]}\nstart: "
                      << start
                      << "\ngoal: {polygon: [[-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]]}\n"
                         "motions:\n  down: {damper: [0, 0, -1]}\nstrategies:\n  s: [down]\n";
  return file.string();
}

// Start .1 in from the top's edge, theta_v = .26: in extreme mode the push is mostly .015 rad outside the
// friction cone (Coulomb sliding speed V (sin .26 - .25 cos .26) = 1.5 % of V, above the 1 % stop rule).
std::string edge_task() { return block_task("edge", 0.26, 0.3, "{point: [0.9, 0, 1]}"); }

// A start square [-.2,.2] x [-.1,.1] in the middle of the top, theta_v = .2455, theta_f = 0: the verifier
// must still say "may slide off" (theta_v > phi), but Coulomb sliding at the largest error is V (sin .2455 -
// .25 cos .2455) = 5e-4 V, far below the 1 % of V under which a rollout counts as stuck: no rollout can
// reach the top's edge, so the search spends its whole budget and finds nothing.
std::string centre_task() {
  return block_task("centre", 0.2455, 0,
                    "{polygon: [[-0.2, -0.1, 1], [0.2, -0.1, 1], [0.2, 0.1, 1], [-0.2, 0.1, 1]]}");
}

TEST(CmtValidate, UnreliableWithoutFailuresSearchesForACounterexampleThatReplays) {
  const std::string file = edge_task();
  const Result r =
      run("validate " + file + " --strategy s -n 5 --seed 1 --threads 2 --search-budget 40 --json");
  ASSERT_NE(r.status, 2) << r.out;
  const json j = json::parse(r.out);
  EXPECT_FALSE(j["reliable"].get<bool>());
  ASSERT_FALSE(j["counterexample"].is_null());
  const json& cx = j["counterexample"];
  if (j["successes"] == 5) {
    // No rollout failed: the counterexample came from the search, as rollout 0 of a derived seed.
    ASSERT_TRUE(j.contains("search"));
    EXPECT_LE(j["search"]["rollouts"].get<int>(), 40);
    EXPECT_NE(cx["how"], "rollouts");
    EXPECT_EQ(cx["index"], 0);
  }
  EXPECT_FALSE(cx["success"].get<bool>());
  const json replayed = replay(cx["replay"].get<std::string>());
  EXPECT_FALSE(replayed["success"].get<bool>());
  EXPECT_EQ(replayed["end"], cx["end"]);
  std::filesystem::remove(file);
}

TEST(CmtValidate, TheSearchSpendsItsBudgetOverThreePhases) {
  const std::string file = centre_task();
  const Result r =
      run("validate " + file + " --strategy s -n 6 --seed 1 --threads 2 --search-budget 30 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const json j = json::parse(r.out);
  EXPECT_FALSE(j["reliable"].get<bool>());
  EXPECT_EQ(j["successes"], 6);
  EXPECT_EQ(j["outside"], 0);
  ASSERT_TRUE(j.contains("search"));
  EXPECT_EQ(j["search"]["rollouts"], 30);  // 10 extreme, 10 at start corners, 10 local
  EXPECT_EQ(j["search"]["outside"], 0);
  EXPECT_TRUE(j["counterexample"].is_null());
  const std::string note = j["search"]["note"];
  EXPECT_NE(note.find("extreme: 10 rollouts"), std::string::npos) << note;
  EXPECT_NE(note.find("start vertices: 10 rollouts"), std::string::npos) << note;
  EXPECT_NE(note.find("local search"), std::string::npos) << note;
  std::filesystem::remove(file);
}

TEST(CmtValidate, ResultsDoNotDependOnTheThreadCount) {
  const std::string file = centre_task();
  for (const std::string& args :
       {"validate " + task("cube") + " --strategy stick -n 12 --seed 5 --mode extreme --ends --json",
        "validate " + file + " --strategy s -n 5 --seed 1 --search-budget 24 --ends --json"}) {
    const Result a = run(args + " --threads 1"), b = run(args + " --threads 2");
    ASSERT_EQ(a.status, b.status) << args;
    EXPECT_EQ(timeless(json::parse(a.out)).dump(), timeless(json::parse(b.out)).dump()) << args;
  }
  std::filesystem::remove(file);
}

TEST(CmtValidate, StickingTrialsAddThePerAtomTable) {
  const Result r = run("validate " + task("cube") +
                       " --strategy stick -n 4 --seed 1 --threads 2 --sticking-trials 30 --json");
  ASSERT_NE(r.status, 2);
  const json j = json::parse(r.out);
  ASSERT_TRUE(j.contains("sticking"));
  EXPECT_EQ(j["sticking"]["trials"], 30);
  int trials = 0, disagreements = 0;
  for (const json& row : j["sticking"]["per_atom"]) {
    for (const char* c : {"must", "may", "never"}) trials += row[c]["trials"].get<int>();
    disagreements += row["disagreements"].get<int>();
  }
  EXPECT_EQ(trials, 30);
  EXPECT_EQ(disagreements, j["sticking"]["disagreements"].get<int>());
  EXPECT_EQ(r.status, disagreements > 0 ? 1 : 0);
}

TEST(CmtValidate, PastTheTimeLimitTheRolloutsRunWithoutAPrediction) {
  // peg_in_hole_real's teach_too_deep verifies in tens of seconds: 10 ms is not enough. The verifier is
  // stopped, the rollouts still run and are reported; with no prediction nothing is scored or searched, and
  // nothing contradicts the verifier (exit 0).
  const Result r = run("validate " + task("peg_in_hole_real") +
                       " --strategy teach_too_deep -n 3 --seed 1 --threads 2 --time-limit 0.01 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const json j = json::parse(r.out);
  EXPECT_TRUE(j["verifier_timed_out"].get<bool>());
  EXPECT_FALSE(j["reliable"].get<bool>());
  EXPECT_EQ(j["rollouts"], 3);
  EXPECT_EQ(j["ends_checked"], 0);
  EXPECT_FALSE(j.contains("search"));
  EXPECT_NE(j["prediction"]["failure"].get<std::string>().find("timed out after 0.01 s"), std::string::npos)
      << j["prediction"];
  EXPECT_EQ(run("validate " + task("cube") + " --strategy stick -n 2 --time-limit 0 --json").status, 2);
}

TEST(CmtValidate, BadInputExitsWithTwoAndSaysWhy) {
  struct Case {
    std::string args, needle;
  };
  // An unknown strategy is found in the process that runs the validation; its key still reaches the JSON.
  for (const Case& c :
       {Case{"validate " + task("cube") + " --strategy nope -n 2 --json", "\"key\": \"strategies\""},
        Case{"validate " + task("cube") + " --strategy stick -n 0 --json", "-n"},
        Case{"validate " + task("cube") + " --strategy stick --mode wild --json", "--mode"},
        Case{"validate " + task("cube") + " --strategy stick --sticking-trials -1 --json",
             "--sticking-trials"},
        Case{"validate /nonexistent/x.yaml --strategy stick --json", "x.yaml"}}) {
    const Result r = run(c.args);
    EXPECT_EQ(r.status, 2) << c.args;
    EXPECT_NE(r.out.find(c.needle), std::string::npos) << c.args << "\n" << r.out;
  }
}

}  // namespace
