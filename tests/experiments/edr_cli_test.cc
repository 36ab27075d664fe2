// `cmt edr`, `cmt verify --edr`, `cmt validate --edr` and `cmt rollout --world` end to end (docs/edr.md) on
// Donald's Example (1), models/tasks/step_offset.yaml, under the rollouts' model: the verdicts, the JSON
// fields, the physics check's outcomes and replays, bad input.
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
  // The 5 slices (-1, -.5, 0, .5, 1) and the refinement toward where the goal appears (--refine 3): .25,
  // .125, .0625 between 0 and .5.
  EXPECT_EQ(j["refine_depth"], 3);
  ASSERT_EQ(j["slices"].size(), 8u);
  for (const auto& s : j["slices"]) {
    const double alpha = s["params"]["alpha"].get<double>();
    EXPECT_EQ(s["goal_empty"].get<bool>(), alpha <= 0) << alpha;
    ASSERT_TRUE(s["terminates"].get<bool>());
    EXPECT_EQ(s["success_area"].get<double>() > 0, alpha > 0) << alpha;
    if (alpha <= 0) {
      EXPECT_GT(s["failure_area"].get<double>(), 0) << alpha;  // H wherever the goal vanishes
    }
    EXPECT_TRUE(s.contains("strong_preimage_area") && s.contains("weak_preimage_area"));
    EXPECT_TRUE(s["distinguishable"].get<bool>());
  }
  EXPECT_TRUE(j["confusions"].empty());

  const Result coarse = run("edr " + task("step_offset") + " --strategy edr --refine 0 --json");
  ASSERT_EQ(coarse.status, 0) << coarse.out;
  EXPECT_EQ(nlohmann::json::parse(coarse.out)["slices"].size(), 5u);

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

TEST(CmtVerifyEdr, ReadsTheMotionsEdrPredicate) {
  const Result edr = run("verify " + task("step_offset") + " --strategy edr --edr --json");
  ASSERT_EQ(edr.status, 0) << edr.out;
  const auto j = nlohmann::json::parse(edr.out);
  EXPECT_TRUE(j["edr_reliable"].get<bool>());
  EXPECT_TRUE(j["reliable"].get<bool>());
  EXPECT_EQ(j["slices"].size(), 8u);  // as `cmt edr`: 5 and the refinement toward alpha = 0
  // The same verdict at another resolution: 3 values, the critical 0 and 2 midpoints, refined the same way;
  // without refinement the 5 alone.
  const Result fine = run("verify " + task("step_offset") + " --strategy edr --edr --resolution 3 --json");
  ASSERT_EQ(fine.status, 0) << fine.out;
  EXPECT_EQ(nlohmann::json::parse(fine.out)["slices"].size(), 8u);
  const Result coarse = run("verify " + task("step_offset") + " --strategy edr --edr --refine 0 --json");
  ASSERT_EQ(coarse.status, 0) << coarse.out;
  EXPECT_EQ(nlohmann::json::parse(coarse.out)["slices"].size(), 5u);

  const Result steep = run("verify " + task("step_offset") + " --strategy steep --edr --json");
  EXPECT_EQ(steep.status, 1) << steep.out;
  EXPECT_FALSE(nlohmann::json::parse(steep.out)["edr_reliable"].get<bool>());

  // `down` carries no `edr: true`: bad input naming the motion's key.
  const Result down = run("verify " + task("step_offset") + " --strategy down --edr --json");
  ASSERT_EQ(down.status, 2) << down.out;
  EXPECT_EQ(nlohmann::json::parse(down.out)["error"]["key"], "motions.down.edr");
}

