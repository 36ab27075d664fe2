#include "experiments/report/results_db.h"

#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "experiments/results/sqlite_db.h"
#include "models/input_error.h"

namespace cmt::report {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The columns the report reads, per table: a database lacking any of them is not a cmt results database (or
// one from an incompatible version), and saying which is missing beats a half-empty report.
const std::map<std::string, std::vector<std::string>>& required_schema() {
  static const std::map<std::string, std::vector<std::string>> schema = {
      {"runs", {"run_id", "spec_path", "spec_text", "created"}},
      {"configs",
       {"config_id", "run_id", "unit_key", "task", "task_file", "task_yaml", "strategy", "params", "n",
        "seed", "mode", "status", "finished"}},
      {"predictions", {"config_id", "reliable", "failure", "verify_seconds", "verify_json"}},
      {"rollouts",
       {"config_id", "rollout", "motion", "start_x", "start_y", "start_z", "end_x", "end_y", "end_z", "atom",
        "termination", "inside", "distance", "success", "unstable"}},
      {"metrics",
       {"config_id", "rollouts", "successes", "unstable", "ends", "outside", "soundness", "coverage",
        "coverage_radius", "contact_tolerance", "soundness_bug", "counterexample", "sticking",
        "rollout_seconds", "verify_seconds"}},
  };
  return schema;
}

// Every SQLite error as InputError(path, key, reason): the report names the table it was reading.
InputError query_error(const SqliteError& e, const std::string& key) {
  return InputError(e.path(), key, "query failed: " + e.detail());
}

// A query of one table: SqliteStatement's errors keyed by the table, NULL columns as the report reads them.
class Query {
 public:
  Query(SqliteDb& db, const std::string& sql, const std::string& key)
      : key_(key), stmt_(prepare(db, sql, key)) {}

  bool step() {
    try {
      return stmt_.step();
    } catch (const SqliteError& e) {
      throw query_error(e, key_);
    }
  }
  bool null(int col) const { return stmt_.is_null(col); }
  std::int64_t integer(int col, std::int64_t if_null = 0) const {
    return null(col) ? if_null : stmt_.integer(col);
  }
  double real(int col) const { return null(col) ? kNaN : stmt_.real(col); }
  std::string text(int col) const { return stmt_.text(col); }

 private:
  static SqliteStatement prepare(SqliteDb& db, const std::string& sql, const std::string& key) {
    try {
      return db.prepare(sql);
    } catch (const SqliteError& e) {
      throw query_error(e, key);
    }
  }

  std::string key_;
  SqliteStatement stmt_;
};

SqliteDb open_read_only(const std::filesystem::path& path) {
  try {
    return SqliteDb(path, SqliteDb::Mode::kReadOnly);
  } catch (const SqliteError& e) {
    throw InputError(e.path(), "", "cannot open the results database: " + e.detail());
  }
}

// sqlite3_open_v2 accepts any file; the first read tells whether it is an SQLite database at all.
void check_is_sqlite(SqliteDb& db) {
  try {
    SqliteStatement probe = db.prepare("SELECT count(*) FROM sqlite_master");
    if (probe.step()) return;
    throw InputError(db.path(), "", "not an SQLite results database (no answer)");
  } catch (const SqliteError& e) {
    throw InputError(db.path(), "", "not an SQLite results database (" + e.detail() + ")");
  }
}

void check_schema(SqliteDb& db) {
  for (const auto& [table, columns] : required_schema()) {
    std::set<std::string> present;
    Query info(db, "PRAGMA table_info(" + table + ")", table);
    while (info.step()) present.insert(info.text(1));
    if (present.empty())
      throw InputError(db.path(), table, "not a cmt results database: table '" + table + "' is missing");
    for (const std::string& c : columns)
      if (!present.count(c))
        throw InputError(
            db.path(), table + "." + c,
            "not a cmt results database: column '" + c + "' of table '" + table + "' is missing");
  }
}

bool has_column(SqliteDb& db, const std::string& table, const std::string& column) {
  Query info(db, "PRAGMA table_info(" + table + ")", table);
  while (info.step())
    if (info.text(1) == column) return true;
  return false;
}

// A JSON text column; NULL or empty text is JSON null.
nlohmann::json json_column(const SqliteDb& db, const Query& s, int col, const std::string& key) {
  if (s.null(col)) return nullptr;
  const std::string text = s.text(col);
  if (text.empty()) return nullptr;
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(db.path(), key, std::string("invalid JSON: ") + e.what());
  }
}

// The tables read in one read transaction: a sweep writing meanwhile cannot make `configs` and `metrics`
// come from different moments (each statement alone would take its own snapshot).
class ReadTransaction {
 public:
  explicit ReadTransaction(SqliteDb& db) : db_(db) { run("BEGIN"); }
  ~ReadTransaction() {
    if (!open_) return;
    try {
      db_.exec("ROLLBACK");
    } catch (const SqliteError&) {
      // Closing the connection ends the transaction anyway.
    }
  }
  ReadTransaction(const ReadTransaction&) = delete;
  ReadTransaction& operator=(const ReadTransaction&) = delete;
  void commit() {
    run("COMMIT");
    open_ = false;
  }

