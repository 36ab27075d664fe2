// The 3-D page (experiments/report/view_data.h, view_page.h; `cmt view`, docs/viewer.md): the data holds
// exactly the prediction's pieces and the recorded ends; the page is self-contained; in headless Chromium
// (Debian package chromium) it loads from disk with no console errors, lists its layers, and a screenshot
// is not blank and changes when layers are hidden.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <regex>
#include <sstream>
#include <string>

#include "experiments/report/predicted_sets.h"
#include "experiments/report/view_data.h"
#include "experiments/report/view_page.h"
#include "models/task_loader.h"
#include "tests/experiments/cmt_runner.h"
#include "tests/experiments/sweep_test_util.h"

namespace cmt {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

const char* kRoomTask =
    "name: room\nunits: in\nfriction: 0.2\n"
    "uncertainty: {eps_s: 0.05, eps_p: 0.05, theta_v: 0.1, theta_f: 0.05}\n"
    "cspace: []\nbounds: {min: [0, 0, 0], max: [4, 4, 3]}\n"
    "start: {point: [2, 2, 0]}\ngoal: {point: [0, 0, 0]}\n"
    "motions: {a: {damper: [-1, 0, -0.5]}, b: {damper: [0, -1, -0.5]}}\nstrategies: {s: [a, b]}\n";

const json& layer(const json& data, const std::string& id) {
  for (const json& l : data["layers"])
    if (l["id"] == id) return l;
  throw std::runtime_error("no layer " + id);
}

std::size_t items(const json& l) {
  std::size_t n = 0;
  for (const char* k : {"polygons", "segments", "points", "polylines", "spheres"}) n += l[k].size();
  return n;
}

report::RolloutRow end_row(int rollout, int motion, const Vec3& end, int atom, bool inside) {
  report::RolloutRow r;
  r.rollout = rollout;
  r.motion = motion;
  r.end = end;
  r.atom = atom;
  r.inside = inside;
  return r;
}

// A prediction of two steps (a face piece with a hole and a vertex; an edge interval and a rest ball) and
// five ends: each lands in its layer, and each piece counts the ends of its own step on its atom.
TEST(ViewData, LayersHoldExactlyThePredictedPiecesAndTheRecordedEnds) {
  const auto task = load_task_from_string(kRoomTask, "room");
  report::PredictedSets prediction;
  report::PredictedPiece face{0,
                              "f0",
                              "face",
                              {{1, 0, 0}, {3, 0, 0}, {3, 0, 2}, {1, 0, 2}},
                              {{{1.5, 0, 0.5}, {2.5, 0, 0.5}, {2.5, 0, 1.5}, {1.5, 0, 1.5}}},
                              {},
                              0};
  report::PredictedPiece vertex{20, "v0", "vertex", {{0, 0, 0}}, {}, {}, 0};
  report::PredictedPiece edge{7, "e1", "edge", {{0, 0, 0}, {0, 1, 0}}, {}, {}, 0};
  report::PredictedPiece ball{-1, "free", "free", {}, {}, Vec3(2, 2, 2), 0.25};
  prediction.steps = {{"a", {face, vertex}}, {"b", {edge, ball}}};
  const std::vector<report::RolloutRow> ends = {
      end_row(0, 0, {2, 0, 0.2}, 0, true), end_row(1, 0, {2, 0, 0.3}, 0, true),
      end_row(2, 0, {0, 3, 0}, 5, false), end_row(0, 1, {0, 0.5, 0}, 7, true),
      end_row(1, 1, {0, 0.6, 0}, 0, true)};
  report::ViewInput in;
  in.task = task.get();
  in.title = "room / s";
  in.prediction = &prediction;
  in.ends = &ends;
  in.trajectories = {{0, true, {{2, 2, 0}, {1, 2, 0}, {0, 2, 0}}}};
  const json data = report::view_data(in);

  EXPECT_EQ(data["format"], "cmt-view-1");
  EXPECT_EQ(data["units"], "in");
  EXPECT_EQ(items(layer(data, "cspace-faces")), task->cspace.faces().size());
  EXPECT_EQ(items(layer(data, "cspace-edges")), task->cspace.edges().size());
  EXPECT_EQ(items(layer(data, "start")), 1u);
  EXPECT_EQ(items(layer(data, "goal")), 1u);
  const json& a = layer(data, "predicted-0");
  ASSERT_EQ(a["polygons"].size(), 1u);
  EXPECT_EQ(a["polygons"][0]["holes"].size(), 1u);
  EXPECT_DOUBLE_EQ(a["polygons"][0]["info"]["area"].get<double>(), 4 - 1);  // 2 x 2 less the 1 x 1 hole
  EXPECT_EQ(a["polygons"][0]["info"]["ends on this atom"], 2);              // rollouts 0 and 1 of step 0
  ASSERT_EQ(a["points"].size(), 1u);
  EXPECT_EQ(a["points"][0]["info"]["ends on this atom"], 0);
  const json& b = layer(data, "predicted-1");
  ASSERT_EQ(b["segments"].size(), 1u);
  EXPECT_EQ(b["segments"][0]["info"]["ends on this atom"], 1);
  ASSERT_EQ(b["spheres"].size(), 1u);
  EXPECT_DOUBLE_EQ(b["spheres"][0]["radius"].get<double>(), 0.25);
  EXPECT_EQ(items(layer(data, "ends-inside-0")), 2u);
  EXPECT_EQ(items(layer(data, "ends-outside-0")), 1u);
  EXPECT_EQ(items(layer(data, "ends-inside-1")), 2u);
  EXPECT_EQ(items(layer(data, "ends-outside-1")), 0u);
  EXPECT_EQ(layer(data, "trajectories")["polylines"][0]["points"].size(), 3u);
  // The focus box holds the start, the goal, the pieces, the ball, the ends and the trajectory.
  EXPECT_EQ(data["focus"]["min"], json::array({0, 0, 0}));
  EXPECT_EQ(data["focus"]["max"], json::array({3, 3, 2.25}));
  EXPECT_EQ(data["bounds"]["max"], json::array({4, 4, 3}));
  EXPECT_FALSE(a["polygons"][0]["info"].contains("stick"));  // no classes given: no shading
}

// With the atoms' stick classes, each predicted piece carries its class and is shaded by it: must solid, may
// lighter, never (a slow-stop or contact-lift piece) faint; the free-space ball has no atom and no class.
TEST(ViewData, PredictedPiecesAreShadedByTheirAtomsStickClass) {
  const auto task = load_task_from_string(kRoomTask, "room");
  report::PredictedSets prediction;
  report::PredictedPiece face{0, "f0", "face", {{1, 0, 0}, {3, 0, 0}, {3, 0, 2}}, {}, {}, 0};
  report::PredictedPiece vertex{20, "v0", "vertex", {{0, 0, 0}}, {}, {}, 0};
  report::PredictedPiece edge{7, "e1", "edge", {{0, 0, 0}, {0, 1, 0}}, {}, {}, 0};
  report::PredictedPiece ball{-1, "free", "free", {}, {}, Vec3(2, 2, 2), 0.25};
  prediction.steps = {{"a", {face, vertex, edge, ball}}};
  report::ViewInput in;
  in.task = task.get();
  in.prediction = &prediction;
  std::vector<std::pair<std::string, int>> asked;
  in.stick_class = [&](const LoadedTask&, const std::string& motion, int atom) -> std::string {
    asked.push_back({motion, atom});
    return atom == 0 ? "must" : atom == 20 ? "may" : "never";
  };
  const json l = layer(report::view_data(in), "predicted-0");
  EXPECT_EQ(l["polygons"][0]["info"]["stick"], "must");
  EXPECT_EQ(l["points"][0]["info"]["stick"], "may");
  EXPECT_EQ(l["segments"][0]["info"]["stick"], "never");
  const double must = l["polygons"][0]["style"]["opacity"], may = l["points"][0]["style"]["opacity"],
               never = l["segments"][0]["style"]["opacity"];
  EXPECT_GT(must, may);
  EXPECT_GT(may, never);
  EXPECT_FALSE(l["spheres"][0]["info"].contains("stick"));
  EXPECT_EQ(asked, (std::vector<std::pair<std::string, int>>{{"a", 0}, {"a", 20}, {"a", 7}}));
}

// Text from the task (here the title) cannot end the data's <script> element early.
TEST(ViewPage, TextFromTheTaskCannotCloseTheDataScript) {
  const fs::path dir = test::fresh_dir("view-page");
  const json data = {{"title", "</script><script>alert(1)</script>"}, {"layers", json::array()}};
  report::write_view_page(data, dir / "page.html", "assets");
  std::stringstream html;
  html << std::ifstream(dir / "page.html").rdbuf();
  const std::string text = html.str();
  std::size_t closes = 0;
  for (std::size_t at = text.find("</script>"); at != std::string::npos; at = text.find("</script>", at + 1))
    ++closes;
  EXPECT_EQ(closes, 4u);  // the data and the three script files
  EXPECT_NE(text.find("<title>&lt;/script&gt;"), std::string::npos);
  EXPECT_NE(text.find("src=\"assets/three.min.js\""), std::string::npos);
}

TEST(CmtView, ATaskAloneGivesAPageWithItsAssets) {
  const fs::path dir = test::fresh_dir("view-task");
  const auto r = test::run("view " + test::task("cube") + " -o " + (dir / "out").string() + " --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["task"], "cube");
  EXPECT_EQ(j["layers"].size(), 4u);  // faces, edges, start, goal
  for (const char* f : {"index.html", "three.min.js", "OrbitControls.js", "cmt_view.js"})
    EXPECT_TRUE(fs::exists(dir / "out" / f)) << f;
}

TEST(CmtView, BadArgumentsExitWithStatus2) {
  const fs::path dir = test::fresh_dir("view-bad");
  const std::string out = " -o " + (dir / "out").string() + " --json";
  auto r = test::run("view " + test::task("cube") + " --strategy nope" + out);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("nope"), std::string::npos);
  r = test::run("view " + test::task("cube") + " --results " + (dir / "missing.sqlite").string() +
                " --config 1" + out);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("missing.sqlite"), std::string::npos);
  r = test::run("view " + test::task("cube") + " --rollouts 3" + out);  // rollouts of no strategy
  EXPECT_EQ(r.status, 2);
}