// Donald's Example (6), the width alone, under the rollouts' model: the two-motion plan is EDR-reliable; the
// goal (the hole's bottom) exists exactly where the hole is wider than the peg (w > 1).
TEST(CmtVerifyEdr, HoleWidthTwoMotionPlanIsEdrReliable) {
  const Result r = run("verify " + task("hole_width") + " --strategy edr --edr --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["edr_reliable"].get<bool>());
  EXPECT_FALSE(j["timed_out"].get<bool>());
  EXPECT_EQ(j["parameters"][0]["critical"], nlohmann::json::array({1.0}));
  int toward_critical = 0, at_the_kink = 0;
  for (const auto& s : j["slices"]) {
    const double w = s["params"]["hole_width"].get<double>();
    EXPECT_EQ(s["goal_empty"].get<bool>(), w <= 1) << w;
    EXPECT_EQ(s["success_area"].get<double>() > 0, w > 1) << w;
    toward_critical += w > 1 && w < 1.125 ? 1 : 0;
    at_the_kink += w > 1.75 && w < 2 ? 1 : 0;
  }
  // Refinement: three bisections from 1.125 toward the critical width 1, where the goal appears; and slices
  // between 1.75 and 2, where the stop on the bottom reaches the right wall at 1.75 (x = w / 2 - .5) but
  // stops short of it at 2, so the pair's sweep misses the worlds between (docs/edr.md "Between slices").
  EXPECT_EQ(toward_critical, 3);
  EXPECT_GE(at_the_kink, 1);
}

TEST(CmtVerifyEdr, AMalformedEdrKeyNamesIt) {
  std::ifstream in(task("step_offset"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "edr: true}     #";
  text.replace(text.find(from), from.size(), "edr: yes}     #");
  const auto path = std::filesystem::temp_directory_path() / "cmt_edr_bad_key.yaml";
  std::ofstream(path) << text;
  const Result r = run("verify " + path.string() + " --strategy edr --json");
  ASSERT_EQ(r.status, 2) << r.out;
  EXPECT_EQ(nlohmann::json::parse(r.out)["error"]["key"], "motions.left.edr");
  std::filesystem::remove(path);
}

// 60 rollouts in 3 worlds drawn over alpha in [-1, 1]: every rollout is classified, none is forbidden, the
// verifier's prediction in each world holds every motion end, and each world's replay command runs its
// rollouts again with the same goal outcomes.
TEST(CmtValidateEdr, StepOffsetOutcomesAreAllowedAndReplay) {
  const Result v = run("validate " + task("step_offset") +
                       " --strategy edr --edr -n 60 --per-world 20 --seed 7 --mode "
                       "extreme --json");
  ASSERT_EQ(v.status, 0) << v.out;
  const auto j = nlohmann::json::parse(v.out);
  EXPECT_TRUE(j["reliable"].get<bool>());
  EXPECT_EQ(j["rollouts"].get<int>(), 60);
  const auto& o = j["outcomes"];
  EXPECT_EQ(o["false_success"].get<int>(), 0);
  EXPECT_EQ(o["false_failure"].get<int>(), 0);
  EXPECT_EQ(o["success"].get<int>() + o["failure_signalled"].get<int>() + o["timeout"].get<int>() +
                j["missed_success"].get<int>() + j["unstable"].get<int>(),
            60);
  EXPECT_EQ(j["successes"].get<int>(),
            o["success"].get<int>() + j["missed_success"].get<int>() + o["false_failure"].get<int>());
  EXPECT_EQ(j["outside"].get<int>(), 0);
  EXPECT_EQ(j["soundness"].get<double>(), 1.0);
  EXPECT_GT(j["coverage"].get<double>(), 0.0);
  ASSERT_EQ(j["worlds"].size(), 3u);
  for (const auto& w : j["worlds"]) {
    const double alpha = w["params"][0].get<double>();
    const auto& c = w["outcomes"];
    // Where the goal vanishes (alpha <= 0) nothing may succeed; the predicate must say failure.
    if (alpha <= 0) {
      EXPECT_EQ(c["success"].get<int>() + c["missed_success"].get<int>(), 0) << alpha;
    }
    const std::string replay = w["replay"].get<std::string>();
    ASSERT_EQ(replay.rfind("cmt rollout ", 0), 0u) << replay;
    const Result again = run(replay.substr(4) + " --json");
    ASSERT_NE(again.status, 2) << replay;
    const auto r = nlohmann::json::parse(again.out);
    ASSERT_EQ(r["rollouts"].get<int>(), 20) << replay;
    EXPECT_EQ(r["successes"].get<int>(),
              c["success"].get<int>() + c["missed_success"].get<int>() + c["false_failure"].get<int>())
        << replay;
  }
}

// `--refine D` reaches the verdict: the slices refined between (docs/edr.md "Between slices"), none with 0.
TEST(CmtValidateEdr, RefineSetsTheVerdictsRefinementDepth) {
  std::vector<std::size_t> slices;
  for (const int depth : {0, 2}) {
    const Result v =
        run("validate " + task("step_offset") + " --strategy edr --edr -n 20 --per-world 20 --seed 7 " +
            "--refine " + std::to_string(depth) + " --json");
    ASSERT_EQ(v.status, 0) << v.out;
    const auto j = nlohmann::json::parse(v.out);
    EXPECT_EQ(j["verdict"]["refine_depth"].get<int>(), depth);
    EXPECT_EQ(j["outcomes"]["false_success"].get<int>() + j["outcomes"]["false_failure"].get<int>(), 0);
    slices.push_back(j["verdict"]["slices"].size());
  }
  EXPECT_GT(slices[1], slices[0]);
  EXPECT_EQ(run("validate " + task("step_offset") + " --strategy edr --edr -n 5 --refine 11").status, 2);
}

TEST(CmtRolloutWorld, BadWorldsExitTwo) {
  const std::string base = "rollout " + task("step_offset") + " --strategy edr -n 1 --json";
  EXPECT_EQ(run(base + " --world alpha=0.5").status, 0);
  const Result unknown = run(base + " --world beta=0.5");
  ASSERT_EQ(unknown.status, 2);
  EXPECT_EQ(nlohmann::json::parse(unknown.out)["error"]["key"], "--world");
  EXPECT_EQ(run(base + " --world alpha=1.5").status, 2);  // outside [-1, 1]
  EXPECT_EQ(run(base + " --world alpha=x").status, 2);
  EXPECT_EQ(run(base + " --world alpha").status, 2);
}

// A discrete parameter takes only its values: the twin universe's worlds are 1 and 2.
TEST(CmtRolloutWorld, ADiscreteParameterTakesOnlyItsValues) {
  const std::string base = "rollout " + task("twin_universe") + " --strategy edr -n 1 --json";
  EXPECT_EQ(run(base + " --world universe=1").status, 0);
  EXPECT_EQ(run(base + " --world universe=2").status, 1);  // runs; its rollout misses the absent goal
  const Result between = run(base + " --world universe=1.5");
  ASSERT_EQ(between.status, 2);
  const auto j = nlohmann::json::parse(between.out);
  EXPECT_EQ(j["error"]["key"], "--world");
  EXPECT_NE(j["error"]["reason"].get<std::string>().find("not one of its values"), std::string::npos);
}

// Donald's Example (3): the two universes are the slices at any resolution; the two-step strategy is
// EDR-reliable, the one-step command is not.
TEST(CmtVerifyEdr, TwinUniverseNeedsTwoSteps) {
  const Result r = run("verify " + task("twin_universe") + " --strategy edr --edr --resolution 9 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["edr_reliable"].get<bool>());
  EXPECT_TRUE(j["linked"].get<bool>());
  EXPECT_TRUE(j["parameters"][0]["discrete"].get<bool>());
  EXPECT_EQ(j["parameters"][0]["values"], nlohmann::json::array({1.0, 2.0}));
  EXPECT_EQ(j["parameters"][0]["critical"], nlohmann::json::array());
  ASSERT_EQ(j["slices"].size(), 2u);
  EXPECT_FALSE(j["slices"][0]["goal_empty"].get<bool>());
  EXPECT_TRUE(j["slices"][1]["goal_empty"].get<bool>());
  const Result one = run("verify " + task("twin_universe") + " --strategy one_step --edr --json");
  ASSERT_EQ(one.status, 1) << one.out;
  EXPECT_FALSE(nlohmann::json::parse(one.out)["edr_reliable"].get<bool>());
}

// LIMITED's search on step_offset: a one-motion plan, re-verified on the fine slices, written with -o as a
// strategy that `cmt verify --edr` accepts and finds EDR-reliable.
TEST(CmtPlanEdr, StepOffsetOneMotionPlanVerifies) {
  const auto path = std::filesystem::temp_directory_path() / "cmt_plan_edr_step.yaml";
  const Result r = run("plan-edr " + task("step_offset") + " --json -o " + path.string());
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["found"].get<bool>());
  ASSERT_EQ(j["strategy"].size(), 1u);
  EXPECT_TRUE(j["verdict"]["edr_reliable"].get<bool>());
  const Result v = run("verify " + path.string() + " --strategy " + j["strategy_name"].get<std::string>() +
                       " --edr --json");
  EXPECT_EQ(v.status, 0) << v.out;
  std::filesystem::remove(path);
}

// Algorithm Multi on hole_width, two-motion plans only: the first motion's push-forward (its terminations in
// every slice) starts the second; the pair is EDR-reliable on the fine slices.
// The plan's physics check: 200 rollouts in 10 worlds drawn over the width, none forbidden (its second
// motion stops in the bottom's right edge, which moves with the width: the predicate needs the sweep between
// slices, docs/edr.md "Between slices").
TEST(CmtPlanEdr, HoleWidthTwoMotionPlanPassesThePhysicsCheck) {
  const auto path = std::filesystem::temp_directory_path() / "cmt_plan_edr_hole.yaml";
  const Result r = run("plan-edr " + task("hole_width") + " --min-motions 2 --json -o " + path.string());
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["motions"].size(), 2u);
  EXPECT_TRUE(j["verdict"]["edr_reliable"].get<bool>());
  for (const auto& s : j["verdict"]["slices"])
    EXPECT_EQ(s["goal_empty"].get<bool>(), s["params"]["hole_width"].get<double>() <= 1);
  const Result v = run("validate " + path.string() +
                       " --strategy plan_edr --edr -n 200 --per-world 20 --mode "
                       "extreme --seed 3 --json");
  ASSERT_EQ(v.status, 0) << v.out;
  const auto check = nlohmann::json::parse(v.out);
  EXPECT_EQ(check["outcomes"]["false_success"].get<int>(), 0);
  EXPECT_EQ(check["outcomes"]["false_failure"].get<int>(), 0);
  EXPECT_GT(check["outcomes"]["success"].get<int>(), 0);
  EXPECT_GT(check["outcomes"]["failure_signalled"].get<int>(), 0);
  std::filesystem::remove(path);
}

// Algorithm Multi on the twin universe: no one-step plan among LIMITED's candidates; with --guaranteed a
// two-step plan that succeeds wherever the goal exists (universe 1), and its physics check: every rollout in
// universe 1 succeeds, every one in universe 2 signals failure.
TEST(CmtPlanEdr, TwinUniverseHasAGuaranteedTwoStepPlanAndNoOneStepPlan) {
  const Result none = run("plan-edr " + task("twin_universe") + " --max-motions 1 --json");
  ASSERT_EQ(none.status, 1) << none.out;
  EXPECT_FALSE(nlohmann::json::parse(none.out)["found"].get<bool>());
  const auto path = std::filesystem::temp_directory_path() / "cmt_plan_edr_twin.yaml";
  const Result r =
      run("plan-edr " + task("twin_universe") + " --min-motions 2 --guaranteed --json -o " + path.string());
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["motions"].size(), 2u);
  EXPECT_TRUE(j["guaranteed"].get<bool>());
  EXPECT_TRUE(j["verdict"]["edr_reliable"].get<bool>());
  const Result v = run("validate " + path.string() +
                       " --strategy plan_edr --edr -n 100 --per-world 10 --mode extreme --seed 2 --json");
  ASSERT_EQ(v.status, 0) << v.out;
  const auto check = nlohmann::json::parse(v.out);
  for (const auto& w : check["worlds"]) {
    const auto& o = w["outcomes"];
    if (w["params"][0].get<double>() == 1) {
      EXPECT_EQ(o["failure_signalled"].get<int>(), 0);  // guaranteed: every rollout reaches the goal
      EXPECT_EQ(o["timeout"].get<int>(), 0);
    } else {
      EXPECT_EQ(o["success"].get<int>(), 0);  // universe 2 has no goal
    }
  }
  EXPECT_EQ(check["outcomes"]["false_success"].get<int>(), 0);
  EXPECT_EQ(check["outcomes"]["false_failure"].get<int>(), 0);
  EXPECT_EQ(check["outcomes"]["missed_success"].get<int>(), 0);
  EXPECT_GT(check["outcomes"]["success"].get<int>(), 0);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace cmt::test
