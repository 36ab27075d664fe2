// cmt report end to end: a small results database is written here with the results-store schema (as
// `cmt sweep` writes it), the report is made with the built program, and its documents and figures are
// checked: every PNG linked from both documents, decodable at the figure size, and showing the known data
// where figures.json's axes put it (the predicted polygon's shading, the red cross of the outside end, the
// stick fraction markers and class bands). The first page of index.html is checked for its summary numbers
// (hand-computed from the rows inserted here), an overview table of at most 8 columns with a thumbnail per
// configuration, and every configuration's details one click away; the stick-fraction binning is checked on
// hand-made records. Bad databases exit with status 2 naming the file.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "experiments/report/cspace_figure.h"
#include "experiments/report/edr_figure.h"
#include "experiments/report/extremes_figure.h"
#include "experiments/report/plan_graph_figure.h"
#include "experiments/report/plot_style.h"
#include "experiments/report/report_documents.h"
#include "experiments/report/report_table.h"
#include "experiments/report/results_db.h"
#include "experiments/report/sticking_figure.h"
#include "models/loaded_task.h"
#include "tests/experiments/cmt_runner.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Figure size of the report (experiments/report/plot_canvas.h FigureSize defaults).
constexpr int kFigureWidth = 1000;
constexpr int kFigureHeight = 720;

// The results-store schema (experiments/results/results_store.h).
constexpr const char* kSchema = R"sql(
CREATE TABLE runs(run_id INTEGER PRIMARY KEY, spec_path TEXT, spec_text TEXT, created TEXT);
CREATE TABLE configs(config_id INTEGER PRIMARY KEY, run_id INTEGER, unit_key TEXT UNIQUE NOT NULL,
  task TEXT NOT NULL, task_file TEXT, task_yaml TEXT NOT NULL, strategy TEXT NOT NULL, params TEXT NOT NULL,
  n INTEGER, seed INTEGER, mode TEXT, status TEXT NOT NULL DEFAULT 'pending', finished TEXT);
CREATE TABLE predictions(config_id INTEGER PRIMARY KEY, reliable INTEGER, failure TEXT, verify_seconds REAL,
  verify_json TEXT);
CREATE TABLE rollouts(config_id INTEGER, rollout INTEGER, motion INTEGER, start_x REAL, start_y REAL,
  start_z REAL, end_x REAL, end_y REAL, end_z REAL, atom INTEGER, termination TEXT, inside INTEGER,
  distance REAL, success INTEGER, unstable INTEGER, PRIMARY KEY(config_id, rollout, motion));
CREATE TABLE metrics(config_id INTEGER PRIMARY KEY, rollouts INTEGER, successes INTEGER, unstable INTEGER,
  ends INTEGER, outside INTEGER, soundness REAL, coverage REAL, coverage_radius REAL, contact_tolerance REAL,
  soundness_bug INTEGER, counterexample TEXT, sticking TEXT, rollout_seconds REAL, verify_seconds REAL);
)sql";

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class Db {
 public:
  // fresh: start from an empty file.
  explicit Db(const fs::path& path, bool fresh = true) {
    if (fresh) fs::remove(path);
    EXPECT_EQ(sqlite3_open(path.c_str(), &db_), SQLITE_OK);
  }
  ~Db() { sqlite3_close(db_); }
  void exec(const std::string& sql) {
    char* err = nullptr;
    const int rc = sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err);
    ASSERT_EQ(rc, SQLITE_OK) << (err ? err : "") << "\n" << sql;
  }
  // Inserts with bound text/real/null values: "?" placeholders, values as JSON (string, number or null).
  void insert(const std::string& sql, const std::vector<json>& values) {
    sqlite3_stmt* st = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db_, sql.c_str(), -1, &st, nullptr), SQLITE_OK) << sqlite3_errmsg(db_);
    for (std::size_t i = 0; i < values.size(); ++i) {
      const int k = static_cast<int>(i) + 1;
      const json& v = values[i];
      if (v.is_null())
        sqlite3_bind_null(st, k);
      else if (v.is_string())
        sqlite3_bind_text(st, k, v.get_ref<const std::string&>().c_str(), -1, SQLITE_TRANSIENT);
      else if (v.is_number_integer() || v.is_boolean())
        sqlite3_bind_int64(st, k, v.is_boolean() ? v.get<bool>() : v.get<std::int64_t>());
      else
        sqlite3_bind_double(st, k, v.get<double>());
    }
    EXPECT_EQ(sqlite3_step(st), SQLITE_DONE) << sqlite3_errmsg(db_);
    sqlite3_finalize(st);
  }

 private:
  sqlite3* db_ = nullptr;
};

// The known data of the test database.
const std::vector<std::vector<double>> kTerminationSquare = {
    {-0.5, -0.5, -1}, {0.5, -0.5, -1}, {0.5, 0.5, -1}, {-0.5, 0.5, -1}};  // on the cube's bottom
// Observed ends of motion p1: inside the square (away from its centre) and one outside it.
const std::vector<std::vector<double>> kInsideEnds = {
    {0.3, 0.2, -1}, {-0.3, -0.25, -1}, {0.2, -0.3, -1}, {-0.2, 0.3, -1}, {0.35, -0.1, -1}};
const std::vector<double> kOutsideEnd = {0.8, 0.75, -1};
const double kPhi = std::atan(0.25);

json sticking_json() {
  json records = json::array();
  // alpha/phi 0.52 .. 1.52 gives bins 0.1 wide (sticking_figure.h): in bin [0.5, 0.6) must stick, all
  // stuck; in bin [1.5, 1.6) never, none stuck.
  for (int i = 0; i < 4; ++i)
    records.push_back({{"atom", 5},
                       {"kind", "face"},
                       {"class", "must"},
                       {"command_angle", 0.52 * kPhi},
                       {"phi", kPhi},
                       {"stuck", true},
                       {"speed", 0.0}});
  for (int i = 0; i < 4; ++i)
    records.push_back({{"atom", 5},
                       {"kind", "face"},
                       {"class", "never"},
                       {"command_angle", 1.52 * kPhi},
                       {"phi", kPhi},
                       {"stuck", false},
                       {"speed", 0.9}});
  // A vertex record (bin [0.9, 1.0)) and one without a usable angle (NaN is stored as null).
  records.push_back({{"atom", 20},
                     {"kind", "vertex"},
                     {"class", "may"},
                     {"command_angle", 0.93 * kPhi},
                     {"phi", kPhi},
                     {"stuck", true},
                     {"speed", 0.0}});
  records.push_back({{"atom", 20},
                     {"kind", "vertex"},
                     {"class", "may"},
                     {"command_angle", nullptr},
                     {"phi", kPhi},
                     {"stuck", true},
                     {"speed", 0.0}});
  return {{"trials", 10},
          {"disagreements", 0},
          {"classes", {{"must", 4}, {"may", 2}, {"never", 4}}},
          {"may_stick_fraction", 1.0},
          {"records", records}};
}

// Config 1: cube/stick, done, reliable, 5 ends inside and 1 outside, a sticking check.
// Config 2: two_blocks/slide, pending: nothing but the config row.
// Config 3: cube/stick with a friction override, done, unreliable with empty sets, no rollouts, NULL metrics.
// Config 4: cube/stick at friction 0.2, done, unreliable, 4 of 4 rollouts succeeded, no counterexample: a
// false alarm. Config 5: cube/stick at friction 0.4, done, reliable, 2 of 3 rollouts succeeded: a soundness
// bug with its counterexample's replay command.
const char* const kReplay5 = "cmt rollout models/tasks/cube.yaml --strategy stick -n 1 --seed 77";

void write_results_db(const fs::path& path) {
  Db db(path);
  db.exec(kSchema);
  db.insert("INSERT INTO runs VALUES (1, 'sweep.yaml', 'tasks: [cube]', '2024-05-01T12:00:00Z')", {});
  const std::string cube = read_file(cmt::test::task("cube"));
  const std::string two_blocks = read_file(cmt::test::task("two_blocks"));
  const std::string config = "INSERT INTO configs VALUES (?, 1, ?, ?, ?, ?, ?, ?, ?, 1, 'uniform', ?, ?)";
  db.insert(config, {1, "u1", "cube", cmt::test::task("cube"), cube, "stick", "{}", 6, "done", "2024-05-01"});
  db.insert(config, {2, "u2", "two_blocks", cmt::test::task("two_blocks"), two_blocks, "slide", "{}", 100,
                     "pending", nullptr});
  db.insert(config, {3, "u3", "cube", cmt::test::task("cube"), cube, "stick", R"({"friction":0.5})", 0,
                     "done", "2024-05-01"});
  db.insert(config, {4, "u4", "cube", cmt::test::task("cube"), cube, "stick", R"({"friction":0.2})", 4,
                     "done", "2024-05-01"});
  db.insert(config, {5, "u5", "cube", cmt::test::task("cube"), cube, "stick", R"({"friction":0.4})", 3,
                     "done", "2024-05-01"});

  const json square = {
      {"atom", 0}, {"name", "f0"}, {"kind", "face"}, {"polygon", kTerminationSquare}, {"area", 1.0}};
  const json verify1 = {{"task", "cube"},
                        {"reliable", true},
                        {"steps", {{{"motion", "p1"}, {"termination", {square}}}}},
                        {"seconds", 0.1}};
  db.insert("INSERT INTO predictions VALUES (1, 1, NULL, 0.1, ?)", {verify1.dump()});
  const json verify3 = {{"task", "cube"},
                        {"reliable", false},
                        {"failed_step", 0},
                        {"failure", "p1 may not terminate"},
                        {"steps", {{{"motion", "p1"}, {"termination", json::array()}}}},
                        {"outside_goal", json::array()}};
  db.insert("INSERT INTO predictions VALUES (3, 0, 'p1 may not terminate', 0.2, ?)", {verify3.dump()});
  db.insert("INSERT INTO predictions VALUES (4, 0, 'p1 may not terminate', 0.3, NULL)", {});
  db.insert("INSERT INTO predictions VALUES (5, 1, '', 0.4, NULL)", {});

  const std::string rollout =
      "INSERT INTO rollouts VALUES (1, ?, 0, 0, -1, 1, ?, ?, ?, 0, 'stuck', ?, ?, ?, 0)";
  int index = 0;
  for (const auto& e : kInsideEnds) db.insert(rollout, {index++, e[0], e[1], e[2], 1, 0.0, 1});
  db.insert(rollout, {index++, kOutsideEnd[0], kOutsideEnd[1], kOutsideEnd[2], 0, 0.3, 0});

  const std::string metrics =
      "INSERT INTO metrics VALUES (?, ?, ?, 0, ?, ?, ?, ?, 0.25, 0.01, 0, ?, ?, ?, ?)";
  db.insert(metrics, {1, 6, 5, 6, 1, 5.0 / 6.0, 0.4, nullptr, sticking_json().dump(), 3.5, 0.1});
  db.insert(metrics, {3, 0, 0, 0, 0, nullptr, nullptr, nullptr, nullptr, 0.0, 0.2});
  db.insert(metrics, {4, 4, 4, 4, 0, 1.0, 0.6, nullptr, nullptr, 0.4, 0.3});
  const json counterexample5 = {{"rollout", 2}, {"replay", kReplay5}};
  db.insert(metrics, {5, 3, 2, 10, 1, 0.9, 0.2, counterexample5.dump(), nullptr, 0.2, 0.4});
  db.exec("UPDATE metrics SET soundness_bug = 1 WHERE config_id = 5");
}

