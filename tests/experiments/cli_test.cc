// End-to-end tests of the cmt program: exit statuses and the JSON fields of docs/contracts.md.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/experiments/cmt_runner.h"
#include "tests/verifier/sensing_tasks.h"

namespace {

using cmt::test::Result;
using cmt::test::run;
using cmt::test::run_stderr;
using cmt::test::task;

TEST(CmtInfo, CubeHasBuckleyCounts) {
  const Result r = run("info " + task("cube") + " --json");
  ASSERT_EQ(r.status, 0);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["faces"], 6);
  EXPECT_EQ(j["edges"], 12);
  EXPECT_EQ(j["vertices"], 8);
  EXPECT_EQ(j["atoms"], 26);
}

TEST(CmtInfo, HoleHasBuckleyCounts) {
  const Result r = run("info " + task("hole") + " --json");
  ASSERT_EQ(r.status, 0);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["faces"], 14);
  EXPECT_EQ(j["edges"], 32);
  EXPECT_EQ(j["vertices"], 20);
  EXPECT_EQ(j["atoms"], 66);
}

TEST(CmtInfo, EveryBuiltInTaskLoads) {
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(CMT_SOURCE_DIR) + "/models/tasks")) {
    if (entry.path().extension() != ".yaml") continue;
    const Result r = run("info " + entry.path().string() + " --json");
    EXPECT_EQ(r.status, 0) << entry.path();
    const auto j = nlohmann::json::parse(r.out, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << entry.path();
    EXPECT_GT(j["faces"].get<int>(), 0) << entry.path();
    EXPECT_EQ(j["atoms"].get<int>(),
              j["faces"].get<int>() + j["edges"].get<int>() + j["vertices"].get<int>());
  }
}

TEST(CmtInfo, AtomListHasGeometry) {
  const Result r = run("info " + task("hole") + " --atoms --json");
  ASSERT_EQ(r.status, 0);
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["atom_list"].size(), 66u);
  int faces = 0;
  for (const auto& a : j["atom_list"]) {
    ASSERT_TRUE(a.contains("id") && a.contains("kind") && a.contains("points"));
    if (a["kind"] == "face") {
      ++faces;
      ASSERT_TRUE(a.contains("normal"));
      EXPECT_GE(a["points"].size(), 3u);
    } else if (a["kind"] == "edge") {
      EXPECT_EQ(a["points"].size(), 2u);
    } else {
      EXPECT_EQ(a["kind"], "vertex");
      EXPECT_EQ(a["points"].size(), 1u);
    }
  }
  EXPECT_EQ(faces, 14);
  // The hole bottom (z = -2, normal +z) is one face, found by its coordinates.
  bool bottom = false;
  for (const auto& a : j["atom_list"])
    if (a["kind"] == "face" && a["normal"][2] == 1.0 && a["points"][0][2] == -2.0) bottom = true;
  EXPECT_TRUE(bottom);
}

TEST(CmtErrors, BadInputExitsTwoWithJsonError) {
  const std::string path = testing::TempDir() + "/bad_task.yaml";
  std::ofstream(path) << "name: bad\nuncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 2.0, theta_f: 0}\n";
  const Result r = run("info " + path + " --json");
  EXPECT_EQ(r.status, 2);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["error"]["file"], path);
  EXPECT_EQ(j["error"]["key"], "uncertainty.theta_v");
}

TEST(CmtErrors, JsonSurvivesBytesThatAreNotUtf8) {
  // The bad byte sits in an unknown key (quoted in the message) and in the name (quoted too).
  for (const std::string& text : {std::string("name: x\n\xbc: 1\n"), std::string("name: \"a\xbc\"\n")}) {
    const std::string path = testing::TempDir() + "/not_utf8.yaml";
    std::ofstream(path, std::ios::binary) << text;
    const Result r = run("info " + path + " --json");
    EXPECT_EQ(r.status, 2);
    const auto j = nlohmann::json::parse(r.out);  // throws (fails the test) on invalid JSON
    EXPECT_NE(j["error"]["message"].get<std::string>().find("\xEF\xBF\xBD"), std::string::npos)
        << "the bad byte is shown as U+FFFD";
  }
}

