// cmt report end to end: a small results database is written here with the results-store schema (as
// `cmt sweep` writes it), the report is made with the built program, and its documents and figures are
// checked: every PNG linked from both documents, decodable at the figure size, and showing the known data
// where figures.json's axes put it (the predicted polygon's shading, the red cross of the outside end, the
// stick fraction dots and class bands). Bad databases exit with status 2 naming the file.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

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
  // alpha/phi in bin [0.50, 0.55): must stick, all stuck; bin [1.50, 1.55): never, none stuck.
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
  // A vertex record and one without a usable angle (NaN is stored as null).
  records.push_back({{"atom", 20},
                     {"kind", "vertex"},
                     {"class", "may"},
                     {"command_angle", 0.9 * kPhi},
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

  const std::string rollout =
      "INSERT INTO rollouts VALUES (1, ?, 0, 0, -1, 1, ?, ?, ?, 0, 'stuck', ?, ?, ?, 0)";
  int index = 0;
  for (const auto& e : kInsideEnds) db.insert(rollout, {index++, e[0], e[1], e[2], 1, 0.0, 1});
  db.insert(rollout, {index++, kOutsideEnd[0], kOutsideEnd[1], kOutsideEnd[2], 0, 0.3, 0});

  const std::string metrics =
      "INSERT INTO metrics VALUES (?, ?, ?, 0, ?, ?, ?, ?, 0.25, 0.01, 0, ?, ?, ?, ?)";
  db.insert(metrics, {1, 6, 5, 6, 1, 5.0 / 6.0, 0.4, nullptr, sticking_json().dump(), 3.5, 0.1});
  db.insert(metrics, {3, 0, 0, 0, 0, nullptr, nullptr, nullptr, nullptr, 0.0, 0.2});
}

struct Report {
  fs::path dir;
  int status = -1;
  std::string markdown, html;
  json figures;  // figures.json
};

Report make_report(const std::string& name) {
  const fs::path base = fs::path(testing::TempDir()) / ("cmt_report_test_" + name);
  fs::remove_all(base);
  fs::create_directories(base);
  write_results_db(base / "results.sqlite");
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
  // Config 1: three views + sticking; config 2 (pending): three views of the C-space; config 3: three views.
  EXPECT_EQ(pngs.size(), 10u);
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

TEST(Report, StickingFigureShowsFractionsAndClassBands) {
  const Report r = make_report("sticking");
  ASSERT_EQ(r.status, 0);
  const json& f = figure(r, 1, "sticking");
  const cv::Mat img = load(r, f);
  ASSERT_FALSE(img.empty());
  const cv::Vec3b face = legend_color(f, "observed, faces");
  // Bin [0.50, 0.55): all 4 stuck -> a dot at fraction 1; bin [1.50, 1.55): none -> a dot at 0.
  EXPECT_EQ(img.at<cv::Vec3b>(to_pixel(f, 0.525, 1.0)), face);
  EXPECT_EQ(img.at<cv::Vec3b>(to_pixel(f, 1.525, 0.0)), face);
  // Behind them the predicted classes of those bins: must, never; a bin without trials has no band.
  EXPECT_EQ(img.at<cv::Vec3b>(to_pixel(f, 0.525, 0.5)), legend_color(f, "predicted must"));
  EXPECT_EQ(img.at<cv::Vec3b>(to_pixel(f, 1.525, 0.5)), legend_color(f, "predicted never"));
  EXPECT_NE(img.at<cv::Vec3b>(to_pixel(f, 1.225, 0.5)), legend_color(f, "predicted never"));
  EXPECT_NE(img.at<cv::Vec3b>(to_pixel(f, 1.225, 0.5)), legend_color(f, "predicted must"));
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

  EXPECT_NE(r.markdown.find("3 configurations (2 done, 1 pending)"), std::string::npos);
  EXPECT_NE(r.html.find("0.8333"), std::string::npos);
}

// Runs the report on a database with --json and returns the error object.
json report_error(const fs::path& db, const fs::path& out, int* status) {
  const cmt::test::Result r = cmt::test::run("report " + db.string() + " -o " + out.string() + " --json");
  *status = r.status;
  return r.out.empty() ? json() : json::parse(r.out)["error"];
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

}  // namespace
