// ResultsStore::export_csv (docs/sweeps.md "CSV export"): runs.csv, configs.csv, predictions.csv,
// rollouts.csv, metrics.csv (every column of each table, in table order) and summary.csv (one row per
// finished unit: the configuration with one column per override parameter, the prediction's verdict and the
// metrics, without the bulky JSON and YAML columns; the adversarial search's budgets and headline numbers).
// RFC 4180 quoting; reals in shortest round-trip form; NULL as an empty field.
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "experiments/common/json_text.h"
#include "experiments/results/results_store.h"

namespace cmt {

namespace {

std::string quote(const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string q = "\"";
  for (const char c : field) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

std::string field(const SqliteStatement& st, int col) {
  if (st.is_null(col)) return "";
  if (st.is_integer(col)) return std::to_string(st.integer(col));
  if (st.is_real(col))
    return json_text(nlohmann::json(st.real(col)));  // shortest text that reads back exactly
  return quote(st.text(col));
}

class CsvFile {
 public:
  explicit CsvFile(const std::filesystem::path& path) : path_(path), out_(path, std::ios::binary) {
    if (!out_) throw std::runtime_error("cannot write CSV file '" + path.string() + "'");
  }
  void row(const std::vector<std::string>& fields) {
    for (std::size_t i = 0; i < fields.size(); ++i) out_ << (i ? "," : "") << fields[i];
    out_ << "\r\n";  // RFC 4180 line ends
  }
  void close() {
    out_.close();
    if (!out_) throw std::runtime_error("cannot write CSV file '" + path_.string() + "': write failed");
  }

 private:
  std::filesystem::path path_;
  std::ofstream out_;
};

// Every row of a query, with its column names as the header.
void write_query(SqliteDb& db, const std::string& sql, const std::filesystem::path& path) {
  auto st = db.prepare(sql);
  CsvFile csv(path);
  std::vector<std::string> header;
  for (int c = 0; c < st.columns(); ++c) header.push_back(quote(st.column_name(c)));
  csv.row(header);
  while (st.step()) {
    std::vector<std::string> fields;
    for (int c = 0; c < st.columns(); ++c) fields.push_back(field(st, c));
    csv.row(fields);
  }
  csv.close();
}

// The metric and verdict columns of summary.csv, after the configuration and parameter columns.
constexpr const char* kSummaryResultColumns =
    "p.reliable, p.failure, p.verifier_theta_v, m.rollouts, m.successes, m.unstable, m.ends, m.outside, "
    "m.soundness, m.coverage, "
    "m.coverage_radius, m.contact_tolerance, m.soundness_bug, m.counterexample IS NOT NULL AS "
    "has_counterexample, "
    "m.verify_seconds, m.rollout_seconds, c.falsify_budget, c.falsify_coverage_budget, "
    "json_extract(m.falsify, '$.rollouts') AS falsify_rollouts, json_extract(m.falsify, '$.outside') AS "
    "falsify_outside, json_extract(m.falsify, '$.coverage_before') AS falsify_coverage_before, "
    "json_extract(m.falsify, '$.coverage_after') AS falsify_coverage_after, "
    "json_extract(m.falsify, '$.gap_budget') AS falsify_gap_budget, json_array_length(m.falsify, '$.gaps') "
    "AS "
    "falsify_gaps, json_extract(m.falsify, '$.gaps_reached') AS falsify_gaps_reached, "
    "json_extract(m.falsify, '$.failure_budget') AS falsify_failure_budget, json_extract(m.falsify, "
    "'$.failures') AS falsify_failures";

void write_summary(SqliteDb& db, const std::filesystem::path& path) {
  const std::string from =
      " FROM configs AS c JOIN predictions AS p ON p.config_id = c.config_id JOIN metrics AS m ON "
      "m.config_id = "
      "c.config_id WHERE c.status = 'done' ORDER BY c.config_id";
  // The parameter columns: every key of any finished unit's params object, sorted.
  std::set<std::string> keys;
  {
    auto st = db.prepare("SELECT c.params" + from);
    while (st.step()) {
      const auto params = nlohmann::json::parse(st.text(0));  // named: items() refers into it
      for (const auto& [k, v] : params.items()) keys.insert(k);
    }
  }
  auto st = db.prepare(
      "SELECT c.config_id, c.unit_key, c.task, c.strategy, c.n, c.seed, c.mode, c.controller, "
      "c.sticking_trials, c.params, " +
      std::string(kSummaryResultColumns) + from);
  constexpr int kParamsColumn = 9;
  CsvFile csv(path);
  std::vector<std::string> header;
  for (int c = 0; c < st.columns(); ++c) {
    if (c == kParamsColumn)
      for (const std::string& k : keys) header.push_back(quote(k));
    else
      header.push_back(quote(st.column_name(c)));
  }
  csv.row(header);
  while (st.step()) {
    std::vector<std::string> fields;
    for (int c = 0; c < st.columns(); ++c) {
      if (c != kParamsColumn) {
        fields.push_back(field(st, c));
        continue;
      }
      const auto params = nlohmann::json::parse(st.text(c));
      for (const std::string& k : keys)
        fields.push_back(params.contains(k) ? quote(json_text(params[k])) : "");  // a vector as "[x,y,z]"
    }
    csv.row(fields);
  }
  csv.close();
}

}  // namespace

std::vector<std::filesystem::path> ResultsStore::export_csv(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  // One read transaction: the files agree with each other even while a sweep keeps committing.
  db_.exec("BEGIN");
  std::vector<std::filesystem::path> files;
  try {
    const std::pair<const char*, const char*> tables[] = {{"runs", "run_id"},
                                                          {"configs", "config_id"},
                                                          {"predictions", "config_id"},
                                                          {"rollouts", "config_id, rollout, motion"},
                                                          {"metrics", "config_id"}};
    for (const auto& [table, order] : tables) {
      files.push_back(dir / (std::string(table) + ".csv"));
      write_query(db_, std::string("SELECT * FROM ") + table + " ORDER BY " + order, files.back());
    }
    files.push_back(dir / "summary.csv");
    write_summary(db_, files.back());
  } catch (...) {
    db_.exec("ROLLBACK");
    throw;
  }
  db_.exec("COMMIT");
  return files;
}

}  // namespace cmt
