// `cmt teach` end to end (docs/teaching.md): teaching session files and their errors, the JSON fields of
// docs/contracts.md, the written task, the interactive mode on stdin and the pre-image check in physics.
#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "tests/experiments/cmt_runner.h"

namespace cmt::test {
namespace {

std::string corner() { return std::string(CMT_SOURCE_DIR) + "/tests/experiments/data/corner.yaml"; }

std::string session_file(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + "/" + name + ".yaml";
  std::ofstream(path) << text;
  return path;
}

TEST(CmtTeach, BadSessionFilesExitTwoNamingFileKeyAndReason) {
  struct Case {
    std::string text, key, reason_part;
  };
  const std::vector<Case> cases = {
      {"steps: [lift, nope]\n", "steps[1]", "no motion named 'nope'"},
      {"steps: [{spring: [1, 2]}]\n", "steps[0].spring", "expected 3 numbers"},
      {"steps: [{damper: [0, 0, 0]}]\n", "steps[0].damper", "zero"},
      {"steps: [{spring: [0, 0, 1], damper: [0, 0, 1]}]\n", "steps[0]", "exactly one of spring, damper"},
      {"steps: [{spring: [0, 0, 1], name: lift}]\n", "steps[0].name", "already has a motion named 'lift'"},
      {"steps: [{spring: [0, 0, 1], name: taught_1}]\n", "steps[0].name", "kept for the inline motions"},
      {"steps: []\n", "steps", "empty"},
      {"moves: [lift]\n", "", "moves"},
  };
  for (const Case& c : cases) {
    const std::string path = session_file("bad_session", c.text);
    const Result r = run("teach " + corner() + " --session " + path + " --json");
    EXPECT_EQ(r.status, 2) << c.text;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["error"]["file"], path) << c.text;
    if (!c.key.empty()) {
      EXPECT_EQ(j["error"]["key"], c.key) << c.text;
    }
    EXPECT_NE(j["error"]["message"].get<std::string>().find(c.reason_part), std::string::npos)
        << c.text << " -> " << j["error"]["message"];
  }
}

// Buckley Alg 5.1 on the ridge (models/tasks/ridge.yaml): the taught strategy senses after `down`; the JSON
// and the written task hold it in the branch form, and the written task verifies reliable as it is read back.
TEST(CmtTeach, RidgeSessionWritesASensedDispatchThatVerifies) {
  const std::string task = std::string(CMT_SOURCE_DIR) + "/models/tasks/ridge.yaml";
  const std::string session = std::string(CMT_SOURCE_DIR) + "/models/sessions/ridge_dispatch.yaml";
  const std::string out = testing::TempDir() + "/ridge_taught.yaml";
  const Result r = run("teach " + task + " --session " + session + " --json -o " + out);
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["solved"].get<bool>());
  const auto& strategy = j["strategy"];
  ASSERT_EQ(strategy.size(), 2u) << strategy;
  EXPECT_EQ(strategy[0], "down");
  const auto& branches = strategy[1]["branch"];
  ASSERT_EQ(branches.size(), 2u) << strategy;
  EXPECT_EQ(branches[0]["then"], nlohmann::json::array({"right"}));
  ASSERT_EQ(branches[0]["when"]["position"].size(), 1u);
  const auto& box = branches[0]["when"]["position"][0]["box"];
  EXPECT_LT(box["min"][0].get<double>(), -1.9);  // the left floor, x down to -1 - 4 tan .2, less eps_s
  EXPECT_NEAR(box["max"][0].get<double>(), -0.4, 1e-3);
  EXPECT_EQ(branches[1]["else"], nlohmann::json::array());
  EXPECT_EQ(j["steps"][1]["chain"], strategy);
  EXPECT_GE(j["steps"][1]["dispatches"].get<int>(), 1);

  const Result v = run("verify " + out + " --strategy taught --json");
  ASSERT_EQ(v.status, 0) << v.out;
  const auto verified = nlohmann::json::parse(v.out);
  EXPECT_TRUE(verified["reliable"].get<bool>());
  // The hand-written chains of the task are not reliable.
  for (const std::string s : {"down", "down_right"})
    EXPECT_EQ(run("verify " + task + " --strategy " + s).status, 1) << s;
}

TEST(CmtTeach, CornerSessionPrintsTheStepsWritesTheTaughtTaskAndItVerifies) {
  const std::string session =
      session_file("corner_session", "steps:\n  - lift\n  - {damper: [1, 0, -0.3]}\n");
  const std::string out = testing::TempDir() + "/corner_taught.yaml";
  const std::string view = testing::TempDir() + "/corner_view";
  const Result r =
      run("teach " + corner() + " --session " + session + " --json -o " + out + " --view " + view);
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["solved"].get<bool>());
  ASSERT_EQ(j["steps"].size(), 2u);
  EXPECT_EQ(j["steps"][0]["motion"], "lift");
  EXPECT_TRUE(j["steps"][0]["solved_regions"].empty());
  EXPECT_FALSE(j["steps"][0]["start_remaining"].empty());
  EXPECT_FALSE(j["steps"][0]["blocking"].empty());
  EXPECT_EQ(j["steps"][1]["motion"], "taught_2");
  ASSERT_FALSE(j["steps"][1]["solved_regions"].empty());
  for (const auto& piece : j["steps"][1]["solved_regions"]) {
    EXPECT_TRUE(piece.contains("atom"));
    EXPECT_TRUE(piece.contains("kind"));
    EXPECT_TRUE(piece.contains("polygon"));
  }
  EXPECT_TRUE(j["steps"][1]["start_remaining"].empty());
  EXPECT_EQ(j["strategy"], nlohmann::json::array({"taught_2"}));
  EXPECT_EQ(j["written"]["strategy"], "taught");
  EXPECT_FALSE(j["steps"][1]["stops_from_solved"].empty());
  // The 3-D page: per step a group of layers (step 1 with the stops to avoid, step 2 with the solved cells).
  EXPECT_EQ(j["view"], view + "/index.html");
  std::ifstream page(view + "/index.html");
  const std::string html((std::istreambuf_iterator<char>(page)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("\"group\":\"step 1: lift\""), std::string::npos);
  EXPECT_NE(html.find("stops from which the earlier motions fail"), std::string::npos);
  EXPECT_NE(html.find("\"group\":\"step 2: taught_2\""), std::string::npos);
  EXPECT_NE(html.find("solved start cells"), std::string::npos);
  const Result v = run("verify " + out + " --strategy taught --json");
  EXPECT_EQ(v.status, 0) << v.out;
  EXPECT_TRUE(nlohmann::json::parse(v.out)["reliable"].get<bool>());
}