struct Report {
  fs::path dir;
  int status = -1;
  std::string markdown, html;
  json figures;  // figures.json
};

// `edit` changes the database before the report is made.
Report make_report(const std::string& name, const std::function<void(const fs::path&)>& edit = {}) {
  const fs::path base = fs::path(testing::TempDir()) / ("cmt_report_test_" + name);
  fs::remove_all(base);
  fs::create_directories(base);
  write_results_db(base / "results.sqlite");
  if (edit) edit(base / "results.sqlite");
  Report r;
  r.dir = base / "report";
  r.status = cmt::test::run("report " + (base / "results.sqlite").string() + " -o " + r.dir.string()).status;
  r.markdown = read_file(r.dir / "report.md");
  r.html = read_file(r.dir / "index.html");
  if (fs::exists(r.dir / "figures.json")) r.figures = json::parse(read_file(r.dir / "figures.json"));
  return r;
}

const json& figure(const Report& r, int config, const std::string& kind) {
  for (const json& f : r.figures["figures"])
    if (f["config_id"] == config && f["kind"] == kind) return f;
  static const json none;
  ADD_FAILURE() << "no figure " << kind << " of config " << config;
  return none;
}

// The pixel of a data point, by the mapping plot_canvas.h documents and figures.json reports.
cv::Point to_pixel(const json& f, double x, double y) {
  const json& p = f["plot"];
  const double px =
      p["left"].get<double>() + (x - f["x"]["min"].get<double>()) /
                                    (f["x"]["max"].get<double>() - f["x"]["min"].get<double>()) *
                                    (p["width"].get<double>() - 1);
  const double py = p["top"].get<double>() + (f["y"]["max"].get<double>() - y) /
                                                 (f["y"]["max"].get<double>() - f["y"]["min"].get<double>()) *
                                                 (p["height"].get<double>() - 1);
  return {static_cast<int>(std::lround(px)), static_cast<int>(std::lround(py))};
}

cv::Vec3b legend_color(const json& f, const std::string& label_prefix) {
  for (const json& e : f["legend"]) {
    const std::string label = e["label"];
    if (label.rfind(label_prefix, 0) == 0) {
      const unsigned v = std::stoul(e["color"].get<std::string>().substr(1), nullptr, 16);
      return {static_cast<unsigned char>(v & 0xff), static_cast<unsigned char>((v >> 8) & 0xff),
              static_cast<unsigned char>(v >> 16)};  // BGR
    }
  }
  ADD_FAILURE() << "no legend entry " << label_prefix << " in " << f.dump();
  return {};
}

cv::Mat load(const Report& r, const json& f) {
  return cv::imread((r.dir / f["file"].get<std::string>()).string());
}

// The cells of the Markdown table row of one configuration.
std::vector<std::string> table_row(const std::string& markdown, int config,
                                   std::vector<std::string>* headers) {
  std::vector<std::string> out;
  std::istringstream in(markdown);
  std::string line;
  auto cells = [](const std::string& l) {
    std::vector<std::string> c;
    std::string cur;
    for (std::size_t i = 1; i < l.size(); ++i) {
      if (l[i] == '|' && l[i - 1] != '\\') {
        c.push_back(cur.substr(1, cur.size() - 2));  // the single spaces around a cell
        cur.clear();
      } else {
        cur += l[i];
      }
    }
    return c;
  };
  while (std::getline(in, line)) {
    if (line.rfind("| config |", 0) == 0) *headers = cells(line);
    if (line.rfind("| " + std::to_string(config) + " |", 0) == 0) out = cells(line);
  }
  return out;
}

std::string cell(const std::vector<std::string>& headers, const std::vector<std::string>& row,
                 const std::string& column) {
  for (std::size_t i = 0; i < headers.size() && i < row.size(); ++i)
    if (headers[i] == column) return row[i];
  ADD_FAILURE() << "no column " << column;
  return "";
}

TEST(Report, WritesDocumentsReferencingEveryFigure) {
  const Report r = make_report("documents");
  ASSERT_EQ(r.status, 0);
  ASSERT_TRUE(fs::exists(r.dir / "index.html"));
  ASSERT_TRUE(fs::exists(r.dir / "report.md"));
  std::set<std::string> pngs;
  for (const auto& e : fs::directory_iterator(r.dir / "figures"))
    if (e.path().extension() == ".png") pngs.insert("figures/" + e.path().filename().string());
  // Config 1: three views + sticking; config 2 (pending): three views of the C-space; configs 3, 4 and 5:
  // three views each.
  EXPECT_EQ(pngs.size(), 16u);
  EXPECT_EQ(r.figures["figures"].size(), pngs.size());
  for (const std::string& png : pngs) {
    EXPECT_NE(r.markdown.find("(" + png + ")"), std::string::npos) << png;
    EXPECT_NE(r.html.find("src=\"" + png + "\""), std::string::npos) << png;
    const cv::Mat img = cv::imread((r.dir / png).string());
    ASSERT_FALSE(img.empty()) << png;
    EXPECT_EQ(img.cols, kFigureWidth) << png;
    EXPECT_EQ(img.rows, kFigureHeight) << png;
    // Not blank: title, axes and data put ink on a good part of it.
    cv::Mat non_white;
    cv::inRange(img, cv::Scalar(255, 255, 255), cv::Scalar(255, 255, 255), non_white);
    const double inked = 1.0 - cv::countNonZero(non_white) / static_cast<double>(img.total());
    EXPECT_GT(inked, 0.02) << png;
  }
}

TEST(Report, TopViewShowsThePredictionAndTheOutsideEnd) {
  const Report r = make_report("top_view");
  ASSERT_EQ(r.status, 0);
  const json& top = figure(r, 1, "top");
  const cv::Mat img = load(r, top);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(top["width"], kFigureWidth);
  EXPECT_EQ(top["x"]["label"], "x (in)");
  EXPECT_EQ(top["y"]["label"], "y (in)");

  // The termination square's centroid (0, 0) has the shading color of motion p1.
  const cv::Vec3b shade = legend_color(top, "predicted end, p1");
  EXPECT_EQ(img.at<cv::Vec3b>(to_pixel(top, 0, 0)), shade);
  // ... and so has a point inside it near a corner, while a point just outside it has not.
  EXPECT_EQ(img.at<cv::Vec3b>(to_pixel(top, -0.45, 0.45)), shade);
  EXPECT_NE(img.at<cv::Vec3b>(to_pixel(top, -0.6, 0.0)), shade);
  // Far outside the C-space ([-1, 1]^3): a corner of the plot area is background.
  const double x_out =
      top["x"]["min"].get<double>() + 0.01 * (top["x"]["max"].get<double>() - top["x"]["min"].get<double>());
  const double y_out =
      top["y"]["max"].get<double>() - 0.01 * (top["y"]["max"].get<double>() - top["y"]["min"].get<double>());
  ASSERT_LT(x_out, -1.0);
  ASSERT_GT(y_out, 1.0);
  EXPECT_EQ(img.at<cv::Vec3b>(to_pixel(top, x_out, y_out)), cv::Vec3b(255, 255, 255));

  // The outside end is a red cross: pure red within a few pixels of its projection, and nowhere near the
  // inside ends.
  const cv::Vec3b red(0, 0, 255);
  EXPECT_EQ(legend_color(top, "observed end outside"), red);
  auto red_near = [&](double x, double y) {
    const cv::Point c = to_pixel(top, x, y);
    for (int dy = -3; dy <= 3; ++dy)
      for (int dx = -3; dx <= 3; ++dx)
        if (img.at<cv::Vec3b>(c + cv::Point(dx, dy)) == red) return true;
    return false;
  };
  EXPECT_TRUE(red_near(kOutsideEnd[0], kOutsideEnd[1]));
  for (const auto& e : kInsideEnds) EXPECT_FALSE(red_near(e[0], e[1])) << e[0] << "," << e[1];
  // Inside ends are dots in the darker shade of their motion.
  const cv::Vec3b dot = legend_color(top, "observed end in set, p1");
  EXPECT_EQ(img.at<cv::Vec3b>(to_pixel(top, kInsideEnds[0][0], kInsideEnds[0][1])), dot);

  // In the front view (x-z) the square is seen edge-on: a thick line at z = -1 in the shading color (the
  // goal's outline runs along its middle).
  const json& front = figure(r, 1, "front");
  const cv::Mat fimg = load(r, front);
  int shaded = 0;
  for (int dy = -3; dy <= 3; ++dy)
    shaded += fimg.at<cv::Vec3b>(to_pixel(front, 0, -1) + cv::Point(0, dy)) == shade;
  EXPECT_GE(shaded, 2);
  EXPECT_EQ(front["y"]["label"], "z (in)");
}

// Pixels darker than light gray in a box of half-size `half` px around `center` (text drawn there).
int dark_pixels(const cv::Mat& img, const cv::Point& center, int half) {
  int dark = 0;
  for (int dy = -half; dy <= half; ++dy)
    for (int dx = -half; dx <= half; ++dx) {
      const cv::Vec3b p = img.at<cv::Vec3b>(center + cv::Point(dx, dy));
      dark += p[0] < 120 && p[1] < 120 && p[2] < 120;
    }
  return dark;
}