// A strategy that misses its goal (the slide ends in the corner (0,0,0), the goal is (4,0,0)): the sweep
// records a counterexample, and the page's replay of it ends where the validation saw it end.
TEST(CmtView, TheCounterexampleIsReplayedToItsRecordedEnd) {
  const fs::path dir = test::fresh_dir("view-cx");
  std::string yaml = kRoomTask;
  yaml.replace(yaml.find("goal: {point: [0, 0, 0]}"), 24, "goal: {point: [4, 0, 0]}");
  test::write_file(dir / "room.yaml", yaml);
  test::write_file(dir / "spec.yaml",
                   "n: 3\nseeds: [5]\nmode: extreme\ncounterexample_budget: 0\n"
                   "tasks:\n  - file: room.yaml\n    strategies: [s]\n");
  ASSERT_EQ(
      test::run("sweep " + (dir / "spec.yaml").string() + " --db " + (dir / "db.sqlite").string()).status, 0);
  const auto cx =
      json::parse(test::query_rows(dir / "db.sqlite", "SELECT counterexample FROM metrics").at(0).at(0));
  ASSERT_TRUE(cx.is_object());
  const auto r = test::run("view " + (dir / "room.yaml").string() + " --results " +
                           (dir / "db.sqlite").string() + " --config 1 -o " + (dir / "view").string());
  ASSERT_EQ(r.status, 0) << r.out;
  std::stringstream html;
  html << std::ifstream(dir / "view" / "index.html").rdbuf();
  const std::string text = html.str();
  const std::string prefix = "window.CMT_VIEW_DATA = ";
  const std::size_t at = text.find(prefix) + prefix.size();
  const json data = json::parse(text.substr(at, text.find(";</script>", at) - at));
  const json& line = layer(data, "counterexample")["polylines"].at(0);
  EXPECT_EQ(line["info"]["success"], false);
  const json& end = line["points"].back();
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(end[k].get<double>(), cx["end"][k].get<double>(), 1e-12) << k;
  EXPECT_GT(line["points"].size(), 10u);
}