TEST(CmtErrors, SyntaxErrorHasKeyAndPlace) {
  const std::string path = testing::TempDir() + "/syntax.yaml";
  std::ofstream(path) << "name: x\nuncertainty: {eps_s: [1, 2}\n";
  const Result r = run("info " + path + " --json");
  EXPECT_EQ(r.status, 2);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["error"]["key"], "uncertainty");
  EXPECT_EQ(j["error"]["line"], 2);
  EXPECT_EQ(j["error"]["column"], 27);
}

TEST(CmtErrors, MissingFileAndUsage) {
  EXPECT_EQ(run("info /nonexistent.yaml --json").status, 2);
  EXPECT_EQ(run("no-such-command").status, 2);
  EXPECT_EQ(run("info").status, 2);
}

TEST(CmtExportMjcf, WritesAScene) {
  const std::string out = testing::TempDir() + "/hole_scene.xml";
  const Result r = run("export-mjcf " + task("hole") + " -o " + out + " --json");
  ASSERT_EQ(r.status, 0);
  std::ifstream in(out);
  const std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(xml.find("<mujoco"), std::string::npos);
  EXPECT_NE(xml.find("slide"), std::string::npos);
  EXPECT_EQ(run("export-mjcf " + task("hole") + " -o /nonexistent_dir/x.xml").status, 2);
}

TEST(CmtSticking, ClassifiesEveryAtom) {
  const Result r = run("sticking " + task("hole") + " --motion p2 --json");
  ASSERT_EQ(r.status, 0);
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["atoms"].size(), 66u);
  for (const auto& a : j["atoms"]) {
    ASSERT_TRUE(a.contains("atom") && a.contains("kind") && a.contains("class"));
    const std::string c = a["class"];
    EXPECT_TRUE(c == "must" || c == "may" || c == "never") << c;
  }
  // Spring motions report each face's weak and strong sticking polygons.
  ASSERT_EQ(j["faces"].size(), 14u);
  EXPECT_TRUE(j["faces"][0].contains("weak") && j["faces"][0].contains("strong"));
  // p2 = (0, 2, -1) lies 1 behind the far hole wall y = 1 (normal -y), halfway down: the robot may stick
  // there.
  int wall = -1;
  const auto info = nlohmann::json::parse(run("info " + task("hole") + " --atoms --json").out);
  for (const auto& a : info["atom_list"])
    if (a["kind"] == "face" && a["normal"][1] == -1.0 && a["points"][0][1] == 1.0) wall = a["id"];
  ASSERT_GE(wall, 0);
  EXPECT_NE(j["atoms"][wall]["class"], "never");
}

TEST(CmtSticking, DamperReportsSlidingCones) {
  const Result r = run("sticking " + task("two_blocks") + " --motion v1 --json");
  ASSERT_EQ(r.status, 0);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["model"], "damper");
  // v1 points straight down with theta_v = .25 > atan(.25) = .245: wherever it presses, some admissible
  // velocity leaves the friction cone (face cones, and summed cones toward their open side, have margin .245
  // there), so no atom must stick.
  for (const auto& f : j["faces"]) EXPECT_TRUE(f.contains("sliding"));
  EXPECT_EQ(j["counts"]["must"], 0);
  EXPECT_EQ(run("sticking " + task("hole") + " --motion nope --json").status, 2);
}

TEST(CmtVerify, TwoBlocksDamperStrategies) {
  // down: theta_v = .25 > atan(.25), so the robot may slide off B's top and stop on B's top or the floor
  // right of B, outside the goal (the gap floor): unreliable, exit 1, with the offending pieces listed.
  const Result down = run("verify " + task("two_blocks") + " --strategy down --json");
  ASSERT_EQ(down.status, 1);
  const auto d = nlohmann::json::parse(down.out);
  EXPECT_EQ(d["reliable"], false);
  ASSERT_EQ(d["steps"].size(), 1u);
  EXPECT_EQ(d["steps"][0]["motion"], "v1");
  EXPECT_FALSE(d["steps"][0]["termination"].empty());
  EXPECT_TRUE(d.contains("seconds"));
  EXPECT_EQ(d["timed_out"], false);
  // slide: 45 degrees down-left from B's top; it can stick only in the corner where A's wall meets the gap
  // floor.
  const Result slide = run("verify " + task("two_blocks") + " --strategy slide --json");
  ASSERT_EQ(slide.status, 0);
  const auto s = nlohmann::json::parse(slide.out);
  EXPECT_EQ(s["reliable"], true);
  for (const auto& piece : s["steps"][0]["termination"]) {
    ASSERT_TRUE(piece.contains("atom") && piece.contains("kind") && piece.contains("polygon"));
    EXPECT_NE(piece["kind"], "face");  // the corner edge and its end vertices only
  }
}