TEST(Report, StickingFigureShowsBinnedMarkersCountsAndClassBands) {
  const Report r = make_report("sticking");
  ASSERT_EQ(r.status, 0);
  const json& f = figure(r, 1, "sticking");
  const cv::Mat img = load(r, f);
  ASSERT_FALSE(img.empty());
  const cv::Vec3b face = legend_color(f, "observed, faces");
  const cv::Vec3b vertex = legend_color(f, "observed, vertices");
  EXPECT_NE(face, vertex);
  // Bins 0.1 wide: [0.5, 0.6) all 4 stuck -> a face marker at (0.55, 1); [1.5, 1.6) none -> at (1.55, 0);
  // the vertex record in [0.9, 1.0), stuck -> a vertex marker at (0.95, 1).
  EXPECT_EQ(img.at<cv::Vec3b>(to_pixel(f, 0.55, 1.0)), face);
  EXPECT_EQ(img.at<cv::Vec3b>(to_pixel(f, 1.55, 0.0)), face);
  EXPECT_EQ(img.at<cv::Vec3b>(to_pixel(f, 0.95, 1.0)), vertex);
  // Markers, not lines: halfway between the two face markers there is no face color.
  EXPECT_NE(img.at<cv::Vec3b>(to_pixel(f, 1.05, 0.5)), face);
  // The count (4) is written right of a face marker; right of an empty bin's centre nothing is.
  const cv::Point right(14, 0);
  EXPECT_GT(dark_pixels(img, to_pixel(f, 0.55, 1.0) + right, 5), 5);
  EXPECT_EQ(dark_pixels(img, to_pixel(f, 1.25, 1.0) + right, 5), 0);
  // Behind them the predicted classes of those bins: must, never; a bin without trials has no band.
  EXPECT_EQ(img.at<cv::Vec3b>(to_pixel(f, 0.55, 0.5)), legend_color(f, "predicted must"));
  EXPECT_EQ(img.at<cv::Vec3b>(to_pixel(f, 1.55, 0.5)), legend_color(f, "predicted never"));
  EXPECT_NE(img.at<cv::Vec3b>(to_pixel(f, 1.25, 0.5)), legend_color(f, "predicted never"));
  EXPECT_NE(img.at<cv::Vec3b>(to_pixel(f, 1.25, 0.5)), legend_color(f, "predicted must"));
  // The legend explains the markers and the numbers.
  std::set<std::string> markers;
  bool explains_counts = false;
  for (const json& e : f["legend"]) {
    markers.insert(e["marker"].get<std::string>());
    explains_counts = explains_counts || e["label"] == "numbers: trials per bin";
  }
  EXPECT_TRUE(markers.count("dot") && markers.count("diamond")) << f["legend"].dump();
  EXPECT_TRUE(explains_counts) << f["legend"].dump();
}

TEST(Report, TableHasTheMetricsAndPendingAndMissingValues) {
  const Report r = make_report("table");
  ASSERT_EQ(r.status, 0);
  std::vector<std::string> headers;
  const auto row1 = table_row(r.markdown, 1, &headers);
  ASSERT_FALSE(row1.empty()) << r.markdown;
  EXPECT_EQ(cell(headers, row1, "task"), "cube");
  EXPECT_EQ(cell(headers, row1, "verdict"), "reliable");
  EXPECT_EQ(cell(headers, row1, "N"), "6");
  EXPECT_EQ(cell(headers, row1, "seed"), "1");
  EXPECT_EQ(cell(headers, row1, "successes"), "5 (83.3%)");
  EXPECT_EQ(cell(headers, row1, "outside"), "1");
  EXPECT_EQ(cell(headers, row1, "soundness"), "0.8333");
  EXPECT_EQ(cell(headers, row1, "coverage (radius)"), "0.4000 (r 0.250)");
  EXPECT_EQ(cell(headers, row1, "soundness bug"), "no");
  EXPECT_NE(cell(headers, row1, "figures").find("(figures/config_1_top.png)"), std::string::npos);

  const auto row2 = table_row(r.markdown, 2, &headers);
  ASSERT_FALSE(row2.empty());
  EXPECT_EQ(cell(headers, row2, "status"), "pending");
  EXPECT_EQ(cell(headers, row2, "verdict"), "pending");
  EXPECT_EQ(cell(headers, row2, "soundness"), "pending");

  const auto row3 = table_row(r.markdown, 3, &headers);
  ASSERT_FALSE(row3.empty());
  EXPECT_EQ(cell(headers, row3, "params"), R"({"friction":0.5})");
  EXPECT_EQ(cell(headers, row3, "verdict"), "NOT reliable");
  EXPECT_EQ(cell(headers, row3, "soundness"), "n/a");
  EXPECT_NE(r.markdown.find("the predicted termination sets are empty"), std::string::npos);
  EXPECT_NE(r.markdown.find("verifier: p1 may not terminate"), std::string::npos);

  EXPECT_NE(r.markdown.find("- **units:** 5 configurations: 4 done, 1 pending"), std::string::npos);
  EXPECT_NE(r.html.find("0.8333"), std::string::npos);
}

// The text between the first `open` at or after `from` and the next `close`; "" when either is missing.
std::string between(const std::string& s, const std::string& open, const std::string& close,
                    std::size_t from = 0) {
  const std::size_t a = s.find(open, from);
  if (a == std::string::npos) return "";
  const std::size_t b = s.find(close, a + open.size());
  return b == std::string::npos ? "" : s.substr(a + open.size(), b - a - open.size());
}

std::size_t occurrences(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + what.size())) ++n;
  return n;
}

std::vector<std::string> split(const std::string& s, const std::string& separator) {
  std::vector<std::string> out;
  std::size_t from = 0;
  for (std::size_t at = s.find(separator); at != std::string::npos; at = s.find(separator, from)) {
    out.push_back(s.substr(from, at - from));
    from = at + separator.size();
  }
  out.push_back(s.substr(from));
  return out;
}

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&')
      out += "&amp;";
    else if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

std::string html_section(const std::string& html, int config) {
  return between(html, "<section class=\"config\" id=\"config-" + std::to_string(config) + "\">",
                 "</section>");
}

// The notes of a configuration's Markdown section: its "- " lines.
std::vector<std::string> markdown_notes(const std::string& markdown, int config) {
  const std::size_t start = markdown.find("## Config " + std::to_string(config) + ":");
  if (start == std::string::npos) return {};
  const std::string section = markdown.substr(start, markdown.find("\n## ", start) - start);
  std::vector<std::string> notes;
  for (const std::string& line : split(section, "\n"))
    if (line.rfind("- ", 0) == 0) notes.push_back(line.substr(2));
  return notes;
}

// A section as report.cc starts one: the row and its label (the other members are left empty).
cmt::report::ConfigSection section_of(const cmt::report::ConfigRow& row, const std::string& label = "") {
  cmt::report::ConfigSection s;
  s.row = &row;
  s.label = label;
  return s;
}

// The numbers by hand from the rows write_results_db inserts (configs 1..5, see there).
TEST(Report, SummaryHasTheHandComputedNumbers) {
  const fs::path base = fs::path(testing::TempDir()) / "cmt_report_test_summary";
  fs::remove_all(base);
  fs::create_directories(base);
  write_results_db(base / "results.sqlite");
  const cmt::report::ResultsDb db = cmt::report::read_results_db(base / "results.sqlite");
  std::vector<cmt::report::ConfigSection> sections;
  for (const cmt::report::ConfigRow& c : db.configs) sections.push_back(section_of(c, c.task));
  const cmt::report::SummaryStats s = cmt::report::build_report_content(db, sections).stats;
  EXPECT_EQ(s.configs, 5);
  EXPECT_EQ(s.done, 4);
  EXPECT_EQ(s.pending, 1);       // config 2
  EXPECT_EQ(s.reliable, 2);      // configs 1, 5
  EXPECT_EQ(s.not_reliable, 2);  // configs 3, 4
  EXPECT_EQ(s.no_verdict, 1);    // config 2
  EXPECT_EQ(s.timed_out, 0);
  EXPECT_EQ(s.rollouts, 6 + 0 + 4 + 3);                               // 13
  EXPECT_EQ(s.successes, 5 + 0 + 4 + 2);                              // 11
  EXPECT_EQ(s.ends, 6 + 0 + 4 + 10);                                  // 20
  EXPECT_EQ(s.outside, 1 + 0 + 0 + 1);                                // 2
  EXPECT_EQ(s.soundness_bugs, 1);                                     // config 5
  EXPECT_EQ(s.false_alarms, 1);                                       // config 4; config 3 has no rollouts
  EXPECT_NEAR(s.min_soundness, 5.0 / 6.0, 1e-12);                     // config 3's is NULL
  EXPECT_NEAR(s.mean_soundness, (5.0 / 6.0 + 1.0 + 0.9) / 3, 1e-12);  // 0.9111
  EXPECT_NEAR(s.min_coverage, 0.2, 1e-12);
  EXPECT_NEAR(s.mean_coverage, (0.4 + 0.6 + 0.2) / 3, 1e-12);
  EXPECT_NEAR(s.verify_seconds, 0.1 + 0.2 + 0.3 + 0.4, 1e-12);  // the predictions
  EXPECT_NEAR(s.rollout_seconds, 3.5 + 0.0 + 0.4 + 0.2, 1e-12);

  // The same numbers in words at the top of both documents.
  const Report r = make_report("summary");
  ASSERT_EQ(r.status, 0);
  const std::vector<std::pair<std::string, std::string>> lines = {
      {"units", "5 configurations: 4 done, 1 pending"},
      {"verdicts", "2 reliable, 2 NOT reliable, 1 without a verdict yet"},
      {"rollouts", "11 of 13 succeeded, 0 unstable; 2 of 20 motion ends outside the prediction"},
      {"soundness", "min 0.8333, mean 0.9111; 1 soundness bug (verified reliable, a rollout failed)"},
      {"coverage", "min 0.2000, mean 0.4000"},
      {"false alarms", "1 (verified NOT reliable, every rollout succeeded, no counterexample found)"},
      {"time", "verify 1.00 s, rollouts 4.10 s (totals)"}};
  const std::string html_summary = between(r.html, "<table class=\"summary\">", "</table>");
  for (const auto& [label, text] : lines) {
    EXPECT_NE(r.markdown.find("- **" + label + ":** " + text + "\n"), std::string::npos) << label;
    EXPECT_NE(html_summary.find("<tr><th>" + label + "</th><td>" + text + "</td></tr>"), std::string::npos)
        << label << "\n"
        << html_summary;
  }
  // Both open on it: before the tables.
  EXPECT_LT(r.markdown.find("## Summary"), r.markdown.find("## Configurations"));
  EXPECT_LT(r.html.find("<table class=\"summary\">"), r.html.find("<table class=\"overview\">"));
}

// A verifier out of its time budget gives no verdict: not a false alarm even when every rollout succeeded.
TEST(Report, TimedOutVerifierIsNoVerdictAndNoFalseAlarm) {
  cmt::report::ConfigRow timed_out;
  timed_out.status = "done";
  timed_out.prediction = cmt::report::PredictionRow{false, "verifier: timed out after 180 s", 180.0, nullptr};
  timed_out.metrics = cmt::report::MetricsRow{};
  timed_out.metrics->rollouts = timed_out.metrics->successes = 2;
  cmt::report::ConfigRow false_alarm = timed_out;
  false_alarm.config_id = 2;
  false_alarm.prediction->failure = "v1 may not terminate";
  const cmt::report::SummaryStats s =
      cmt::report::summarize({section_of(timed_out), section_of(false_alarm)});
  EXPECT_EQ(s.timed_out, 1);
  EXPECT_EQ(s.not_reliable, 1);
  EXPECT_EQ(s.false_alarms, 1);
  EXPECT_FALSE(cmt::report::is_false_alarm(timed_out));
  EXPECT_TRUE(cmt::report::is_false_alarm(false_alarm));
  false_alarm.metrics->counterexample = {{"replay", "cmt rollout ..."}};  // the search found one
  EXPECT_FALSE(cmt::report::is_false_alarm(false_alarm));
}

