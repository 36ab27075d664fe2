// ResultsStore::merge_from: folds another results database (a shard's, an MPI rank's) into this one. Units
// are matched by unit_key, so merging is idempotent and order-independent: a unit finished in both keeps
// this database's results (they are equal up to timings: a unit's results depend on its key only).
#include <stdexcept>
#include <string>

#include "experiments/results/results_schema.h"
#include "experiments/results/results_store.h"

namespace cmt {

namespace s = results_schema;

namespace {

int count(SqliteDb& db, const std::string& sql) {
  auto st = db.prepare(sql);
  st.step();
  return static_cast<int>(st.integer(0));
}

// The merge proper, with `src` attached.
MergeCounts merge_attached(SqliteDb& db) {
  MergeCounts c;
  SqliteTransaction t(db);
  db.exec(
      "DROP TABLE IF EXISTS temp.merge_run_map; DROP TABLE IF EXISTS temp.merge_pairs;"
      "CREATE TEMP TABLE merge_run_map(from_id INTEGER PRIMARY KEY, to_id INTEGER);");
  {
    auto runs =
        db.prepare("SELECT run_id, spec_path, spec_text, created, shard FROM src.runs ORDER BY run_id");
    auto ins = db.prepare("INSERT INTO main.runs(spec_path, spec_text, created, shard) VALUES (?, ?, ?, ?)");
    auto map = db.prepare("INSERT INTO merge_run_map(from_id, to_id) VALUES (?, ?)");
    while (runs.step()) {
      for (int k = 1; k <= 4; ++k)
        if (runs.is_null(k))
          ins.bind_null(k);
        else
          ins.bind(k, runs.text(k));
      ins.run();
      map.bind(1, runs.integer(0)).bind(2, db.last_insert_rowid()).run();
      ++c.runs;
    }
  }
  const int before = count(db, "SELECT count(*) FROM main.configs");
  db.exec(std::string("INSERT OR IGNORE INTO main.configs(") + s::kConfigColumns +
          ") SELECT (SELECT to_id FROM merge_run_map WHERE from_id = c.run_id), unit_key, task, task_file, "
          "task_yaml, strategy, params, n, seed, mode, 'pending', NULL, unit_index, sticking_trials, "
          "counterexample_budget, controller, falsify_budget, falsify_coverage_budget FROM src.configs AS c "
          "ORDER BY c.config_id");
  c.new_units = count(db, "SELECT count(*) FROM main.configs") - before;
  c.already_done =
      count(db,
            "SELECT count(*) FROM src.configs AS a JOIN main.configs AS b ON a.unit_key = b.unit_key "
            "WHERE a.status = 'done' AND b.status = 'done'");
  db.exec(
      "CREATE TEMP TABLE merge_pairs AS SELECT a.config_id AS from_id, b.config_id AS to_id, a.finished AS "
      "finished FROM src.configs AS a JOIN main.configs AS b ON a.unit_key = b.unit_key "
      "WHERE a.status = 'done' AND b.status <> 'done'");
  c.merged = count(db, "SELECT count(*) FROM merge_pairs");
  for (const char* table : {"predictions", "rollouts", "metrics"})
    db.exec(std::string("DELETE FROM main.") + table + " WHERE config_id IN (SELECT to_id FROM merge_pairs)");
  const std::pair<const char*, const char*> tables[] = {{"predictions", s::kPredictionColumns},
                                                        {"rollouts", s::kRolloutColumns},
                                                        {"metrics", s::kMetricColumns}};
  for (const auto& [table, columns] : tables)
    db.exec(std::string("INSERT INTO main.") + table + "(config_id, " + columns + ") SELECT p.to_id, " +
            columns + " FROM src." + table + " JOIN merge_pairs AS p ON src." + table +
            ".config_id = p.from_id");
  db.exec(
      "UPDATE main.configs SET status = 'done', finished = (SELECT finished FROM merge_pairs WHERE to_id = "
      "config_id) WHERE config_id IN (SELECT to_id FROM merge_pairs)");
  db.exec("DROP TABLE temp.merge_pairs; DROP TABLE temp.merge_run_map;");
  t.commit();
  return c;
}

}  // namespace

MergeCounts ResultsStore::merge_from(const std::filesystem::path& other) {
  if (!std::filesystem::is_regular_file(other))
    throw std::runtime_error(other.string() + ": no such results database");
  if (std::filesystem::equivalent(other, db_.path()))
    throw std::runtime_error(other.string() + ": cannot merge a results database into itself");
  // Opening it as a store first checks (or, for a file that is not a database, rejects) its schema version,
  // migrating a version-2 file to version 3 in place.
  { ResultsStore check(other); }
  db_.prepare("ATTACH DATABASE ? AS src").bind(1, other.string()).run();
  try {
    const MergeCounts c = merge_attached(db_);
    db_.exec("DETACH DATABASE src");
    return c;
  } catch (...) {
    try {
      db_.exec("DETACH DATABASE src");
    } catch (...) {  // the original error is the one to report
    }
    throw;
  }
}

}  // namespace cmt