TEST(CmtVerify, HoleSpringStrategies) {
  // teach_too_deep: p2_deep = (0,2,-8). On the start face (z = 0, |x| < 1, y < -1) the pull (-x, 2 - y, -8)
  // has tangent/normal (2 - y)/8 < tan(phi + theta_v) = tan(.4474 + .25) = .838 for y > -4.7 (plus eps_s),
  // so the robot may stick on the top before the hole. Then p1 = (0,0,-2.4): at (0,-2,0) the pull (0,2,-2.4)
  // has tangent/normal .83 < .838: it may stick there again, on the top face, outside the goal (hole bottom).
  // A real failure (Buckley L1435): unreliable, failing at the last motion with top-face pieces outside.
  const Result deep = run("verify " + task("hole") + " --strategy teach_too_deep --json");
  ASSERT_EQ(deep.status, 1);
  const auto d = nlohmann::json::parse(deep.out);
  EXPECT_EQ(d["reliable"], false);
  EXPECT_EQ(d["failed_step"], 1);
  bool top = false;
  for (const auto& piece : d["outside_goal"])
    if (piece["kind"] == "face")
      for (const auto& q : piece["polygon"]) top = top || std::abs(q[2].get<double>()) < 1e-9;
  EXPECT_TRUE(top);
  EXPECT_EQ(run("verify " + task("hole") + " --strategy nope --json").status, 2);
}

// A reliable two-motion verdict of `cmt verify --json` whose every termination vertex of motion k passes
// check_k(x, y, z) (the checks say where by the task's geometry).
using EndCheck = std::function<void(double, double, double)>;
void expect_reliable_two_motions(const std::string& args, const EndCheck& first, const EndCheck& second) {
  const Result r = run("verify " + args + " --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto d = nlohmann::json::parse(r.out);
  EXPECT_EQ(d["reliable"], true);
  ASSERT_EQ(d["steps"].size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const auto& termination = d["steps"][k]["termination"];
    ASSERT_FALSE(termination.empty()) << k;
    for (const auto& piece : termination)
      for (const auto& q : piece["polygon"]) {
        SCOPED_TRACE(piece["name"].get<std::string>());
        (k == 0 ? first : second)(q[0].get<double>(), q[1].get<double>(), q[2].get<double>());
      }
  }
}

TEST(CmtVerify, HoleTeachReliableUnderTheVelocityModel) {
  // Buckley §5.2's taught strategy teach = (p2, p1), expected reliable (issue: "hole teach reliable"). By the
  // task's geometry (models/tasks/hole.yaml): p2 = (0,2,-1) lies 1 in behind the far hole wall y = 1, so the
  // robot ends on that wall below its rim (the failure mode was the top face behind the hole, z = 0, y > 1,
  // where p1 may stick); p1 = (0,0,-2.4) then takes it from the wall to the hole bottom z = -2, |x|, |y|
  // <= 1. The velocity model (default; the impedance and admittance forms) keeps p* fixed during a motion.
  expect_reliable_two_motions(
      task("hole") + " --strategy teach",
      [](double, double y, double z) {
        EXPECT_NEAR(y, 1.0, 1e-9);  // on the far wall's plane
        EXPECT_LT(z, 0.0);          // below the rim
      },
      [](double x, double y, double z) {
        EXPECT_NEAR(z, -2.0, 1e-9);
        EXPECT_LE(std::abs(x), 1.0 + 1e-9);
        EXPECT_LE(std::abs(y), 1.0 + 1e-9);
      });
}

TEST(CmtVerify, TslotInsertReliableUnderTheVelocityModel) {
  // Buckley §1.1's T-slot (double hole), strategy insert = (m1, m2), expected reliable (issue: "tslot
  // 2-motion strategy reliable"). By the task's geometry (models/tasks/tslot.yaml): m1 = (0,2,-1) is hole p2,
  // 1 in behind the first hole's far wall y = 1, so the T ends on that wall below its rim (z < 0); m2 =
  // (0,4.5,-6) lies 1.5 beyond the goal face y = 3 and 1 below the second hole's floor z = -5, so the T
  // slides down the wall, passes under the lips and ends on the goal face (x in [-1,1], z in [-5,-2]) or its
  // edges. The invariant half-spaces (m1 never rises above the start's top, m2 never above m1's ends) and the
  // direction cones of slides (a robot on the top at the rim leaves into the hole) are what make it so.
  expect_reliable_two_motions(
      task("tslot") + " --strategy insert",
      [](double, double y, double z) {
        EXPECT_NEAR(y, 1.0, 1e-9);
        EXPECT_LT(z, 0.0);
      },
      [](double x, double y, double z) {
        EXPECT_NEAR(y, 3.0, 1e-9);  // the goal face's plane
        EXPECT_LE(std::abs(x), 1.0 + 1e-9);
        EXPECT_GE(z, -5.0 - 1e-9);
        EXPECT_LE(z, -2.0 + 1e-9);
      });
}

TEST(CmtVerify, TimeLimitGivesAClearAnswer) {
  // peg_in_hole_real teach_too_deep verifies in tens of seconds: 10 ms is not enough.
  const Result r =
      run("verify " + task("peg_in_hole_real") + " --strategy teach_too_deep --time-limit 0.01 --json");
  EXPECT_EQ(r.status, 1);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["reliable"], false);
  EXPECT_EQ(j["timed_out"], true);
  EXPECT_EQ(j["time_limit"], 0.01);
  EXPECT_TRUE(j["steps"].empty());
  EXPECT_NE(j["failure"].get<std::string>().find("timed out"), std::string::npos);
  EXPECT_EQ(run("verify " + task("two_blocks") + " --strategy down --time-limit 0 --json").status, 2);
}

