#include "experiments/results/results_store.h"

#include <stdexcept>

#include "experiments/common/json_text.h"
#include "experiments/results/results_schema.h"

namespace cmt {

namespace s = results_schema;

ResultsStore::ResultsStore(const std::filesystem::path& path) : db_(path) {
  // WAL: a reader (CSV export, a report) never blocks the sweep's commits, and a commit is one append.
  // synchronous=NORMAL in WAL mode: a committed transaction survives a killed process (kill -9); only a
  // power loss can drop the last commits, which a rerun then recomputes (never a corrupt file).
  {
    auto mode = db_.prepare("PRAGMA journal_mode=WAL");
    mode.step();
  }
  db_.exec("PRAGMA synchronous=NORMAL");
  db_.exec("PRAGMA foreign_keys=OFF");
  SqliteTransaction t(db_);  // two processes creating one new file: the second sees the first's schema
  auto version = db_.prepare("PRAGMA user_version");
  version.step();
  const auto v = version.integer(0);
  if (v == 0) {
    auto tables = db_.prepare("SELECT count(*) FROM sqlite_master");
    tables.step();
    if (tables.integer(0) != 0)
      throw std::runtime_error(db_.path() + ": not a cmt results database (it has other tables)");
    db_.exec(s::kCreate);
    db_.exec("PRAGMA user_version=" + std::to_string(kResultsSchemaVersion));
  } else if (v == 2) {
    // In the same transaction: another process opening the file meanwhile waits, then sees version 3.
    db_.exec(s::kMigrate2To3);
    db_.exec("PRAGMA user_version=" + std::to_string(kResultsSchemaVersion));
  } else if (v != kResultsSchemaVersion) {
    throw std::runtime_error(db_.path() + ": results schema version " + std::to_string(v) +
                             ", this cmt reads version " + std::to_string(kResultsSchemaVersion) +
                             " (and migrates version 2)");
  }
  t.commit();
}

std::int64_t ResultsStore::add_run(const std::string& spec_path, const std::string& spec_text,
                                   const std::string& shard) {
  auto st = db_.prepare(std::string("INSERT INTO runs(spec_path, spec_text, created, shard) VALUES (?, ?, ") +
                        s::kNow + ", ?)");
  st.bind(1, spec_path).bind(2, spec_text);
  if (shard.empty())
    st.bind_null(3);
  else
    st.bind(3, shard);
  st.run();
  return db_.last_insert_rowid();
}

void ResultsStore::register_units(std::int64_t run_id, const std::vector<SweepUnit>& units) {
  SqliteTransaction t(db_);
  auto st = db_.prepare(
      "INSERT OR IGNORE INTO configs(run_id, unit_key, task, task_file, task_yaml, strategy, params, n, "
      "seed, "
      "mode, unit_index, sticking_trials, counterexample_budget, controller, falsify_budget, "
      "falsify_coverage_budget) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  for (const SweepUnit& u : units) {
    if (run_id > 0)
      st.bind(1, run_id);
    else
      st.bind_null(1);
    st.bind(2, u.unit_key)
        .bind(3, u.task)
        .bind(4, u.task_file)
        .bind(5, u.task_yaml)
        .bind(6, u.strategy)
        .bind(7, json_text(u.params))
        .bind(8, u.n)
        .bind(9, static_cast<std::int64_t>(u.seed))
        .bind(10, sample_mode_name(u.mode))
        .bind(11, u.index)
        .bind(12, u.sticking_trials)
        .bind(13, u.counterexample_budget)
        .bind(14, controller_form_name(u.controller))
        .bind(15, u.falsify_budget)
        .bind(16, u.falsify_coverage_budget);
    st.run();
  }
  t.commit();
}

std::set<std::string> ResultsStore::done_keys() {
  std::set<std::string> keys;
  auto st = db_.prepare("SELECT unit_key FROM configs WHERE status = 'done'");
  while (st.step()) keys.insert(st.text(0));
  return keys;
}

bool ResultsStore::is_done(const std::string& unit_key) {
  auto st = db_.prepare("SELECT status FROM configs WHERE unit_key = ?");
  st.bind(1, unit_key);
  return st.step() && st.text(0) == "done";
}

int ResultsStore::count_units(const std::string& status) {
  auto st = db_.prepare("SELECT count(*) FROM configs WHERE status = ?");
  st.bind(1, status);
  st.step();
  return static_cast<int>(st.integer(0));
}

bool ResultsStore::commit_unit(const std::string& unit_key, const UnitRecord& r) {
  SqliteTransaction t(db_);
  std::int64_t id = 0;
  {
    auto st = db_.prepare("SELECT config_id, status FROM configs WHERE unit_key = ?");
    st.bind(1, unit_key);
    if (!st.step()) throw std::runtime_error(db_.path() + ": unit " + unit_key + " is not registered");
    if (st.text(1) == "done") return false;  // the transaction rolls back: nothing written twice
    id = st.integer(0);
  }
  // Rows of an earlier attempt cannot exist (commits are atomic), but clearing them makes that certain.
  for (const char* table : {"predictions", "rollouts", "metrics"})
    db_.prepare(std::string("DELETE FROM ") + table + " WHERE config_id = ?").bind(1, id).run();

  db_.prepare(std::string("INSERT INTO predictions(config_id, ") + s::kPredictionColumns +
              ") VALUES (?, ?, ?, ?, ?, ?, ?)")
      .bind(1, id)
      .bind(2, r.reliable)
      .bind(3, r.failure)
      .bind(4, r.verify_seconds)
      .bind(5, r.verify_json)
      .bind(6, r.verifier_theta_v)
      .bind(7, r.verifier_model)
      .run();

  auto ins = db_.prepare(std::string("INSERT INTO rollouts(config_id, ") + s::kRolloutColumns +
                         ") VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  for (const RolloutRow& row : r.rollouts) {
    ins.bind(1, id).bind(2, row.rollout).bind(3, row.motion);
    for (int k = 0; k < 3; ++k) ins.bind(4 + k, row.start[k]).bind(7 + k, row.end[k]);
    ins.bind(10, row.atom)
        .bind(11, row.termination)
        .bind(12, row.inside)
        .bind(13, row.distance)
        .bind(14, row.success)
        .bind(15, row.unstable);
    ins.run();
  }

  db_.prepare(std::string("INSERT INTO metrics(config_id, ") + s::kMetricColumns +
              ") VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)")
      .bind(1, id)
      .bind(2, r.rollout_count)
      .bind(3, r.successes)
      .bind(4, r.unstable)
      .bind(5, r.ends)
      .bind(6, r.outside)
      .bind(7, r.soundness)
      .bind(8, r.coverage)
      .bind(9, r.coverage_radius)
      .bind(10, r.contact_tolerance)
      .bind(11, r.soundness_bug)
      .bind(12, r.counterexample)
      .bind(13, r.sticking)
      .bind(14, r.rollout_seconds)
      .bind(15, r.verify_seconds)
      .bind(16, r.falsify)
      .run();

  db_.prepare(std::string("UPDATE configs SET status = 'done', finished = ") + s::kNow +
              " WHERE config_id = ?")
      .bind(1, id)
      .run();
  t.commit();
  return true;
}

}  // namespace cmt