TEST(Report, OverviewTableIsNarrowWithAThumbnailPerConfiguration) {
  const Report r = make_report("overview");
  ASSERT_EQ(r.status, 0);
  const std::string table = between(r.html, "<table class=\"overview\">", "</table>");
  ASSERT_FALSE(table.empty()) << r.html;
  EXPECT_NE(r.html.find("table.overview { table-layout: fixed; width: 100%; }"), std::string::npos);
  std::vector<std::string> rows = split(table, "<tr>");
  ASSERT_GE(rows.size(), 2u);
  const std::size_t columns = occurrences(rows[1], "<th>");
  EXPECT_GE(columns, 6u);
  EXPECT_LE(columns, 8u);
  EXPECT_EQ(occurrences(between(table, "<colgroup>", "</colgroup>"), "<col"), columns);
  rows.erase(rows.begin(), rows.begin() + 2);  // before the first row, the header row
  ASSERT_EQ(rows.size(), 5u);                  // one per configuration, in order
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string id = std::to_string(i + 1);
    SCOPED_TRACE("config " + id);
    EXPECT_EQ(rows[i].rfind("<td><a href=\"#config-" + id + "\">" + id + "</a></td>", 0), 0u) << rows[i];
    EXPECT_EQ(occurrences(rows[i], "<td>"), columns);
    // The thumbnail: the first C-space view, small, linked to the full figure.
    const std::string png = "figures/config_" + id + "_front.png";
    EXPECT_NE(rows[i].find("<a href=\"" + png + "\"><img class=\"thumb\" src=\"" + png + "\""),
              std::string::npos)
        << rows[i];
    EXPECT_NE(rows[i].find("width=\"120\""), std::string::npos);
    EXPECT_TRUE(fs::exists(r.dir / png)) << png;
    EXPECT_NE(rows[i].find("<a href=\"#config-" + id + "\">details</a>"), std::string::npos);
    EXPECT_NE(html_section(r.html, static_cast<int>(i + 1)), "") << "no section to link to";
  }
  // Key columns: verdict, rollouts, soundness (with the bug flag), coverage; the false alarm says so.
  EXPECT_NE(rows[0].find("<td>reliable</td><td>5/6</td><td>0.8333</td><td>0.4000</td>"), std::string::npos)
      << rows[0];
  EXPECT_NE(rows[1].find("<td>pending</td><td>pending</td><td>pending</td><td>pending</td>"),
            std::string::npos)
      << rows[1];
  EXPECT_NE(rows[3].find("<td>NOT reliable (no failure found)</td><td>4/4</td>"), std::string::npos)
      << rows[3];
  EXPECT_NE(rows[4].find("<td>0.9000, BUG</td>"), std::string::npos) << rows[4];
  // Replay commands and notes are not on the first page.
  EXPECT_EQ(table.find(kReplay5), std::string::npos);
  EXPECT_EQ(table.find("<code>"), std::string::npos);
}

// Every column of the full table (report.md) and every note are in the configuration's HTML section.
TEST(Report, DetailsKeepEveryMetricNoteAndFigure) {
  const Report r = make_report("details");
  ASSERT_EQ(r.status, 0);
  for (int config = 1; config <= 5; ++config) {
    SCOPED_TRACE("config " + std::to_string(config));
    const std::string section = html_section(r.html, config);
    ASSERT_FALSE(section.empty());
    std::vector<std::string> headers;
    const std::vector<std::string> row = table_row(r.markdown, config, &headers);
    ASSERT_EQ(row.size(), headers.size());
    for (std::size_t k = 0; k < headers.size(); ++k) {
      if (headers[k] == "figures") continue;  // links, checked below as the figures themselves
      const std::string& md = row[k];
      const bool code = md.size() > 2 && md.front() == '`' && md.back() == '`';
      const std::string value =
          code ? "<code>" + html_escape(md.substr(1, md.size() - 2)) + "</code>" : html_escape(md);
      EXPECT_NE(section.find("<tr><th>" + html_escape(headers[k]) + "</th><td>" + value + "</td></tr>"),
                std::string::npos)
          << headers[k] << " = " << value;
    }
    const std::vector<std::string> notes = markdown_notes(r.markdown, config);
    EXPECT_FALSE(notes.empty());
    for (const std::string& note : notes)
      EXPECT_NE(section.find("<li>" + html_escape(note) + "</li>"), std::string::npos) << note;
    for (const json& f : r.figures["figures"]) {
      if (f["config_id"] != config) continue;
      EXPECT_NE(section.find("<img src=\"" + f["file"].get<std::string>() + "\""), std::string::npos)
          << f["file"];
    }
  }
  // The counterexample's replay command, in the table and in the notes of config 5.
  const std::string section5 = html_section(r.html, 5);
  EXPECT_NE(section5.find("<td><code>" + html_escape(kReplay5) + "</code></td>"), std::string::npos);
  EXPECT_NE(section5.find("<li>counterexample, replay with: " + html_escape(kReplay5) + "</li>"),
            std::string::npos);
  EXPECT_NE(section5.find("SOUNDNESS BUG"), std::string::npos);
  EXPECT_NE(html_section(r.html, 3).find("<li>verifier: p1 may not terminate</li>"), std::string::npos);
  EXPECT_NE(html_section(r.html, 1).find("<li>sticking check: 10 trials, 0 disagreements</li>"),
            std::string::npos);
  // The sweep runs are one click away too.
  EXPECT_NE(r.html.find("<details><summary>1 sweep run</summary>"), std::string::npos);
  EXPECT_NE(r.html.find("run 1: sweep.yaml, created 2024-05-01T12:00:00Z"), std::string::npos);
}

TEST(Report, ViewPageIsLinkedFromTheRowAndTheSection) {
  cmt::report::ResultsDb db;
  db.path = "results.sqlite";
  cmt::report::ConfigRow with_view, without_view;
  with_view.config_id = 7;
  without_view.config_id = 8;
  for (cmt::report::ConfigRow* c : {&with_view, &without_view}) {
    c->task = "cube";
    c->strategy = "stick";
    c->params = json::object();
    c->status = "pending";
    c->unit_key = "u" + std::to_string(c->config_id);
  }
  cmt::report::ConfigSection viewed = section_of(with_view, "cube / stick");
  viewed.figures = {{"figures/config_7_front.png", "front view"}};
  viewed.view_page = "views/config_7.html";
  const cmt::report::ReportContent content =
      cmt::report::build_report_content(db, {viewed, section_of(without_view, "cube / stick")});
  const std::string html = cmt::report::render_html(content);
  const std::string link = "<a href=\"views/config_7.html\">3-D view</a>";
  const std::string table = between(html, "<table class=\"overview\">", "</table>");
  EXPECT_EQ(occurrences(table, link), 1u) << table;
  EXPECT_EQ(occurrences(html_section(html, 7), link), 1u);
  EXPECT_EQ(occurrences(html, "3-D view"), 2u);  // config 8 has none
  EXPECT_EQ(occurrences(html_section(html, 8), "3-D view"), 0u);

  const std::string markdown = cmt::report::render_markdown(content);
  const std::string section7 = between(markdown, "## Config 7:", "## Config 8:");
  EXPECT_NE(section7.find("[3-D view](views/config_7.html)"), std::string::npos) << markdown;
  EXPECT_EQ(occurrences(markdown, "3-D view"), 1u);
}

// Hand-made records at phi = 0.5: alpha/phi from 0.12 to 1.17 (span 1.05) gives bins 0.1 wide (0.05 would
// need 22 bins from 0.10 to 1.15, more than 15), from 0.1: 11 bins.
TEST(Report, StickingRecordsAreBinnedPerKind) {
  auto record = [](const char* kind, const char* cls, json angle, double phi, bool stuck) {
    json r = {{"atom", 1}, {"class", cls}, {"command_angle", angle}, {"phi", phi}, {"stuck", stuck}};
    if (kind) r["kind"] = kind;
    return r;
  };
  const json sticking = {{"records",
                          {record("vertex", "may", 0.305, 0.5, true),   // 0.61
                           record("face", "must", 0.06, 0.5, true),     // 0.12
                           record("face", "must", 0.09, 0.5, true),     // 0.18
                           record("face", "may", 0.165, 0.5, false),    // 0.33
                           record("edge", "may", 0.18, 0.5, true),      // 0.36
                           record("edge", "never", 0.475, 0.5, false),  // 0.95
                           record("face", "never", 0.585, 0.5, false),  // 1.17
                           record("face", "must", nullptr, 0.5, true),  // no angle
                           record("edge", "must", 0.1, 0.0, true),      // no friction angle
                           record(nullptr, "must", 0.1, 0.5, true)}}};  // no kind
  const cmt::report::StickBinning b = cmt::report::bin_sticking_records(sticking);
  EXPECT_NEAR(b.width, 0.1, 1e-12);
  EXPECT_NEAR(b.origin, 0.1, 1e-12);
  EXPECT_EQ(b.count, 11);
  EXPECT_EQ(b.skipped, 3);
  EXPECT_EQ(b.kinds, (std::vector<std::string>{"face", "edge", "vertex"}));
  struct Expected {
    std::string kind;
    int index, trials, stuck;
    std::array<int, 3> classes;
  };
  const std::vector<Expected> expected = {{"face", 0, 2, 2, {2, 0, 0}},  {"face", 2, 1, 0, {0, 1, 0}},
                                          {"face", 10, 1, 0, {0, 0, 1}}, {"edge", 2, 1, 1, {0, 1, 0}},
                                          {"edge", 8, 1, 0, {0, 0, 1}},  {"vertex", 5, 1, 1, {0, 1, 0}}};
  ASSERT_EQ(b.bins.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    SCOPED_TRACE(i);
    const cmt::report::StickBin& bin = b.bins[i];
    EXPECT_EQ(bin.kind, expected[i].kind);
    EXPECT_EQ(bin.index, expected[i].index);
    EXPECT_EQ(bin.trials, expected[i].trials);
    EXPECT_EQ(bin.stuck, expected[i].stuck);
    EXPECT_EQ(bin.classes, expected[i].classes);
    EXPECT_NEAR(bin.lo, 0.1 + 0.1 * expected[i].index, 1e-12);
    EXPECT_NEAR(bin.hi, bin.lo + 0.1, 1e-12);
  }
  EXPECT_NEAR(b.bins[0].centre(), 0.15, 1e-12);
  EXPECT_DOUBLE_EQ(b.bins[0].fraction(), 1.0);
  EXPECT_DOUBLE_EQ(b.bins[1].fraction(), 0.0);

  EXPECT_TRUE(cmt::report::bin_sticking_records(json::object()).bins.empty());
  EXPECT_THROW(cmt::report::bin_sticking_records({{"records", 3}}), std::invalid_argument);
  EXPECT_THROW(cmt::report::bin_sticking_records({{"records", {1, 2}}}), std::invalid_argument);
}

