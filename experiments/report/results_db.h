// Reads a results database written by `cmt sweep` (experiments/results/results_store.h) for the report, with
// plain sqlite3 queries against the schema of the results store: runs, configs, predictions, rollouts,
// metrics. The database is opened read-only, so a report can be made while a sweep is still writing;
// configurations whose units are not done yet come back with status "pending" and whatever rows they already
// have.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "models/task.h"

namespace cmt::report {

struct RunRow {
  std::int64_t run_id = 0;
  std::string spec_path, created;
};

// The verifier's answer for a configuration (predictions table).
struct PredictionRow {
  bool reliable = false;
  std::string failure;
  double verify_seconds = 0;   // NaN when NULL
  nlohmann::json verify_json;  // experiments/cli/verify_command.cc verify_json; null when NULL
};

// One observed motion end (rollouts table). Coordinates are the 3-D configuration (planar tasks: y = 0).
struct RolloutRow {
  int rollout = 0, motion = 0;
  Vec3 start = Vec3::Zero(), end = Vec3::Zero();
  int atom = -1;
  std::string termination;
  bool inside = false;
  double distance = 0;
  bool success = false, unstable = false;
};

// Predicted vs observed summary (metrics table). Real values are NaN when NULL.
struct MetricsRow {
  int rollouts = 0, successes = 0, unstable = 0, ends = 0, outside = 0;
  double soundness = 0, coverage = 0, coverage_radius = 0, contact_tolerance = 0;
  bool soundness_bug = false;
  nlohmann::json counterexample;  // null when NULL
  nlohmann::json sticking;  // experiments/validation/sticking_check.h sticking_check_json; null when NULL
  double rollout_seconds = 0, verify_seconds = 0;
  // The adversarial search (docs/falsify.md "In sweeps and the report"): `cmt falsify --json`'s object
  // without `threads`; null when NULL or the database predates the column (schema version < 3).
  nlohmann::json falsify;
};

struct ConfigRow {
  std::int64_t config_id = 0, run_id = 0;
  std::string unit_key, task, task_file, task_yaml, strategy;
  nlohmann::json params;  // object of parameter overrides
  std::int64_t n = 0, seed = 0;
  std::string mode, status, finished;
  std::string controller = "impedance";  // cmt validate --controller of the unit
  std::optional<PredictionRow> prediction;
  std::vector<RolloutRow> rollouts;  // ordered by (rollout, motion)
  std::optional<MetricsRow> metrics;
  bool done() const { return status == "done"; }
};

struct ResultsDb {
  std::filesystem::path path;
  std::vector<RunRow> runs;
  std::vector<ConfigRow> configs;  // ordered by config_id
};

// Throws InputError(path, table or column, reason) when the file is missing, is not an SQLite database, lacks
// a table or column of the schema, or holds a JSON column that does not parse.
ResultsDb read_results_db(const std::filesystem::path& path);

}  // namespace cmt::report