TEST(CmtTeach, UnsolvedSessionExitsOne) {
  const std::string session = session_file("corner_lift", "steps: [lift]\n");
  const Result r = run("teach " + corner() + " --session " + session + " --json");
  EXPECT_EQ(r.status, 1);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j["solved"].get<bool>());
  EXPECT_TRUE(j["strategy"].is_null());
}

TEST(CmtTeach, StepsAfterTheStartIsSolvedAreNotRun) {
  const std::string session = session_file("corner_extra", "steps: [{damper: [1, 0, -0.3]}, lift]\n");
  const Result r = run("teach " + corner() + " --session " + session + " --json --depth 1");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["steps"].size(), 1u);
  EXPECT_EQ(j["steps_not_run"], 1);
  EXPECT_EQ(j["session"], session);
  EXPECT_EQ(j["options"]["depth"], 1);
  EXPECT_EQ(j["options"]["spring_model"], "velocity");
}

TEST(CmtTeach, InteractiveModeReadsMotionsAndUndoFromStdin) {
  const std::string transcript = testing::TempDir() + "/corner_transcript.yaml";
  const std::string cmd = "printf 'lift\\nundo\\nlift\\nspring 1 2\\ndamper 1 0 -0.3\\nsave " + transcript +
                          "\\n' | " + std::string(CMT_BINARY) + " teach " + corner() + " --json 2>/dev/null";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), pipe)) out += buf.data();
  const int status = pclose(pipe);
  EXPECT_EQ(WEXITSTATUS(status), 0);
  const auto j = nlohmann::json::parse(out);  // the step summaries go to stderr with --json
  EXPECT_TRUE(j["solved"].get<bool>());
  ASSERT_EQ(j["steps"].size(), 2u);  // lift, undone, lift again; the bad line is refused
  EXPECT_EQ(j["steps"][0]["motion"], "lift");
  EXPECT_EQ(j["strategy"].size(), 1u);

  // Without --json the step summaries come on stdout, numbered from 1 after the undo too.
  const std::string text_cmd = "printf 'lift\\nundo\\nlift\\ndamper 1 0 -0.3\\n' | " +
                               std::string(CMT_BINARY) + " teach " + corner() + " 2>/dev/null";
  FILE* text_pipe = popen(text_cmd.c_str(), "r");
  ASSERT_NE(text_pipe, nullptr);
  std::string text;
  while (fgets(buf.data(), buf.size(), text_pipe)) text += buf.data();
  pclose(text_pipe);
  EXPECT_NE(text.find("step 1: lift"), std::string::npos) << text;
  EXPECT_NE(text.find("step 2: taught_2"), std::string::npos) << text;
  EXPECT_EQ(text.find("step 0"), std::string::npos) << text;
}

// Buckley §5.2 taught with the rollouts' model, then checked by physics: rollouts from the solved cells
// (extreme mode: starts mostly at the cells' vertices and edges, errors at their bounds) all reach the goal.
TEST(CmtTeach, HoleSessionTeachesP2ThenP1AndEveryCheckRolloutReachesTheGoal) {
  const std::string out = testing::TempDir() + "/hole_taught.yaml";
  const Result r =
      run("teach " + task("hole") + " --session " + std::string(CMT_SOURCE_DIR) +
          "/models/sessions/hole_teach.yaml --json -o " + out + " --check 300 --threads 2 --seed 5" +
          " --check-dir " + testing::TempDir() + "/hole_check");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["strategy"], nlohmann::json::array({"p2", "p1"}));
  EXPECT_EQ(j["check"]["rollouts"], 300);
  EXPECT_EQ(j["check"]["failures"], 0);
  EXPECT_EQ(j["check"]["outside"], 0);
  EXPECT_EQ(j["check"]["successes"].get<int>() + j["check"]["unstable"].get<int>(), 300);
  const Result v = run("verify " + out + " --strategy taught --json");
  EXPECT_EQ(v.status, 0);
}

TEST(CmtTeach, HoleSessionWithP2TooDeepIsNotSolvedAndSaysWhere) {
  const Result r = run("teach " + task("hole") + " --session " + std::string(CMT_SOURCE_DIR) +
                       "/models/sessions/hole_too_deep.yaml --depth 1");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("hole: NOT solved"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("p2_deep may stop where the motions taught before do not reach the goal: f"),
            std::string::npos)
      << r.out;
}

}  // namespace
}  // namespace cmt::test