TEST(Report, StickBinWidthIsANiceStepGivingAtMost15Bins) {
  using cmt::report::stick_bin_width;
  EXPECT_NEAR(stick_bin_width(0.52, 1.52), 0.1, 1e-12);  // 0.5 .. 1.5: 11 bins (0.05: 21)
  EXPECT_NEAR(stick_bin_width(0.0, 3.0), 0.25, 1e-12);   // 13 bins (0.2: 16)
  EXPECT_NEAR(stick_bin_width(0.0, 0.05), 0.01, 1e-12);  // the minimum width: 6 bins
  EXPECT_NEAR(stick_bin_width(0.7, 0.7), 0.01, 1e-12);   // one value
}

// Runs the report on a database with --json and returns the error object.
json report_error(const fs::path& db, const fs::path& out, int* status) {
  const cmt::test::Result r = cmt::test::run("report " + db.string() + " -o " + out.string() + " --json");
  *status = r.status;
  return r.out.empty() ? json() : json::parse(r.out)["error"];
}

// The adversarial search of config 1 (cube / stick), as the sweep stores it (metrics.falsify, schema
// version 3): one end outside, one of two pieces unreached.
const char* const kFalsifyReplay = "cmt rollout models/tasks/cube.yaml --strategy stick --errors 0.5,1";

json falsify_json_of_config1() {
  const json reached = {
      {"step", 0},         {"motion", "p1"},       {"atom", 0},         {"atom_name", "f0"},
      {"kind", "face"},    {"measure", 1.0},       {"reached", true},   {"reached_by", "random"},
      {"searched", false}, {"search_rollouts", 0}, {"closest_end", 0.0}};
  const json unreached = {
      {"step", 0},        {"motion", "p1"},        {"atom", 3},          {"atom_name", "e3"},
      {"kind", "edge"},   {"measure", 0.5},        {"reached", false},   {"reached_by", nullptr},
      {"searched", true}, {"search_rollouts", 16}, {"closest_end", 0.02}};
  return {{"task", "cube"},
          {"strategy", "stick"},
          {"reliable", true},
          {"budget", 32},
          {"coverage_budget", 16},
          {"searches", 5},
          {"rollouts", 48},
          {"unstable", 2},
          {"outside", 1},
          {"soundness_bugs",
           {{{"how", "falsify"},
             {"motion", "p1"},
             {"step", 0},
             {"distance", 0.0125},
             {"replay", kFalsifyReplay}}}},
          {"motions", {{{"step", 0}, {"motion", "p1"}, {"best_signed_distance", 0.0125}}}},
          {"coverage_before", 0.4},
          {"coverage_after", 0.55},
          {"pieces", {reached, unreached}},
          {"unreached_pieces", {unreached}},
          {"gaps",
           {{{"step", 0},
             {"motion", "p1"},
             {"point", {0.5, 0, -1}},
             {"gap", 0.4},
             {"closest_end", 0.1},
             {"reached", true},
             {"rollouts", 16}},
            {{"step", 0},
             {"motion", "p1"},
             {"point", {-0.9, 0.9, -1}},
             {"gap", 1.0},
             {"closest_end", 0.8},
             {"reached", false},
             {"rollouts", 32}}}},
          {"gaps_reached", 1}};
}

TEST(Report, AdversarialRolloutsSectionListsTheSearch) {
  const Report r = make_report("falsify", [](const fs::path& db) {
    Db edit(db, false);
    edit.exec("ALTER TABLE metrics ADD COLUMN falsify TEXT");
    edit.insert("UPDATE metrics SET falsify = ? WHERE config_id = 1", {falsify_json_of_config1().dump()});
  });
  ASSERT_EQ(r.status, 0);
  // HTML: the section after the overview, one row (config 1 only).
  const std::string html = between(r.html, "<h2 id=\"falsify\">Adversarial rollouts</h2>", "</table>");
  ASSERT_FALSE(html.empty()) << r.html;
  EXPECT_LT(r.html.find("<h2 id=\"overview\">"), r.html.find("<h2 id=\"falsify\">"));
  EXPECT_LT(r.html.find("<h2 id=\"falsify\">"), r.html.find("<h2 id=\"details\">"));
  EXPECT_EQ(occurrences(html, "<tr>"), 2u);  // the header and config 1
  EXPECT_NE(html.find("<tr><td><a href=\"#config-1\">1</a></td><td>cube / stick</td><td>reliable</td>"
                      "<td>48 (2 unstable)</td><td>5</td><td>1</td><td>p1 0.0125 (outside)</td>"
                      "<td>0.4000 → 0.5500</td><td>1/2 (random 1)</td>"
                      "<td>step 0 p1: e3 (edge, measure 0.5, closest end 0.02, searched)</td>"
                      "<td>1/2; unreached: p1 at (-0.9, 0.9, -1), closest end 0.8</td><td>-</td></tr>"),
            std::string::npos)
      << html;
  // Markdown: the same table under its own heading.
  const std::string md = between(r.markdown, "## Adversarial rollouts", "## Config 1:");
  ASSERT_FALSE(md.empty()) << r.markdown;
  EXPECT_NE(
      md.find("| [1](#config-1) | cube / stick | reliable | 48 (2 unstable) | 5 | 1 | p1 0.0125 "
              "(outside) | 0.4000 → 0.5500 | 1/2 (random 1) | step 0 p1: e3 (edge, measure 0.5, "
              "closest end 0.02, searched) | 1/2; unreached: p1 at (-0.9, 0.9, -1), closest end 0.8 | - |"),
      std::string::npos)
      << md;
  // The note with the farthest end's replay command, in both documents; the summary line.
  const std::string note = std::string(
                               "adversarial search: 48 search rollouts, 1 motion end outside the "
                               "prediction (farthest 0.0125), replay with: ") +
                           kFalsifyReplay;
  EXPECT_NE(html_section(r.html, 1).find("<li>" + html_escape(note) + "</li>"), std::string::npos);
  EXPECT_NE(r.markdown.find("- " + note), std::string::npos);
  EXPECT_NE(r.markdown.find("- **adversarial rollouts:** 1 configuration searched: 48 search rollouts, 1 "
                            "motion ends outside the prediction found by the search; mean coverage 0.4000 "
                            "before, 0.5500 after"),
            std::string::npos)
      << r.markdown;

  // A search stored without `search_ends` still has its figure (the pieces and gaps).
  EXPECT_EQ(figure(r, 1, "falsify_0")["kind"], "falsify_0");

  // Without search data (no falsify column, or NULL): no section.
  const cmt::report::ResultsDb db;
  cmt::report::ConfigRow plain;
  plain.status = "done";
  plain.metrics = cmt::report::MetricsRow{};
  const cmt::report::ReportContent content = cmt::report::build_report_content(db, {section_of(plain)});
  EXPECT_TRUE(content.falsify.rows.empty());
  EXPECT_EQ(cmt::report::render_html(content).find("Adversarial rollouts"), std::string::npos);
  EXPECT_EQ(cmt::report::render_markdown(content).find("Adversarial rollouts"), std::string::npos);

  // The gaps cell: "-" without a gap search, "0/0 (no gap)" when it found nothing uncovered, and at most
  // three unreached gaps, the nearest approaches first.
  const auto gaps_cell = [&](const json& falsify) {
    cmt::report::ConfigRow row = plain;
    row.metrics->falsify = falsify;
    const cmt::report::ReportContent c = cmt::report::build_report_content(db, {section_of(row)});
    EXPECT_EQ(c.falsify.rows.size(), 1u);
    constexpr std::size_t kGapsColumn = 10;  // "gaps reached/targeted"
    EXPECT_EQ(c.falsify.headers.at(kGapsColumn), "gaps reached/targeted");
    return c.falsify.rows.empty() ? std::string() : c.falsify.rows[0].at(kGapsColumn).at(0).text;
  };
  json f = falsify_json_of_config1();
  f.erase("gaps");
  EXPECT_EQ(gaps_cell(f), "-");
  f["gaps"] = json::array();
  f["gap_budget"] = 400;
  EXPECT_EQ(gaps_cell(f), "0/0 (no gap)");
  for (double closest : {0.9, 0.2, 0.5, 0.7})
    f["gaps"].push_back(
        {{"motion", "p1"}, {"point", {closest, 0, 0}}, {"closest_end", closest}, {"reached", false}});
  f["gaps_reached"] = 0;
  EXPECT_EQ(
      gaps_cell(f),
      "0/4; unreached: p1 at (0.2, 0, 0), closest end 0.2; unreached: p1 at (0.5, 0, 0), closest end 0.5; "
      "unreached: p1 at (0.7, 0, 0), closest end 0.7; and 1 more unreached");
}

// The per-motion figure of the search (experiments/report/falsify_figure.h): config 1's square lies on the
// cube's bottom, so the top view shows it widest. The search's ends are drawn by phase, an end outside as a
// red cross, the unreached piece's outline and the unreached gap in ink; the random ends keep their dots.
// A report of the test database with config 1's metrics.falsify set to `falsify`.
Report report_with_search(const std::string& name, const json& falsify) {
  return make_report(name, [&](const fs::path& db) {
    Db edit(db, false);
    edit.exec("ALTER TABLE metrics ADD COLUMN falsify TEXT");
    edit.insert("UPDATE metrics SET falsify = ? WHERE config_id = 1", {falsify.dump()});
  });
}

// The failure search under an unreliable verdict: its column, the note and the summary count, for a search
// that found a failing rollout and for one that did not (a false alarm).
TEST(Report, AdversarialRolloutsShowTheFailureSearch) {
  json failed = falsify_json_of_config1();
  failed["reliable"] = false;
  failed["outside"] = 0;
  failed["soundness_bugs"] = json::array();
  failed["failure_budget"] = 400;
  failed["failure_searched"] = true;
  failed["failure_rollouts"] = 400;
  failed["failure_closest"] = 0.25;
  failed["failures"] = 3;
  failed["first_failure"] = {{"how", "failure"}, {"goal_distance", 0.125}, {"replay", kFalsifyReplay}};
  const Report r = report_with_search("failure_search", failed);
  ASSERT_EQ(r.status, 0);
  const std::string cell =
      "400 rollouts, closest 0.25 to a predicted failure; 3 failed (first by failure, "
      "0.125 from the goal)";
  const std::string html = between(r.html, "<h2 id=\"falsify\">Adversarial rollouts</h2>", "</table>");
  EXPECT_NE(html.find("<th>failure search (unreliable verdicts)</th>"), std::string::npos) << html;
  EXPECT_NE(html.find("<td>" + cell + "</td></tr>"), std::string::npos) << html;
  EXPECT_NE(r.markdown.find("coverage 0.4000 → 0.5500; failure search: " + cell), std::string::npos)
      << r.markdown;
  EXPECT_NE(r.markdown.find("failure search under 1 unreliable verdict: 0 with no failing rollout (false "
                            "alarms)"),
            std::string::npos)
      << r.markdown;

  json none = failed;
  none["failures"] = 0;
  none["first_failure"] = nullptr;
  none["failure_closest"] = nullptr;
  const Report q = report_with_search("false_alarm", none);
  ASSERT_EQ(q.status, 0);
  EXPECT_NE(q.html.find("<td>400 rollouts; none failed: a false alarm</td></tr>"), std::string::npos);
  EXPECT_NE(q.markdown.find("failure search: none of 400 rollouts failed (a false alarm)"),
            std::string::npos);
  EXPECT_NE(q.markdown.find("failure search under 1 unreliable verdict: 1 with no failing rollout"),
            std::string::npos);

  // A reliable verdict with a failure budget: the search did not run.
  json reliable = falsify_json_of_config1();
  reliable["failure_budget"] = 400;
  reliable["failure_searched"] = false;
  const Report t = report_with_search("reliable_budget", reliable);
  ASSERT_EQ(t.status, 0);
  EXPECT_NE(t.html.find("<td>not run (reliable)</td></tr>"), std::string::npos);
  EXPECT_EQ(t.markdown.find("failure search under"), std::string::npos);
}