TEST(CmtVerify, PerfectSensingAnswersWithinTheTimeLimit) {
  // eps_s = eps_p = 0 (perfect sensing and positioning) once cut every spring source to the piece budget and
  // ran for more than 20 minutes (docs/verifier.md "Time limit"); the hole's teach is reliable then too (the
  // same motions with smaller errors). 120 s is far above its few seconds: this checks an answer, not a
  // speed.
  std::ifstream in(task("hole"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* key : {"eps_s: 0.2", "eps_p: 0.2"}) {
    const auto at = text.find(key);
    ASSERT_NE(at, std::string::npos) << key;
    text.replace(at, std::string(key).size(), std::string(key).substr(0, 7) + "0");
  }
  const std::string path = testing::TempDir() + "/hole_perfect.yaml";
  std::ofstream(path) << text;
  const Result r = run("verify " + path + " --strategy teach --time-limit 120 --json");
  EXPECT_EQ(r.status, 0);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["timed_out"], false);
  EXPECT_EQ(j["reliable"], true);
}

// A task so far from the world origin that a region cell spans few units in the last place of its
// coordinates gets a note on stderr; the same task near the origin gets none. Both verify reliable: a damper
// pressed straight into a floor sticks where it lands.
TEST(CmtVerify, NotesATaskTooFarFromTheOriginForTheRegionGrid) {
  auto write = [](const std::string& name, double x0) {
    const std::string path = testing::TempDir() + "/" + name + ".yaml";
    const std::string a = std::to_string(x0), b = std::to_string(x0 + 4), c = std::to_string(x0 + 2);
    std::ofstream(path) << "name: " << name << "\nunits: in\nfriction: 0.5\n"
                        << "uncertainty: {eps_s: 0.05, eps_p: 0.05, theta_v: 0.1, theta_f: 0.05}\n"
                        << "cspace: []\nbounds: {min: [" << a << ", 0, 0], max: [" << b << ", 4, 2]}\n"
                        << "start: {point: [" << c << ", 2, 0]}\n"
                        << "goal: {polygon: [[" << a << ", 0, 0], [" << b << ", 0, 0], [" << b << ", 4, 0], ["
                        << a << ", 4, 0]]}\nmotions: {down: {damper: [0, 0, -1]}}\nstrategies: {s: [down]}\n";
    return path;
  };
  const Result far = run_stderr("verify " + write("far_floor", 5e5) + " --strategy s");
  EXPECT_EQ(far.status, 0) << far.out;
  EXPECT_NE(far.out.find("scene scales from the world origin"), std::string::npos) << far.out;
  const Result near = run_stderr("verify " + write("near_floor", 0) + " --strategy s");
  EXPECT_EQ(near.status, 0) << near.out;
  EXPECT_EQ(near.out.find("note:"), std::string::npos) << near.out;
}