// ---- in a browser ----

bool have_chromium() { return std::system("command -v chromium > /dev/null 2>&1") == 0; }

// Headless Chromium on a file URL: the DOM after the page's scripts ran, or a screenshot.
std::string chromium(const std::string& url, const std::string& what, const fs::path& profile) {
  const std::string cmd =
      "timeout 120 chromium --headless --no-sandbox --disable-gpu-sandbox "
      "--enable-unsafe-swiftshader --use-angle=swiftshader --window-size=1000,700 "
      "--virtual-time-budget=5000 --user-data-dir=" +
      profile.string() + " " + what + " '" + url + "' 2>/dev/null";
  std::string out;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return out;
  char buf[4096];
  while (fgets(buf, sizeof buf, pipe)) out += buf;
  pclose(pipe);
  return out;
}

// Layer ids and item counts as the page lists them (li data-layer, data-items).
std::map<std::string, int> listed_layers(const std::string& dom) {
  std::map<std::string, int> out;
  const std::regex li("data-layer=\"([^\"]+)\" data-items=\"([0-9]+)\"");
  for (auto it = std::sregex_iterator(dom.begin(), dom.end(), li); it != std::sregex_iterator(); ++it)
    out[(*it)[1]] = std::stoi((*it)[2]);
  return out;
}