TEST(Report, AdversarialSearchFigureShowsEachPhaseAndWhatStayedUnreached) {
  const std::vector<double> falsify_end = {0.1, 0.1, -1}, gap_end = {-0.3, 0.05, -1},
                            outside = {0.1, 0.8, -1}, coverage_end = {0.3, -0.35, -1},
                            failure_end = {-0.1, -0.4, -1};
  json f = falsify_json_of_config1();
  f["coverage_radius"] = 0.3;  // the pooled radius; the gap has its own
  f["gaps"][1]["radius"] = 0.1;
  f["pieces"][1]["points"] = {{1, -1, -1}, {1, 1, -1}};  // e3, unreached
  json vertex = f["pieces"][1];
  vertex["points"] = {{-1, 1, 1}};  // an unreached vertex at the top, seen from above
  f["pieces"].push_back(vertex);
  f["search_ends"] = {{{"how", "falsify"}, {"step", 0}, {"end", falsify_end}, {"inside", true}},
                      {{"how", "gap"}, {"step", 0}, {"end", gap_end}, {"inside", true}},
                      {{"how", "coverage"}, {"step", 0}, {"end", coverage_end}, {"inside", true}},
                      {{"how", "failure"}, {"step", 0}, {"end", failure_end}, {"inside", true}},
                      {{"how", "coverage"}, {"step", 0}, {"end", outside}, {"inside", false}}};
  const Report r = make_report("falsify_figure", [&](const fs::path& db) {
    Db edit(db, false);
    edit.exec("ALTER TABLE metrics ADD COLUMN falsify TEXT");
    edit.insert("UPDATE metrics SET falsify = ? WHERE config_id = 1", {f.dump()});
  });
  ASSERT_EQ(r.status, 0);
  const json& fig = figure(r, 1, "falsify_0");
  const cv::Mat img = load(r, fig);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(fig["y"]["label"], "y (in)");  // the top view
  EXPECT_NE(r.html.find("adversarial search, p1 (top view)"), std::string::npos);
  const auto at = [&](const std::vector<double>& p) { return img.at<cv::Vec3b>(to_pixel(fig, p[0], p[1])); };
  EXPECT_EQ(at(falsify_end), legend_color(fig, "falsification search end"));
  EXPECT_EQ(at(gap_end), legend_color(fig, "gap search end"));
  EXPECT_EQ(at(coverage_end), legend_color(fig, "coverage search end"));
  EXPECT_EQ(at(failure_end), legend_color(fig, "failure search end"));
  std::set<int> distinct;  // packed colors
  for (const char* phase : {"falsification", "coverage", "failure", "gap"}) {
    const cv::Vec3b c = legend_color(fig, std::string(phase) + " search end");
    distinct.insert(c[0] | c[1] << 8 | c[2] << 16);
  }
  EXPECT_EQ(distinct.size(), 4u);
  const cv::Vec3b red(0, 0, 255), ink(0, 0, 0);
  EXPECT_EQ(at(outside), red);
  EXPECT_EQ(at(kInsideEnds[0]), legend_color(fig, "random end in set"));
  EXPECT_NE(at(kInsideEnds[0]), red);
  EXPECT_EQ(at({1, 0}), ink);       // the unreached edge's outline, midway (the start edge is at y = -1)
  EXPECT_EQ(at({-0.9, 0.9}), ink);  // the unreached gap's centre
  // Its ring has the gap's own radius, 0.1, not the pooled 0.3: ink near x = -0.8, none at -0.6 or -0.85.
  const auto ink_near = [&](double x, double y) {
    const cv::Point c = to_pixel(fig, x, y);
    for (int dx = -2; dx <= 2; ++dx)
      if (img.at<cv::Vec3b>(c + cv::Point(dx, 0)) == ink) return true;
    return false;
  };
  EXPECT_TRUE(ink_near(-0.8, 0.9));
  EXPECT_FALSE(ink_near(-0.6, 0.9));
  EXPECT_FALSE(ink_near(-0.85, 0.9));
  // The unreached vertex: a ring around it.
  const cv::Point v = to_pixel(fig, -1, 1);
  int ring = 0;
  for (int dx = 7; dx <= 11; ++dx) ring += img.at<cv::Vec3b>(v + cv::Point(dx, 0)) == ink;
  EXPECT_GT(ring, 0);
  EXPECT_EQ(legend_color(fig, "piece no rollout reached"), ink);
  EXPECT_EQ(legend_color(fig, "gap not covered"), ink);
  // Only config 1 has a search.
  for (const json& other : r.figures["figures"]) {
    if (other["kind"].get<std::string>().rfind("falsify", 0) == 0) {
      EXPECT_EQ(other["config_id"], 1);
    }
  }

  // A search end that is not a point: exit 2, naming the column and the JSON path.
  const fs::path base = fs::path(testing::TempDir()) / "cmt_report_test_falsify_figure_bad";
  fs::remove_all(base);
  fs::create_directories(base);
  write_results_db(base / "results.sqlite");
  f["search_ends"][1]["end"] = {1, 2};
  {
    Db edit(base / "results.sqlite", false);
    edit.exec("ALTER TABLE metrics ADD COLUMN falsify TEXT");
    edit.insert("UPDATE metrics SET falsify = ? WHERE config_id = 1", {f.dump()});
  }
  int status = -1;
  const json e = report_error(base / "results.sqlite", base / "out", &status);
  EXPECT_EQ(status, 2);
  EXPECT_EQ(e["key"], "metrics.falsify (config_id 1)");
  EXPECT_NE(e["reason"].get<std::string>().find("search_ends[1].end"), std::string::npos) << e.dump();
}

TEST(Report, BadDatabasesExitWithStatus2) {
  const fs::path base = fs::path(testing::TempDir()) / "cmt_report_test_bad";
  fs::remove_all(base);
  fs::create_directories(base);
  int status = -1;

  json e = report_error(base / "missing.sqlite", base / "out", &status);
  EXPECT_EQ(status, 2);
  EXPECT_EQ(e["file"], (base / "missing.sqlite").string());
  EXPECT_NE(e["reason"].get<std::string>().find("no such"), std::string::npos);

  std::ofstream(base / "text.sqlite") << "not a database, just text\n";
  e = report_error(base / "text.sqlite", base / "out", &status);
  EXPECT_EQ(status, 2);
  EXPECT_EQ(e["file"], (base / "text.sqlite").string());
  EXPECT_NE(e["reason"].get<std::string>().find("not an SQLite"), std::string::npos);

  {
    Db db(base / "other.sqlite");
    db.exec(
        "CREATE TABLE runs(run_id INTEGER PRIMARY KEY, spec_path TEXT, spec_text TEXT, created TEXT);"
        "CREATE TABLE something(x INTEGER);");
  }
  e = report_error(base / "other.sqlite", base / "out", &status);
  EXPECT_EQ(status, 2);
  EXPECT_EQ(e["file"], (base / "other.sqlite").string());
  EXPECT_NE(e["reason"].get<std::string>().find("not a cmt results database"), std::string::npos);

  // A results database whose prediction is not JSON: the key names the column and the config.
  write_results_db(base / "bad_json.sqlite");
  Db(base / "bad_json.sqlite", false)
      .exec("UPDATE predictions SET verify_json = '{\"steps\": [' WHERE config_id = 1");
  e = report_error(base / "bad_json.sqlite", base / "out", &status);
  EXPECT_EQ(status, 2);
  EXPECT_EQ(e["key"], "predictions.verify_json (config_id 1)");
  EXPECT_NE(e["reason"].get<std::string>().find("invalid JSON"), std::string::npos);

  // The output path is a file.
  write_results_db(base / "good.sqlite");
  std::ofstream(base / "a_file") << "x";
  report_error(base / "good.sqlite", base / "a_file", &status);
  EXPECT_EQ(status, 2);
}

TEST(Report, TeachingSessionsSectionListsEachSession) {
  const json session = {
      {"task", "hole"},
      {"solved", true},
      {"strategy", {"p2", "p1"}},
      {"seconds", 8.5},
      {"steps",
       {{{"motion", "p1"},
         {"chain", {"p1"}},
         {"solved_measure", 0.0},
         {"remaining_measure", 2.0},
         {"failure", "termination of motion 'p1' is not inside the goal"}},
        {{"motion", "p2"}, {"chain", {"p2", "p1"}}, {"solved_measure", 2.0}, {"remaining_measure", 0.0}}}},
      {"check", {{"rollouts", 20}, {"successes", 19}, {"failures", 0}, {"outside", 0}, {"unstable", 1}}}};
  cmt::report::ResultsDb db;
  cmt::report::ReportContent content = cmt::report::build_report_content(db, {});
  EXPECT_EQ(cmt::report::render_markdown(content).find("Teaching sessions"), std::string::npos);
  content.teaching =
      cmt::report::teaching_table({{"hole_teach.json", session, "../teach/hole_view/index.html"}});
  const std::string md = cmt::report::render_markdown(content);
  EXPECT_NE(
      md.find("| hole | hole_teach.json [3-D view](../teach/hole_view/index.html) | yes | (p2, p1) | p1 "
              "(p1): solved 0, left 2 (termination of motion 'p1' is not inside the goal); p2 (p2, p1): "
              "solved 2, left 0 | 19 / 20 reached the "
              "goal, 0 failed, 0 ends outside the prediction, 1 unstable | 8.5 |"),
      std::string::npos)
      << md;
  const std::string html = cmt::report::render_html(content);
  EXPECT_NE(html.find("<h2 id=\"teaching\">Teaching sessions</h2>"), std::string::npos);
  EXPECT_NE(html.find("<td>(p2, p1)</td>"), std::string::npos) << html;
  EXPECT_NE(html.find("<a href=\"../teach/hole_view/index.html\">3-D view</a>"), std::string::npos) << html;
}