 private:
  void run(const char* sql) {
    try {
      db_.exec(sql);
    } catch (const SqliteError& e) {
      throw InputError(e.path(), "",
                       std::string("cannot read the results database (") + sql + "): " + e.detail());
    }
  }
  SqliteDb& db_;
  bool open_ = true;
};

std::string config_key(std::int64_t id, const char* table, const char* column) {
  return std::string(table) + "." + column + " (config_id " + std::to_string(id) + ")";
}

// config_id -> position in ResultsDb::configs.
using ConfigIndex = std::map<std::int64_t, std::size_t>;

// The runs table, in run order.
void read_runs(SqliteDb& db, ResultsDb* out) {
  Query s(db, "SELECT run_id, spec_path, created FROM runs ORDER BY run_id", "runs");
  while (s.step()) out->runs.push_back({s.integer(0), s.text(1), s.text(2)});
}

// The configs table, in config order; fills `index`.
void read_configs(SqliteDb& db, ResultsDb* out, ConfigIndex* index) {
  // `controller` is a later addition to the schema: databases without it ran the default, impedance.
  const std::string controller = has_column(db, "configs", "controller") ? "controller" : "'impedance'";
  Query s(db,
          "SELECT config_id, run_id, unit_key, task, task_file, task_yaml, strategy, params, n, seed, "
          "mode, status, finished, " +
              controller + " FROM configs ORDER BY config_id",
          "configs");
  while (s.step()) {
    ConfigRow c;
    c.config_id = s.integer(0);
    c.run_id = s.integer(1);
    c.unit_key = s.text(2);
    c.task = s.text(3);
    c.task_file = s.text(4);
    c.task_yaml = s.text(5);
    c.strategy = s.text(6);
    c.params = json_column(db, s, 7, config_key(c.config_id, "configs", "params"));
    if (c.params.is_null()) c.params = nlohmann::json::object();
    if (!c.params.is_object())
      throw InputError(db.path(), config_key(c.config_id, "configs", "params"), "not a JSON object");
    c.n = s.integer(8);
    c.seed = s.integer(9);
    c.mode = s.text(10);
    c.status = s.text(11);
    c.finished = s.text(12);
    c.controller = s.text(13);
    if (c.controller.empty()) c.controller = "impedance";
    (*index)[c.config_id] = out->configs.size();
    out->configs.push_back(std::move(c));
  }
}

// Each listed configuration's prediction (a prediction of no listed configuration has nothing to be
// reported under).
void read_predictions(SqliteDb& db, const ConfigIndex& index, ResultsDb* out) {
  Query s(db, "SELECT config_id, reliable, failure, verify_seconds, verify_json FROM predictions",
          "predictions");
  while (s.step()) {
    const auto it = index.find(s.integer(0));
    if (it == index.end()) continue;  // a prediction of no listed config: nothing to report it under
    PredictionRow p;
    p.reliable = s.integer(1) != 0;
    p.failure = s.text(2);
    p.verify_seconds = s.real(3);
    p.verify_json = json_column(db, s, 4, config_key(it->first, "predictions", "verify_json"));
    out->configs[it->second].prediction = std::move(p);
  }
}

// Each listed configuration's rollouts, in rollout and motion order.
void read_rollouts(SqliteDb& db, const ConfigIndex& index, ResultsDb* out) {
  Query s(db,
          "SELECT config_id, rollout, motion, start_x, start_y, start_z, end_x, end_y, end_z, atom, "
          "termination, inside, distance, success, unstable FROM rollouts "
          "ORDER BY config_id, rollout, motion",
          "rollouts");
  while (s.step()) {
    const auto it = index.find(s.integer(0));
    if (it == index.end()) continue;
    RolloutRow r;
    r.rollout = static_cast<int>(s.integer(1));
    r.motion = static_cast<int>(s.integer(2));
    r.start = Vec3(s.real(3), s.real(4), s.real(5));
    r.end = Vec3(s.real(6), s.real(7), s.real(8));
    r.atom = static_cast<int>(s.integer(9, -1));
    r.termination = s.text(10);
    r.inside = s.integer(11) != 0;
    r.distance = s.real(12);
    r.success = s.integer(13) != 0;
    r.unstable = s.integer(14) != 0;
    out->configs[it->second].rollouts.push_back(r);
  }
}

// Each listed configuration's metrics.
void read_metrics(SqliteDb& db, const ConfigIndex& index, ResultsDb* out) {
  // `falsify` is a later addition (schema version 3): older databases ran no search.
  const std::string falsify = has_column(db, "metrics", "falsify") ? "falsify" : "NULL";
  Query s(db,
          "SELECT config_id, rollouts, successes, unstable, ends, outside, soundness, coverage, "
          "coverage_radius, contact_tolerance, soundness_bug, counterexample, sticking, "
          "rollout_seconds, verify_seconds, " +
              falsify + " FROM metrics",
          "metrics");
  while (s.step()) {
    const auto it = index.find(s.integer(0));
    if (it == index.end()) continue;
    MetricsRow m;
    m.rollouts = static_cast<int>(s.integer(1));
    m.successes = static_cast<int>(s.integer(2));
    m.unstable = static_cast<int>(s.integer(3));
    m.ends = static_cast<int>(s.integer(4));
    m.outside = static_cast<int>(s.integer(5));
    m.soundness = s.real(6);
    m.coverage = s.real(7);
    m.coverage_radius = s.real(8);
    m.contact_tolerance = s.real(9);
    m.soundness_bug = s.integer(10) != 0;
    m.counterexample = json_column(db, s, 11, config_key(it->first, "metrics", "counterexample"));
    m.sticking = json_column(db, s, 12, config_key(it->first, "metrics", "sticking"));
    m.rollout_seconds = s.real(13);
    m.verify_seconds = s.real(14);
    m.falsify = json_column(db, s, 15, config_key(it->first, "metrics", "falsify"));
    if (!m.falsify.is_null() && !m.falsify.is_object())
      throw InputError(db.path(), config_key(it->first, "metrics", "falsify"), "not a JSON object");
    out->configs[it->second].metrics = std::move(m);
  }
}

}  // namespace

ResultsDb read_results_db(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw InputError(path.string(), "", "no such results database (run `cmt sweep` first)");
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path.string(), "", "is a directory, not a results database");
  SqliteDb db = open_read_only(path);
  check_is_sqlite(db);
  ReadTransaction snapshot(db);
  check_schema(db);

  ResultsDb out;
  out.path = path;
  read_runs(db, &out);
  ConfigIndex index;
  read_configs(db, &out, &index);
  read_predictions(db, index, &out);
  read_rollouts(db, index, &out);
  read_metrics(db, index, &out);
  snapshot.commit();
  return out;
}

}  // namespace cmt::report
