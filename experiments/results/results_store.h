// The sweep results store (docs/sweeps.md "Results database"): one SQLite file holding runs, the
// configurations (units) of a sweep with their status, and for every finished unit its prediction, every
// observed motion end and the metrics. Each finished unit is committed in one transaction, so a killed sweep
// loses at most the units in flight and a rerun finds every committed unit complete and skips it.
// The file uses WAL journaling (readers never block the writer) and waits for locks held by other processes
// (shards, MPI ranks, a CSV export) instead of failing.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "experiments/results/sqlite_db.h"
#include "experiments/sweep/spec/sweep_units.h"

namespace cmt {

// PRAGMA user_version of a cmt results database. 2: configs.controller and predictions.verifier_theta_v /
// verifier_model (the controller form became a unit field). 3: configs.falsify_budget /
// falsify_coverage_budget and metrics.falsify (the adversarial search). A version-2 file is migrated in place
// when opened (results_schema.h kMigrate2To3); other versions are refused.
inline constexpr int kResultsSchemaVersion = 3;

// One row of `rollouts`: the end of one motion of one rollout.
struct RolloutRow {
  int rollout = 0;
  int motion = 0;  // index into the strategy; -1 for a rollout that ended before its first motion did
  std::array<double, 3> start{};  // where this motion started (the rollout's start for motion 0)
  std::array<double, 3> end{};
  int atom = -1;
  std::string termination;
  std::optional<bool> inside;  // NULL when the end took no part in the soundness count
  std::optional<double> distance;
  bool success = false;   // of the whole rollout
  bool unstable = false;  // of the whole rollout
};

// Everything a finished unit writes: `predictions`, `rollouts` and `metrics` rows.
struct UnitRecord {
  // predictions
  bool reliable = false;
  std::string failure;
  double verify_seconds = 0;
  std::string verify_json;      // verify_json(task, prediction, seconds)
  double verifier_theta_v = 0;  // the theta_v the verifier used (widened for the admittance form)
  std::string verifier_model;   // verifier_model_json: that theta_v and why
  // rollouts
  std::vector<RolloutRow> rollouts;
  // metrics
  int rollout_count = 0, successes = 0, unstable = 0, ends = 0, outside = 0;
  double soundness = 1, coverage = 0, coverage_radius = 0, contact_tolerance = 0;
  bool soundness_bug = false;
  std::optional<std::string> counterexample;  // counterexample_json
  std::optional<std::string> sticking;        // sticking_check_json
  double rollout_seconds = 0;
  std::optional<std::string> falsify;  // falsify_json without `threads` (sweep_executor.h falsify_record)
};

struct MergeCounts {
  int runs = 0;          // runs rows copied
  int new_units = 0;     // configurations the target did not know
  int merged = 0;        // finished units copied
  int already_done = 0;  // finished in both: the target's results kept
};

class ResultsStore {
 public:
  // Opens the database, creating the schema in a new file and migrating a version-2 file to version 3;
  // throws std::runtime_error for a file that is not a cmt results database (or of another version).
  explicit ResultsStore(const std::filesystem::path& path);

  // A runs row for this invocation; returns run_id.
  std::int64_t add_run(const std::string& spec_path, const std::string& spec_text, const std::string& shard);
  // Adds the units that are not there yet (status pending), in one transaction. run_id 0: NULL.
  void register_units(std::int64_t run_id, const std::vector<SweepUnit>& units);
  std::set<std::string> done_keys();
  bool is_done(const std::string& unit_key);
  // Writes predictions, rollouts and metrics and sets status done, all in one transaction. Returns false
  // (and writes nothing) when the unit is already done (another process finished it first). Throws when
  // the unit is not registered.
  bool commit_unit(const std::string& unit_key, const UnitRecord& record);
  // Copies runs, unknown configurations and the finished units of another results database that this one
  // has not finished, in one transaction.
  MergeCounts merge_from(const std::filesystem::path& other);
  // One CSV file per table plus summary.csv (experiments/results/results_csv.cc, docs/sweeps.md "CSV
  // export"). Returns the files written.
  std::vector<std::filesystem::path> export_csv(const std::filesystem::path& dir);

  int count_units(const std::string& status);
  SqliteDb& db() { return db_; }

 private:
  SqliteDb db_;
};

}  // namespace cmt