// A taught strategy with a sensed dispatch (docs/task-format.md branch form) is shown in words, not as JSON.
TEST(Report, TeachingSessionsSectionShowsASensedDispatchInWords) {
  const json box = {{"box", {{"min", {-2.0, -1.0, -0.1}}, {"max", {-0.4, 1.0, 0.1}}}}};
  const json dispatch = {
      "down",
      {{"branch",
        {{{"when", {{"position", {box, box}}, {"force", {{{"direction", {0, 0, 1}}, {"angle", 0.5}}}}}},
          {"then", {"right"}}},
         {{"else", json::array()}}}}}};
  const json session = {
      {"task", "ridge"},
      {"solved", true},
      {"strategy", dispatch},
      {"seconds", 1.0},
      {"steps",
       {{{"motion", "down"}, {"chain", dispatch}, {"solved_measure", 3.0}, {"remaining_measure", 0.0}}}}};
  cmt::report::ResultsDb db;
  cmt::report::ReportContent content = cmt::report::build_report_content(db, {});
  content.teaching = cmt::report::teaching_table({{"ridge_dispatch.json", session, ""}});
  const std::string md = cmt::report::render_markdown(content);
  const std::string text = "(down, branch [position in 2 boxes and force in 1 cone: (right); else: ()])";
  EXPECT_NE(md.find("| " + text + " | down " + text + ": solved 3, left 0 |"), std::string::npos) << md;
  EXPECT_EQ(md.find("\"box\""), std::string::npos) << md;
}

TEST(Report, PlannedStrategiesSectionListsEachPlan) {
  const json found = {
      {"task", "cube"},
      {"found", true},
      {"termination", "sticking"},
      {"strategy", {"planned_1"}},
      {"motions", {{{"name", "planned_1"}, {"commanded", {0.0, 0.0, -2.0}}, {"depth", 0.07}}}},
      {"steps", {{{"state", {"e4"}}, {"targets", {"f2"}}}}},
      {"verified", {{"reliable", true}, {"failure", ""}}},
      {"check", {{"rollouts", 200}, {"successes", 200}, {"outside", 0}, {"seed", 1}}},
      {"seconds", 4.5}};
  const json not_found = {{"task", "hole"},
                          {"found", false},
                          {"termination", "sticking"},
                          {"reason", "no strategy of at most 3 motions"},
                          {"strategy", nullptr},
                          {"seconds", 2.0}};
  cmt::report::ResultsDb db;
  cmt::report::ReportContent content = cmt::report::build_report_content(db, {});
  EXPECT_EQ(cmt::report::render_markdown(content).find("Planned strategies"), std::string::npos);
  content.planner = cmt::report::planner_table({found, not_found});
  const std::string md = cmt::report::render_markdown(content);
  EXPECT_NE(md.find("| cube | sticking | yes | planned_1 | planned_1 to (0, 0, -2), depth 0.07, from e4, may "
                    "stop in f2 | "
                    "reliable | 200 / 200 reached the goal, 0 ends outside the prediction (seed 1) | 4.5 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| hole | sticking | no: no strategy of at most 3 motions |  |  |  | not run | 2 |"),
            std::string::npos)
      << md;
  EXPECT_NE(cmt::report::render_html(content).find("<h2 id=\"planner\">Planned strategies</h2>"),
            std::string::npos);
}

TEST(Report, TeachingSessionsSectionListsABackprojection) {
  const json backprojection = {
      {"task", "two_blocks"},
      {"motions", {"v3", "v2"}},
      {"start_inside", true},
      {"seconds", 4.25},
      {"steps",
       {{{"motion", "v2"}, {"strong_area", 123.25}, {"base_area", 0.0}},
        {{"motion", "v3"}, {"strong_area", 162.5}, {"base_area", 48.0}}}},
      {"check", {{"rollouts", 100}, {"successes", 100}, {"failures", 0}, {"outside", 0}, {"unstable", 0}}}};
  cmt::report::ResultsDb db;
  cmt::report::ReportContent content = cmt::report::build_report_content(db, {});
  content.teaching = cmt::report::teaching_table({{"two_blocks_backproject.json", backprojection, ""}});
  const std::string md = cmt::report::render_markdown(content);
  EXPECT_NE(
      md.find("| two_blocks | two_blocks_backproject.json | yes (start in S) | (v3, v2) | v2: strong "
              "backprojection area 123.2 (stops outside the target: area 0); v3: strong backprojection "
              "area 162.5 (stops outside the target: area 48) | 100 / 100 reached the goal, 0 failed, 0 "
              "ends outside the prediction, 0 unstable | 4.25 |"),
      std::string::npos)
      << md;
}

TEST(Report, EdrSectionListsSlicesAndTheCheck) {
  const json edr = {{"task", "step_offset"},
                    {"strategy", "edr"},
                    {"edr_reliable", true},
                    {"reason", ""},
                    {"confusion_count", 0},
                    {"seconds", 12.5},
                    {"slices",
                     {{{"params", {{"alpha", -1.0}}},
                       {"terminates", true},
                       {"goal_empty", true},
                       {"success_area", 0.0},
                       {"failure_area", 2.5}},
                      {{"params", {{"alpha", 0.5}}},
                       {"terminates", true},
                       {"goal_empty", false},
                       {"success_area", 0.75},
                       {"failure_area", 0.0}}}},
                    {"check",
                     {{"rollouts", 20},
                      {"worlds", json::array({json::object(), json::object()})},
                      {"outcomes",
                       {{"success", 9},
                        {"failure_signalled", 11},
                        {"false_success", 0},
                        {"false_failure", 0},
                        {"missed_success", 0},
                        {"timeout", 0}}}}}};
  cmt::report::ResultsDb db;
  cmt::report::ReportContent content = cmt::report::build_report_content(db, {});
  content.edr = cmt::report::edr_table({edr});
  const std::string md = cmt::report::render_markdown(content);
  EXPECT_NE(md.find("## Error detection and recovery"), std::string::npos) << md;
  EXPECT_NE(
      md.find("| step_offset | edr | yes |  | alpha=-1: no goal, H 2.5; alpha=0.5: goal 0.75, H 0 | 0 | 20 "
              "rollouts in 2 worlds: success 9, failure signalled 11, false success 0, false failure 0, "
              "missed success 0, time-out 0 | 12.5 |"),
      std::string::npos)
      << md;
}

// The colour (0xrrggbb) of a figure's pixel at plot coordinates (x, y).
int figure_color_at(const cmt::report::PlotCanvas& canvas, double x, double y) {
  const cv::Point2d p = canvas.to_image({x, y});
  const cv::Vec3b c =
      canvas.image().at<cv::Vec3b>(static_cast<int>(std::lround(p.y)), static_cast<int>(std::lround(p.x)));
  return (c[2] << 16) | (c[1] << 8) | c[0];  // BGR to 0xrrggbb
}

}  // namespace

// The EDR figure: one stacked bar per world at its alpha, its outcome fractions in the outcomes' colours,
// nothing where no world was drawn; no figure without a check.
TEST(Report, EdrFigureStacksEachWorldsOutcomesAtItsValue) {
  const json run = {{"task", "step_offset"},
                    {"strategy", "edr"},
                    {"parameters", {{{"name", "alpha"}, {"min", -1.0}, {"max", 1.0}, {"critical", {0.0}}}}},
                    {"check",
                     {{"worlds",
                       {{{"params", {-0.5}}, {"outcomes", {{"failure_signalled", 10}, {"success", 0}}}},
                        {{"params", {0.5}}, {"outcomes", {{"success", 6}, {"failure_signalled", 4}}}}}}}}};
  const auto canvas = cmt::report::draw_edr_figure(run, "step_offset / edr");
  ASSERT_TRUE(canvas.has_value());
  auto color_at = [&](double x, double y) { return figure_color_at(*canvas, x, y); };
  const int green = 0x009e73, blue = 0x0072b2;
  EXPECT_EQ(color_at(-0.5, 0.2), blue);  // all ten signalled failure
  EXPECT_EQ(color_at(-0.5, 0.9), blue);
  EXPECT_EQ(color_at(0.5, 0.3), green);   // six of ten succeeded: the bottom 0.6
  EXPECT_EQ(color_at(0.5, 0.8), blue);    // then four failures
  EXPECT_NE(color_at(0.25, 0.5), green);  // no world there
  EXPECT_NE(color_at(0.25, 0.5), blue);

  json without_check = run;
  without_check.erase("check");
  EXPECT_FALSE(cmt::report::draw_edr_figure(without_check, "x").has_value());
}

// A discrete parameter (the twin universe): worlds drawn at one value make one bar, its outcomes summed, and
// the bars are wide (a fraction of the gap between the values).
TEST(Report, EdrFigureMergesTheWorldsOfADiscreteValue) {
  const json run = {
      {"task", "twin_universe"},
      {"strategy", "edr"},
      {"parameters",
       {{{"name", "universe"}, {"min", 1.0}, {"max", 2.0}, {"discrete", true}, {"critical", json::array()}}}},
      {"check",
       {{"worlds",
         {{{"params", {1.0}}, {"outcomes", {{"success", 10}}}},
          {{"params", {2.0}}, {"outcomes", {{"failure_signalled", 10}}}},
          {{"params", {1.0}}, {"outcomes", {{"success", 2}, {"failure_signalled", 8}}}}}}}}};
  const auto canvas = cmt::report::draw_edr_figure(run, "twin_universe / edr");
  ASSERT_TRUE(canvas.has_value());
  auto color_at = [&](double x, double y) { return figure_color_at(*canvas, x, y); };
  const int green = 0x009e73, blue = 0x0072b2;
  // Universe 1: 12 successes of 20, then 8 signalled failures.
  EXPECT_EQ(color_at(1.0, 0.55), green);
  EXPECT_EQ(color_at(1.0, 0.65), blue);
  EXPECT_EQ(color_at(1.1, 0.3), green);  // 0.1 from the value: inside the wide bar
  EXPECT_EQ(color_at(2.0, 0.5), blue);
  EXPECT_NE(color_at(1.5, 0.5), green);  // nothing between the values
  EXPECT_NE(color_at(1.5, 0.5), blue);
}