// The verifier's model options on the cube's sticking motion (docs/verifier.md), each echoed in the JSON. By
// default: the velocity spring model and the stop rule's kappa at the rollouts' 1 %
// (controllers/termination.h). Under the via-point model `stick` is reliable too. With Coulomb sticking only
// (kappa 0), theta_v .25 > phi .245 lets the spring circle the foot of its target on the floor forever
// ("Termination: sliding forever"): unreliable, exit 1. An unknown model and kappa outside [0, 1] are usage
// errors (exit 2).
TEST(CmtVerify, SpringModelAndStopRuleOptions) {
  const Result d = run("verify " + task("cube") + " --strategy stick --json");
  ASSERT_EQ(d.status, 0);
  const nlohmann::json dj = nlohmann::json::parse(d.out);
  EXPECT_EQ(dj["spring_model"], "velocity");
  EXPECT_DOUBLE_EQ(dj["stop_relative_speed"].get<double>(), 0.01);
  const Result v = run("verify " + task("cube") + " --strategy stick --spring-model via-point --json");
  ASSERT_EQ(v.status, 0);
  EXPECT_EQ(nlohmann::json::parse(v.out)["spring_model"], "via-point");
  const Result z = run("verify " + task("cube") + " --strategy stick --stop-relative-speed 0 --json");
  ASSERT_EQ(z.status, 1);
  const nlohmann::json zj = nlohmann::json::parse(z.out);
  EXPECT_DOUBLE_EQ(zj["stop_relative_speed"].get<double>(), 0);
  EXPECT_NE(zj["failure"].get<std::string>().find("may slide forever"), std::string::npos) << z.out;
  for (const char* bad : {"--spring-model tube", "--stop-relative-speed 2", "--stop-relative-speed -1"})
    EXPECT_EQ(run("verify " + task("cube") + " --strategy stick " + bad + " --json").status, 2) << bad;
}

// Sensing termination (docs/task-format.md "terminate", docs/verifier.md §4.5): the room of
// tests/verifier/sensing_tasks.h. P_s = [0, 1] x [-.5, .5] x [-.5, .5] grown by eps_s = .1 meets the reached
// floor in the rectangle [-.1, 1.1] x [-.6, .6] (area 1.44), which `verify` lists as the step's
// sensing_termination and inside its termination (with the sticking edge x = 5); rollouts stop by "position".
TEST(CmtVerify, SensingTerminationPiecesAndRollouts) {
  const std::string path = testing::TempDir() + "/sensing_room.yaml";
  std::ofstream(path) << cmt::test::sensing_room(
      "{position: {box: {min: [0, -0.5, -0.5], max: [1, 0.5, 0.5]}}}");
  const Result r = run("verify " + path + " --strategy s --json");
  ASSERT_EQ(r.status, 1);  // the floor rectangle is not in the goal (the edge x = 5)
  const auto j = nlohmann::json::parse(r.out);
  const auto& sensing = j["steps"][0]["sensing_termination"];
  ASSERT_EQ(sensing.size(), 1u);
  EXPECT_EQ(sensing[0]["kind"], "face");
  EXPECT_NEAR(sensing[0]["area"].get<double>(), 1.44, 1e-6);
  bool floor_piece = false, edge_piece = false;
  for (const auto& piece : j["steps"][0]["termination"]) {
    if (piece["kind"] == "face") floor_piece = std::abs(piece["area"].get<double>() - 1.44) < 1e-6;
    if (piece["kind"] == "edge") edge_piece = true;
  }
  EXPECT_TRUE(floor_piece);
  EXPECT_TRUE(edge_piece);

  const Result ro = run("rollout " + path + " --strategy s -n 2 --seed 1 --threads 1 --json");
  ASSERT_EQ(ro.status, 1);  // no rollout ends in the goal
  for (const auto& o : nlohmann::json::parse(ro.out)["outcomes"]) EXPECT_EQ(o["termination"], "position");

  // A termination set without a sensible cone: exit 2, naming the key.
  std::ofstream(path) << cmt::test::sensing_room("{force: {direction: [0, 0, 1], angle: 2}}");
  const Result bad = run("verify " + path + " --strategy s --json");
  EXPECT_EQ(bad.status, 2);
  EXPECT_EQ(nlohmann::json::parse(bad.out)["error"]["key"], "motions.m.terminate.force.angle");
}

}  // namespace