// Hole `teach` swept with a few rollouts, then its configuration's page from `cmt view --results` and from
// `cmt report`: both load with no errors and list exactly the data's layers; hiding the predicted sets
// changes the picture.
TEST(ViewBrowser, HoleTeachPageLoadsListsItsLayersAndTogglesThem) {
  if (!have_chromium()) GTEST_SKIP() << "chromium is not installed (scripts/setup.sh installs it)";
  const fs::path dir = test::fresh_dir("view-browser");
  test::write_file(dir / "spec.yaml", "n: 4\nseeds: [1]\ntasks:\n  - file: " + test::task("hole") +
                                          "\n    strategies: [teach]\n");
  ASSERT_EQ(
      test::run("sweep " + (dir / "spec.yaml").string() + " --db " + (dir / "db.sqlite").string()).status, 0);
  const auto r = test::run("view " + test::task("hole") + " --results " + (dir / "db.sqlite").string() +
                           " --config 1 -o " + (dir / "view").string() + " --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const json summary = json::parse(r.out);
  EXPECT_EQ(summary["reliable"], true);
  std::map<std::string, int> expected;
  int ends = 0;
  for (const json& l : summary["layers"]) {
    expected[l["id"]] = l["items"];
    if (l["id"].get<std::string>().rfind("ends-", 0) == 0) ends += l["items"].get<int>();
  }
  EXPECT_EQ(ends, test::query_count(dir / "db.sqlite", "SELECT COUNT(*) FROM rollouts"));
  EXPECT_GT(expected.at("predicted-0"), 0);
  EXPECT_GT(expected.at("predicted-1"), 0);

  const std::string url = "file://" + (dir / "view" / "index.html").string();
  const std::string dom = chromium(url, "--dump-dom", dir / "profile");
  EXPECT_NE(dom.find("<div id=\"status\">ready</div>"), std::string::npos) << dom.substr(0, 2000);
  EXPECT_NE(dom.find("id=\"errors\" data-count=\"0\""), std::string::npos);
  EXPECT_EQ(listed_layers(dom), expected);

  const fs::path all = dir / "all.png", hidden = dir / "hidden.png";
  chromium(url, "--screenshot=" + all.string(), dir / "profile");
  chromium(url + "#hide=predicted-0,predicted-1", "--screenshot=" + hidden.string(), dir / "profile");
  const cv::Mat a = cv::imread(all.string()), b = cv::imread(hidden.string());
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(b.empty());
  cv::Scalar mean, stddev;
  cv::meanStdDev(a, mean, stddev);
  EXPECT_GT(stddev[0] + stddev[1] + stddev[2], 10) << "the screenshot is blank";
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  EXPECT_GT(cv::countNonZero(diff.reshape(1)), 500) << "hiding the predicted sets changed nothing";

  // The report links the same page for the configuration.
  ASSERT_EQ(test::run("report " + (dir / "db.sqlite").string() + " -o " + (dir / "report").string()).status,
            0);
  ASSERT_TRUE(fs::exists(dir / "report" / "view" / "config_1.html"));
  std::stringstream index;
  index << std::ifstream(dir / "report" / "index.html").rdbuf();
  EXPECT_NE(index.str().find("view/config_1.html"), std::string::npos);
  const std::string report_dom = chromium("file://" + (dir / "report" / "view" / "config_1.html").string(),
                                          "--dump-dom", dir / "profile");
  EXPECT_NE(report_dom.find("<div id=\"status\">ready</div>"), std::string::npos);
  EXPECT_EQ(listed_layers(report_dom), expected);
}

}  // namespace
}  // namespace cmt