// §6.3.4's experiment in the report: a row per motion (what it claims, its vertices' rollouts, the rate at
// each growth) and a figure with each motion's success rate against the distance outside its cpositions.
TEST(Report, ExtremePointsTableAndFigureShowEachMotionsRates) {
  const json trials_all = {{"points", json::array({json::object(), json::object()})},
                           {"rollouts", 200},
                           {"successes", 200},
                           {"rate", 1.0}};
  const json grown_half = {{"factor", 1.0},
                           {"points", json::array({json::object()})},
                           {"rollouts", 100},
                           {"successes", 50},
                           {"rate", 0.5}};
  const json run = {
      {"task", "cube"},
      {"found", true},
      {"termination", "sticking"},
      {"extremes",
       {{"motions",
         {{{"motion", "planned_1"}, {"claims_cell", true}, {"vertices", trials_all}, {"grown", {grown_half}}},
          {{"motion", "planned_2"},
           {"claims_cell", false},
           {"vertices", trials_all},
           {"grown", json::array()}}}}}}};
  const cmt::report::Table t = cmt::report::extremes_table({run, {{"task", "hole"}, {"found", false}}});
  ASSERT_EQ(t.rows.size(), 2u);
  cmt::report::ResultsDb db;
  cmt::report::ReportContent content = cmt::report::build_report_content(db, {});
  content.planner = cmt::report::planner_table({run});
  content.extremes = t;
  const std::string md = cmt::report::render_markdown(content);
  EXPECT_NE(md.find("| cube | planned_1 | a cell | 200 / 200 at 2 points | 1 eps_p: 50 % (50 / 100 at 1 "
                    "points) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| cube | planned_2 | one commanded position | 200 / 200 at 2 points |  |"),
            std::string::npos)
      << md;
  EXPECT_NE(cmt::report::render_html(content).find("<table class=\"extremes\">"), std::string::npos);

  const auto canvas = cmt::report::draw_extremes_figure(run, "cube");
  ASSERT_TRUE(canvas.has_value());
  EXPECT_EQ(figure_color_at(*canvas, 1.0, 0.5), 0x0072b2);   // planned_1's marker at (1 eps_p, 50 %)
  EXPECT_EQ(figure_color_at(*canvas, 0.5, 0.75), 0x0072b2);  // on its line from (0, 1)
  EXPECT_NE(figure_color_at(*canvas, 0.5, 0.25), 0x0072b2);
  EXPECT_FALSE(cmt::report::draw_extremes_figure({{"task", "cube"}}, "cube").has_value());
}

// A plan's cells in the C-space views (Buckley's Figs 6.6, 6.8-6.11): each piece's projection outlined and
// the commanded position marked, in the motion's color.
TEST(Report, PlannedMotionsCellIsOutlinedAndItsCommandMarked) {
  const auto task = cmt::load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/cube.yaml");
  std::vector<cmt::Vec3> box;
  for (double x : {-0.5, 0.5})
    for (double y : {-0.5, 0.5})
      for (double z : {-1.8, -1.2}) box.push_back(cmt::Vec3(x, y, z));
  const std::vector<cmt::report::PlannedMotionLayer> layers = {{"planned_1", cmt::Vec3(0, 0, -1.5), {box}}};
  const cmt::report::CSpaceFigureData data{task.get(), {"planned_1"},  nullptr,
                                           nullptr,    "cube planned", &layers};
  const auto canvas = cmt::report::draw_cspace_view(data, cmt::report::View::kFront);
  const cv::Scalar c = cmt::report::darker(cmt::report::motion_color(0, 1), 0.75);
  const int color = (static_cast<int>(c[2]) << 16) | (static_cast<int>(c[1]) << 8) | static_cast<int>(c[0]);
  EXPECT_EQ(figure_color_at(canvas, 0, -1.5), color);      // the commanded position
  EXPECT_EQ(figure_color_at(canvas, -0.5, -1.4), color);   // the outline's left side (x = -0.5)
  EXPECT_EQ(figure_color_at(canvas, 0.25, -1.2), color);   // its top (z = -1.2)
  EXPECT_NE(figure_color_at(canvas, 0.25, -1.35), color);  // inside: not filled
}

// The T-slot plan (§6.3.5) as a graph: f6 -planned_1-> f12 -planned_2-> two goal heads; columns are the
// motions done, the heads one row apart; the leaves drawn as goals, the others as states, with arrows
// between.
TEST(Report, PlanGraphPutsEachHeadOneColumnRightOfItsStepsState) {
  const json run = {
      {"task", "tslot"},
      {"start_states", json::array({json::array({"f6"})})},
      {"steps", json::array({{{"state", {"f6"}}, {"motion", "planned_1"}, {"heads", {{"f12"}}}},
                             {{"state", {"f12"}},
                              {"motion", "planned_2"},
                              {"heads", {{"f13", "e22", "e23", "v10"}, {"f13", "e23", "e36", "v19"}}}}})}};
  const cmt::report::PlanGraph g = cmt::report::plan_graph(run);
  ASSERT_EQ(g.nodes.size(), 4u);
  EXPECT_EQ(g.nodes[0].label, "f6");
  EXPECT_EQ(g.nodes[0].column, 0);
  EXPECT_FALSE(g.nodes[0].goal);
  EXPECT_EQ(g.nodes[1].label, "f12");
  EXPECT_EQ(g.nodes[1].column, 1);
  EXPECT_FALSE(g.nodes[1].goal);
  EXPECT_EQ(g.nodes[2].label, "f13, e22, e23, v10");
  EXPECT_EQ(g.nodes[2].column, 2);
  EXPECT_EQ(g.nodes[2].row, 0);
  EXPECT_EQ(g.nodes[3].row, 1);
  EXPECT_TRUE(g.nodes[2].goal);
  EXPECT_TRUE(g.nodes[3].goal);
  ASSERT_EQ(g.edges.size(), 3u);
  EXPECT_EQ(g.edges[0].motion, "planned_1");
  EXPECT_EQ(g.edges[2].from, 1);
  EXPECT_EQ(g.edges[2].to, 3);

  const auto canvas = cmt::report::draw_plan_graph(run, "tslot plan");
  ASSERT_TRUE(canvas.has_value());
  const auto rgb_of = [](const cv::Scalar& c) {
    return (static_cast<int>(c[2]) << 16) | (static_cast<int>(c[1]) << 8) | static_cast<int>(c[0]);
  };
  const double inside = 0.75 * cmt::report::kPlanNodeHalfHeight;  // above the label, inside the box
  EXPECT_EQ(figure_color_at(*canvas, 0, inside), 0xe8eef7);       // a state's fill
  EXPECT_EQ(figure_color_at(*canvas, 2, -1 + inside), rgb_of(cmt::report::kGoalFill));
  EXPECT_EQ(figure_color_at(*canvas, 0.45, 0), 0x000000);  // the arrow f6 -> f12
  EXPECT_NE(figure_color_at(*canvas, 1, -1), 0x000000);    // nothing below f12
  EXPECT_FALSE(cmt::report::draw_plan_graph(json{{"steps", json::array()}}, "none").has_value());
}

// A type 2 motion's sensed-position set (Buckley Fig 6.9) is outlined in its own color: the §6.3.2 box
// [-.6, .6]^2 x [-1.2, -.8] in the front view (x, z).
TEST(Report, PlannedMotionsSensedPositionsAreOutlined) {
  const auto task = cmt::load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/cube_sensing.yaml");
  cmt::report::PlannedMotionLayer layer{"planned_1", cmt::Vec3(0, 0, -1.7), {}};
  layer.sensed_positions = {cmt::AxisBox{cmt::Vec3(-0.6, -0.6, -1.2), cmt::Vec3(0.6, 0.6, -0.8)}};
  const std::vector<cmt::report::PlannedMotionLayer> layers = {layer};
  const cmt::report::CSpaceFigureData data{task.get(), {"planned_1"},  nullptr,
                                           nullptr,    "cube planned", &layers};
  const auto canvas = cmt::report::draw_cspace_view(data, cmt::report::View::kFront);
  const cv::Scalar c = cmt::report::kSensedPositionsLine;
  const int color = (static_cast<int>(c[2]) << 16) | (static_cast<int>(c[1]) << 8) | static_cast<int>(c[0]);
  EXPECT_EQ(color, 0xd55e00);
  EXPECT_EQ(figure_color_at(canvas, -0.6, -0.9), color);   // left side
  EXPECT_EQ(figure_color_at(canvas, 0.6, -1.1), color);    // right side
  EXPECT_EQ(figure_color_at(canvas, 0.3, -1.2), color);    // bottom
  EXPECT_NE(figure_color_at(canvas, 0.3, -0.9), color);    // inside: not filled
  EXPECT_NE(figure_color_at(canvas, -0.75, -0.9), color);  // outside
}

// `cmt report --plan`: a plan result whose task file loads gets its cells in the three C-space views, one
// with `extremes` its success-rate figure, each referenced by the documents and listed in figures.json; a
// later report without plans removes them.
TEST(Report, PlanResultsAddCellViewsAndTheExtremesFigureAndARerunRemovesThem) {
  const fs::path base = fs::path(testing::TempDir()) / "cmt_report_test_plan";
  fs::remove_all(base);
  fs::create_directories(base);
  write_results_db(base / "results.sqlite");
  const json trials = {
      {"points", json::array({json::object()})}, {"rollouts", 10}, {"successes", 10}, {"rate", 1.0}};
  const json plan = {{"task", "cube"},
                     {"task_file", std::string(CMT_SOURCE_DIR) + "/models/tasks/cube.yaml"},
                     {"found", true},
                     {"termination", "sticking"},
                     {"strategy", {"planned_1"}},
                     {"motions",
                      {{{"name", "planned_1"},
                        {"commanded", {0.0, 0.0, -1.5}},
                        {"depth", 0.1},
                        {"cpositions",
                         {{{"halfspaces", json::array()},
                           {"vertices",
                            {{-0.5, -0.5, -1.8},
                             {0.5, -0.5, -1.8},
                             {0.5, 0.5, -1.8},
                             {-0.5, 0.5, -1.8},
                             {-0.5, -0.5, -1.2},
                             {0.5, -0.5, -1.2},
                             {0.5, 0.5, -1.2},
                             {-0.5, 0.5, -1.2}}}}}}}}},
                     {"extremes",
                      {{"motions",
                        {{{"motion", "planned_1"},
                          {"claims_cell", true},
                          {"vertices", trials},
                          {"grown", json::array()}}}}}},
                     {"seconds", 1.0}};
  {
    std::ofstream out(base / "plan.json");
    out << plan.dump();
  }
  const fs::path dir = base / "report";
  const std::string report = "report " + (base / "results.sqlite").string() + " -o " + dir.string();
  ASSERT_EQ(cmt::test::run(report + " --plan " + (base / "plan.json").string()).status, 0);
  const std::string md = read_file(dir / "report.md");
  for (const std::string png : {"figures/plan_0_front.png", "figures/plan_0_top.png",
                                "figures/plan_0_side.png", "figures/extremes_0.png"}) {
    EXPECT_TRUE(fs::exists(dir / png)) << png;
    EXPECT_NE(md.find("(" + png + ")"), std::string::npos) << png;
  }
  const json figures = json::parse(read_file(dir / "figures.json"));
  int plan_figures = 0, extremes_figures = 0;
  for (const json& f : figures["figures"]) {
    plan_figures += f["kind"] == "plan";
    extremes_figures += f["kind"] == "extremes";
  }
  EXPECT_EQ(plan_figures, 3);
  EXPECT_EQ(extremes_figures, 1);
  ASSERT_EQ(cmt::test::run(report).status, 0);
  EXPECT_FALSE(fs::exists(dir / "figures/plan_0_front.png"));
  EXPECT_FALSE(fs::exists(dir / "figures/extremes_0.png"));
}
