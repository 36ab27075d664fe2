// The results store and the sweep runner with a fake executor (no verifier, no MuJoCo): atomic commits,
// resume after a crash without loss or duplicates, merging shards, CSV export.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "experiments/results/results_store.h"
#include "experiments/results/unit_record_json.h"
#include "experiments/sweep/mpi/sweep_mpi.h"
#include "experiments/sweep/spec/sweep_spec.h"
#include "experiments/sweep/spec/sweep_units.h"
#include "experiments/sweep/sweep_runner.h"
#include "tests/experiments/sweep_test_util.h"

namespace cmt {
namespace {

using test::query_count;
using test::query_rows;

// 2 frictions x 2 strategies x 2 seeds = 8 units of n = 6.
std::vector<SweepUnit> eight_units() {
  const std::string spec = "n: 6\nseeds: [1, 2]\ntasks:\n  - file: " + test::source_task("two_blocks") +
                           "\n    strategies: [down, slide]\n    grid:\n      friction: [0.2, 0.3]\n";
  return expand_units(parse_sweep_spec(spec, "spec.yaml", "/"));
}

// A record that depends on the unit only (as a real validation does), with text that needs CSV quoting.
UnitRecord fake_record(const SweepUnit& u, int /*threads*/) {
  UnitRecord r;
  r.reliable = u.strategy == "slide";
  r.failure = r.reliable ? "" : "ends \"outside\", e.g.\nthe floor";
  r.verify_seconds = 0.5;
  r.verify_json = R"({"reliable": false})";
  r.verifier_theta_v = 0.25;  // the impedance form: the task's theta_v
  r.verifier_model = R"({"controller": "impedance", "theta_v": 0.25})";
  for (int i = 0; i < u.n; ++i) {
    RolloutRow row;
    row.rollout = i;
    row.motion = 0;
    row.start = {static_cast<double>(u.seed), 0, 3};
    row.end = {0.25 * i, u.params["friction"].get<double>(), 0};
    row.atom = i % 3;
    row.termination = "sticking";
    row.inside = i % 2 == 0;
    if (i % 2 == 1) row.distance = 0.125 * i;  // NULL for the inside ones
    row.success = i % 2 == 0;
    r.rollouts.push_back(row);
  }
  r.rollout_count = u.n;
  r.successes = (u.n + 1) / 2;
  r.ends = u.n;
  r.outside = u.n / 2;
  r.soundness = 0.5;
  r.coverage = 1.0 / (1 + u.index);
  r.coverage_radius = 0.1;
  r.contact_tolerance = 0.001;
  r.soundness_bug = false;
  if (!r.reliable) r.counterexample = R"({"index": 1})";
  r.rollout_seconds = 0.25;
  return r;
}

class SweepStore : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_dir("sweep-store"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

SweepRunCounts run_all(const std::filesystem::path& db, const std::vector<SweepUnit>& units,
                       const UnitExecutor& exec = fake_record) {
  ResultsStore store(db);
  store.register_units(store.add_run("spec.yaml", "n: 6", ""), units);
  return run_units(store, units, store.done_keys(), exec, SweepRunOptions{});
}

TEST_F(SweepStore, SchemaHasTheInterfaceColumns) {
  ResultsStore store(dir_ / "r.sqlite");
  const std::pair<const char*, const char*> tables[] = {
      {"runs", "run_id,spec_path,spec_text,created"},
      {"configs",
       "config_id,run_id,unit_key,task,task_file,task_yaml,strategy,params,n,seed,mode,status,finished"},
      {"predictions",
       "config_id,reliable,failure,verify_seconds,verify_json,verifier_theta_v,verifier_model"},
      {"rollouts",
       "config_id,rollout,motion,start_x,start_y,start_z,end_x,end_y,end_z,atom,termination,inside,distance,"
       "success,"
       "unstable"},
      {"metrics",
       "config_id,rollouts,successes,unstable,ends,outside,soundness,coverage,coverage_radius,contact_"
       "tolerance,"
       "soundness_bug,counterexample,sticking,rollout_seconds,verify_seconds"}};
  for (const auto& [table, columns] : tables) {
    std::string names;
    for (const auto& row :
         query_rows(dir_ / "r.sqlite", std::string("SELECT name FROM pragma_table_info('") + table + "')"))
      names += (names.empty() ? "" : ",") + row[0];
    EXPECT_EQ(names.substr(0, std::string(columns).size()), columns) << table;
  }
  EXPECT_EQ(query_rows(dir_ / "r.sqlite", "PRAGMA journal_mode")[0][0], "wal");
}

TEST_F(SweepStore, RunsEveryUnitOnce) {
  const auto units = eight_units();
  const SweepRunCounts c = run_all(dir_ / "r.sqlite", units);
  EXPECT_EQ(c.units, 8);
  EXPECT_EQ(c.ran, 8);
  EXPECT_EQ(c.skipped, 0);
  const auto db = dir_ / "r.sqlite";
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM configs WHERE status = 'done' AND finished IS NOT NULL"),
            8);
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM predictions"), 8);
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM metrics"), 8);
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM rollouts"), 8 * 6);
  // A config row carries the unit as registered.
  const auto row = query_rows(
      db, "SELECT task, strategy, params, n, seed, mode, unit_index FROM configs WHERE unit_key = '" +
              units[5].unit_key + "'");
  ASSERT_EQ(row.size(), 1u);
  EXPECT_EQ(row[0],
            (std::vector<std::string>{"two_blocks", "down", "{\"friction\":0.3}", "6", "2", "uniform", "5"}));
  // NULL distance for inside ends, as written.
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM rollouts WHERE distance IS NULL"), 8 * 3);
}

TEST_F(SweepStore, CrashThenResumeLosesAndDuplicatesNothing) {
  const auto units = eight_units();
  const auto db = dir_ / "r.sqlite";
  int calls = 0;
  // The fourth unit "crashes" (an exception in place of kill -9: the transaction of that unit never starts).
  const UnitExecutor crashing = [&](const SweepUnit& u, int t) {
    if (++calls == 4) throw std::runtime_error("simulated crash");
    return fake_record(u, t);
  };
  EXPECT_THROW(run_all(db, units, crashing), std::runtime_error);
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM configs WHERE status = 'done'"), 3);
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM configs WHERE status = 'pending'"), 5);
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM rollouts"), 3 * 6);

  int resumed_calls = 0;
  const UnitExecutor counting = [&](const SweepUnit& u, int t) {
    ++resumed_calls;
    return fake_record(u, t);
  };
  const SweepRunCounts c = run_all(db, units, counting);
  EXPECT_EQ(c.skipped, 3);
  EXPECT_EQ(c.ran, 5);
  EXPECT_EQ(resumed_calls, 5);
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM configs"), 8);
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM rollouts"), 8 * 6);

  const auto reference = dir_ / "reference.sqlite";
  run_all(reference, units);
  EXPECT_EQ(test::unit_results(db), test::unit_results(reference));
  EXPECT_EQ(test::rollout_results(db), test::rollout_results(reference));
}

TEST_F(SweepStore, CommitIsAllOrNothing) {
  const auto units = eight_units();
  const auto db = dir_ / "r.sqlite";
  ResultsStore store(db);
  store.register_units(0, units);
  UnitRecord bad = fake_record(units[0], 1);
  bad.rollouts.push_back(
      bad.rollouts.front());  // the same (rollout, motion) twice: the primary key refuses it
  EXPECT_THROW(store.commit_unit(units[0].unit_key, bad), std::runtime_error);
  EXPECT_FALSE(store.is_done(units[0].unit_key));
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM predictions"), 0);  // written before the failing row ...
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM rollouts"), 0);     // ... and rolled back with it
  // A second commit of a finished unit writes nothing.
  EXPECT_TRUE(store.commit_unit(units[0].unit_key, fake_record(units[0], 1)));
  EXPECT_FALSE(store.commit_unit(units[0].unit_key, fake_record(units[0], 1)));
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM rollouts"), 6);
  EXPECT_THROW(store.commit_unit("not-a-unit", fake_record(units[0], 1)), std::runtime_error);
}

TEST_F(SweepStore, ShardsMergeIntoOneRun) {
  const auto units = eight_units();
  std::vector<SweepUnit> shard0, shard1;
  for (const SweepUnit& u : units) (Shard{0, 2}.contains(u.index) ? shard0 : shard1).push_back(u);
  run_all(dir_ / "s0.sqlite", shard0);
  run_all(dir_ / "s1.sqlite", shard1);
  run_all(dir_ / "one.sqlite", units);
  ResultsStore merged(dir_ / "merged.sqlite");
  const MergeCounts a = merged.merge_from(dir_ / "s0.sqlite");
  const MergeCounts b = merged.merge_from(dir_ / "s1.sqlite");
  EXPECT_EQ(a.merged, 4);
  EXPECT_EQ(a.new_units, 4);
  EXPECT_EQ(b.merged, 4);
  EXPECT_EQ(a.runs + b.runs, 2);
  EXPECT_EQ(test::unit_results(dir_ / "merged.sqlite"), test::unit_results(dir_ / "one.sqlite"));
  EXPECT_EQ(test::rollout_results(dir_ / "merged.sqlite"), test::rollout_results(dir_ / "one.sqlite"));
  // Merging again changes nothing.
  const MergeCounts again = merged.merge_from(dir_ / "s1.sqlite");
  EXPECT_EQ(again.merged, 0);
  EXPECT_EQ(again.already_done, 4);
  EXPECT_EQ(query_count(dir_ / "merged.sqlite", "SELECT count(*) FROM rollouts"), 8 * 6);
  // A pending unit in the target is completed by a merge.
  ResultsStore partial(dir_ / "partial.sqlite");
  partial.register_units(0, units);
  EXPECT_EQ(partial.merge_from(dir_ / "s0.sqlite").merged, 4);
  EXPECT_EQ(partial.count_units("done"), 4);
  EXPECT_EQ(partial.count_units("pending"), 4);
  EXPECT_THROW(merged.merge_from(dir_ / "merged.sqlite"), std::runtime_error);  // into itself
  EXPECT_THROW(merged.merge_from(dir_ / "missing.sqlite"), std::runtime_error);
}

TEST_F(SweepStore, RefusesForeignDatabases) {
  {
    ResultsStore store(dir_ / "r.sqlite");
    store.db().exec("CREATE TABLE extra(x)");  // additions to a results database are fine
  }
  EXPECT_NO_THROW(ResultsStore(dir_ / "r.sqlite"));
  test::write_file(dir_ / "text.sqlite",
                   "this is not a database, just some text that is long enough........\n");
  EXPECT_THROW(ResultsStore(dir_ / "text.sqlite"), std::runtime_error);
  {
    SqliteDb other(dir_ / "other.sqlite");
    other.exec("CREATE TABLE t(x)");
  }
  EXPECT_THROW(ResultsStore(dir_ / "other.sqlite"), std::runtime_error);
}

std::vector<std::string> lines(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  std::vector<std::string> out;
  std::string text = s.str(), line;
  for (std::size_t pos = 0; pos < text.size();) {
    const std::size_t end = text.find("\r\n", pos);
    out.push_back(text.substr(pos, end - pos));
    pos = end == std::string::npos ? text.size() : end + 2;
  }
  return out;
}

TEST_F(SweepStore, CsvExport) {
  const auto units = eight_units();
  ResultsStore store(dir_ / "r.sqlite");
  store.register_units(store.add_run("spec.yaml", "n: 6", ""), units);
  run_units(store, {units[0], units[2]}, {}, fake_record, SweepRunOptions{});  // down and slide, friction 0.2
  const auto files = store.export_csv(dir_ / "csv");
  ASSERT_EQ(files.size(), 6u);
  for (const auto& f : files) EXPECT_TRUE(std::filesystem::is_regular_file(f)) << f;

  const auto summary = lines(dir_ / "csv" / "summary.csv");
  ASSERT_EQ(summary.size(),
            3u);  // header and 2 rows (records end in CRLF; the quoted failure text has an LF)
  EXPECT_EQ(
      summary[0],
      "config_id,unit_key,task,strategy,n,seed,mode,controller,sticking_trials,friction,reliable,failure,"
      "verifier_theta_v,rollouts,"
      "successes,unstable,ends,outside,soundness,coverage,coverage_radius,contact_tolerance,soundness_bug,"
      "has_counterexample,verify_seconds,rollout_seconds,falsify_budget,falsify_coverage_budget,"
      "falsify_rollouts,falsify_outside,falsify_coverage_before,falsify_coverage_after,falsify_gap_budget,"
      "falsify_gaps,falsify_gaps_reached,falsify_failure_budget,falsify_failures");
  // Unit 0: down, friction 0.2, seed 1: the fake's values (coverage 1/(1+0) = 1).
  EXPECT_EQ(summary[1], "1," + units[0].unit_key +
                            ",two_blocks,down,6,1,uniform,impedance,0,0.2,0,\"ends \"\"outside\"\", "
                            "e.g.\nthe floor\",0.25,6,3,0,6,3,0.5,1.0,0.1,0.001,0,1,0.5,0.25,0,0,,,,,,,,,");
  // Unit 2: slide, reliable, no failure text (empty field), coverage 1/3 in shortest round-trip form.
  EXPECT_EQ(summary[2],
            "3," + units[2].unit_key +
                ",two_blocks,slide,6,1,uniform,impedance,0,0.2,1,,0.25,6,3,0,6,3,0.5,0.3333333333333333,0.1,"
                "0.001,0,0,0.5,0.25,0,0,,,,,,,,,");  // no search: budgets 0, its numbers empty

  const auto rollouts = lines(dir_ / "csv" / "rollouts.csv");
  ASSERT_EQ(rollouts.size(), 1u + 12);
  EXPECT_EQ(
      rollouts[0],
      "config_id,rollout,motion,start_x,start_y,start_z,end_x,end_y,end_z,atom,termination,inside,distance,"
      "success,unstable");
  EXPECT_EQ(rollouts[2], "1,1,0,1.0,0.0,3.0,0.25,0.2,0.0,1,sticking,0,0.125,0,0");  // rollout 1 of unit 0
  EXPECT_EQ(rollouts[1], "1,0,0,1.0,0.0,3.0,0.0,0.2,0.0,0,sticking,1,,1,0");        // NULL distance: empty
  EXPECT_EQ(lines(dir_ / "csv" / "configs.csv").size(), 1u + 8);  // task_yaml's LFs stay inside quotes
}

// Units with an adversarial search (docs/falsify.md "In sweeps and the report"): 2 strategies x 2 seeds.
std::vector<SweepUnit> falsify_units() {
  const std::string spec =
      "n: 6\nseeds: [1, 2]\nfalsify: {budget: 32, coverage_budget: 16}\ntasks:\n"
      "  - file: " +
      test::source_task("two_blocks") + "\n    strategies: [down, slide]\n    grid:\n      friction: [0.2]\n";
  return expand_units(parse_sweep_spec(spec, "spec.yaml", "/"));
}

// The fake record with a falsify object whose numbers depend on the unit.
UnitRecord falsify_record(const SweepUnit& u, int threads) {
  UnitRecord r = fake_record(u, threads);
  r.falsify = R"({"rollouts":)" + std::to_string(u.falsify_budget + u.falsify_coverage_budget) +
              R"(,"outside":)" + std::to_string(u.index) +
              R"(,"coverage_before":0.25,"coverage_after":0.5,"gap_budget":8,"gaps":[{"reached":true},)"
              R"({"reached":false}],"gaps_reached":1,"failure_budget":5,"failures":2})";
  return r;
}

TEST_F(SweepStore, FalsifyColumnsRoundTripThroughCommitMergeAndCsv) {
  const auto units = falsify_units();
  ASSERT_EQ(units.size(), 4u);
  const auto db = dir_ / "r.sqlite";
  run_all(db, units, falsify_record);
  EXPECT_EQ(query_rows(db, "PRAGMA user_version")[0][0], "3");
  EXPECT_EQ(query_count(db,
                        "SELECT count(*) FROM configs WHERE falsify_budget = 32 AND "
                        "falsify_coverage_budget = 16"),
            4);
  const auto row = query_rows(db,
                              "SELECT m.falsify FROM metrics m JOIN configs c USING (config_id) WHERE "
                              "c.unit_key = '" +
                                  units[3].unit_key + "'");
  ASSERT_EQ(row.size(), 1u);
  EXPECT_EQ(row[0][0], *falsify_record(units[3], 1).falsify);
  // A unit without a search: budgets 0, falsify NULL.
  const auto plain = eight_units();
  run_all(db, {plain[0]});
  EXPECT_EQ(query_rows(db,
                       "SELECT c.falsify_budget, c.falsify_coverage_budget, m.falsify FROM configs c "
                       "JOIN metrics m USING (config_id) WHERE c.unit_key = '" +
                           plain[0].unit_key + "'"),
            (test::Rows{{"0", "0", "NULL"}}));

  // The record's text (a forked unit's way back) keeps the field, and its absence.
  const UnitRecord with = falsify_record(units[1], 1);
  EXPECT_EQ(unit_record_from_text(unit_record_to_text(with)).falsify, with.falsify);
  EXPECT_FALSE(unit_record_from_text(unit_record_to_text(fake_record(units[1], 1))).falsify.has_value());

  // A merge copies the columns.
  ResultsStore merged(dir_ / "merged.sqlite");
  EXPECT_EQ(merged.merge_from(db).merged, 5);
  const std::string columns =
      "SELECT c.unit_key, c.falsify_budget, c.falsify_coverage_budget, m.falsify FROM configs c JOIN metrics "
      "m "
      "USING (config_id) ORDER BY c.unit_key";
  EXPECT_EQ(query_rows(dir_ / "merged.sqlite", columns), query_rows(db, columns));

  // CSV: the tables' new columns last; summary.csv's search columns after the timings.
  ResultsStore store(db);
  store.export_csv(dir_ / "csv");
  const auto configs = lines(dir_ / "csv" / "configs.csv");
  EXPECT_NE(configs[0].find(",controller,falsify_budget,falsify_coverage_budget"), std::string::npos)
      << configs[0];
  const auto metrics = lines(dir_ / "csv" / "metrics.csv");
  EXPECT_NE(metrics[0].find(",rollout_seconds,verify_seconds,falsify"), std::string::npos) << metrics[0];
  const auto summary = lines(dir_ / "csv" / "summary.csv");
  const std::string tail =
      ",verify_seconds,rollout_seconds,falsify_budget,falsify_coverage_budget,falsify_rollouts,falsify_"
      "outside,"
      "falsify_coverage_before,falsify_coverage_after,falsify_gap_budget,falsify_gaps,falsify_gaps_reached,"
      "falsify_failure_budget,falsify_failures";
  ASSERT_GE(summary[0].size(), tail.size());
  EXPECT_EQ(summary[0].substr(summary[0].size() - tail.size()), tail) << summary[0];
  // Unit 3 (slide, seed 2): 48 search rollouts, 3 outside; the plain unit: budgets 0, the rest empty.
  bool found_search = false, found_plain = false;
  for (const std::string& l : summary) {
    if (l.find(units[3].unit_key) != std::string::npos) {
      EXPECT_EQ(l.substr(l.size() - std::string(",32,16,48,3,0.25,0.5,8,2,1,5,2").size()),
                ",32,16,48,3,0.25,0.5,8,2,1,5,2");
      found_search = true;
    }
    if (l.find(plain[0].unit_key) != std::string::npos) {
      EXPECT_EQ(l.substr(l.size() - std::string(",0,0,,,,,,,,,").size()), ",0,0,,,,,,,,,");
      found_plain = true;
    }
  }
  EXPECT_TRUE(found_search);
  EXPECT_TRUE(found_plain);
}

// The schema of results version 2 (before the falsify columns), as cmt wrote it.
constexpr const char* kSchemaVersion2 = R"sql(
CREATE TABLE runs(
  run_id INTEGER PRIMARY KEY,
  spec_path TEXT,
  spec_text TEXT,
  created TEXT,
  shard TEXT                        -- addition: "i/N" of --shard, "rank i/K" under MPI, NULL for all units
);
CREATE TABLE configs(
  config_id INTEGER PRIMARY KEY,
  run_id INTEGER,
  unit_key TEXT UNIQUE NOT NULL,
  task TEXT NOT NULL,
  task_file TEXT,
  task_yaml TEXT NOT NULL,
  strategy TEXT NOT NULL,
  params TEXT NOT NULL,             -- JSON object of the overrides
  n INTEGER,
  seed INTEGER,
  mode TEXT,
  status TEXT NOT NULL DEFAULT 'pending',  -- pending | done
  finished TEXT,
  unit_index INTEGER,               -- addition: position in the spec's expansion
  sticking_trials INTEGER,          -- addition
  counterexample_budget INTEGER,    -- addition
  controller TEXT                   -- addition: impedance | admittance | position (cmt validate --controller)
);
CREATE TABLE predictions(
  config_id INTEGER PRIMARY KEY,
  reliable INTEGER,
  failure TEXT,
  verify_seconds REAL,
  verify_json TEXT,
  verifier_theta_v REAL,            -- addition: the theta_v the verifier used (widened for admittance)
  verifier_model TEXT               -- addition: JSON, that theta_v and why (experiments/validation/verifier_model.h)
);
CREATE TABLE rollouts(
  config_id INTEGER,
  rollout INTEGER,
  motion INTEGER,                   -- the prediction step scoring it (verify_json steps; = the motion's
                                    -- index in a decision-free strategy; steps + its position in the
                                    -- rollout when nothing predicts it), -1: a rollout row without motions
  start_x REAL, start_y REAL, start_z REAL,
  end_x REAL, end_y REAL, end_z REAL,
  atom INTEGER,
  termination TEXT,
  inside INTEGER,
  distance REAL,
  success INTEGER,
  unstable INTEGER,
  PRIMARY KEY(config_id, rollout, motion)
);
CREATE TABLE metrics(
  config_id INTEGER PRIMARY KEY,
  rollouts INTEGER,
  successes INTEGER,
  unstable INTEGER,
  ends INTEGER,
  outside INTEGER,
  soundness REAL,
  coverage REAL,
  coverage_radius REAL,
  contact_tolerance REAL,
  soundness_bug INTEGER,
  counterexample TEXT,
  sticking TEXT,
  rollout_seconds REAL,
  verify_seconds REAL
);
CREATE INDEX configs_status ON configs(status);
CREATE INDEX configs_task_strategy ON configs(task, strategy);
)sql";

// A version-2 database with one finished unit (units[0]) and one pending (units[1]), as cmt 2 wrote them.
void write_version2(const std::filesystem::path& path, const std::vector<SweepUnit>& units) {
  SqliteDb db(path);
  db.exec(kSchemaVersion2);
  db.exec("PRAGMA user_version=2");
  for (int i = 0; i < 2; ++i) {
    const SweepUnit& u = units[static_cast<std::size_t>(i)];
    db.prepare(
          "INSERT INTO configs(config_id, run_id, unit_key, task, task_file, task_yaml, strategy, params, n, "
          "seed, mode, status, finished, unit_index, sticking_trials, counterexample_budget, controller) "
          "VALUES (?, NULL, ?, ?, ?, ?, ?, '{}', ?, ?, 'uniform', ?, ?, ?, 0, 400, 'impedance')")
        .bind(1, i + 1)
        .bind(2, u.unit_key)
        .bind(3, u.task)
        .bind(4, u.task_file)
        .bind(5, u.task_yaml)
        .bind(6, u.strategy)
        .bind(7, u.n)
        .bind(8, static_cast<std::int64_t>(u.seed))
        .bind(9, i == 0 ? "done" : "pending")
        .bind(10, i == 0 ? "2024-05-01T12:00:00.000Z" : "")
        .bind(11, u.index)
        .run();
  }
  db.exec("INSERT INTO predictions VALUES (1, 0, 'v1 may not terminate', 0.5, '{}', 0.25, '{}')");
  db.exec("INSERT INTO rollouts VALUES (1, 0, 0, 3, 0, 3, 0, 0, 0, 2, 'sticking', 1, NULL, 1, 0)");
  db.exec("INSERT INTO metrics VALUES (1, 1, 1, 0, 1, 0, 1.0, 0.5, 0.1, 0.001, 0, NULL, NULL, 0.25, 0.5)");
}

TEST_F(SweepStore, MigratesAVersion2DatabaseInPlace) {
  const auto units = eight_units();
  const auto db = dir_ / "v2.sqlite";
  write_version2(db, units);
  {
    ResultsStore store(db);                                                    // migrates
    EXPECT_EQ(store.done_keys(), (std::set<std::string>{units[0].unit_key}));  // the unit keys still match
    EXPECT_EQ(store.count_units("pending"), 1);
  }
  EXPECT_EQ(query_rows(db, "PRAGMA user_version")[0][0], "3");
  // The columns of a new file, in the same order (new ones at the end), and the old rows kept.
  { ResultsStore fresh(dir_ / "fresh.sqlite"); }
  for (const char* table : {"runs", "configs", "predictions", "rollouts", "metrics"}) {
    const std::string sql = std::string("SELECT name, type FROM pragma_table_info('") + table + "')";
    EXPECT_EQ(query_rows(db, sql), query_rows(dir_ / "fresh.sqlite", sql)) << table;
  }
  EXPECT_EQ(query_rows(db,
                       "SELECT unit_key, status, falsify_budget, falsify_coverage_budget FROM configs "
                       "ORDER BY config_id"),
            (test::Rows{{units[0].unit_key, "done", "0", "0"}, {units[1].unit_key, "pending", "0", "0"}}));
  EXPECT_EQ(query_rows(db, "SELECT coverage, falsify FROM metrics"), (test::Rows{{"0.5", "NULL"}}));
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM rollouts"), 1);
  // The migrated file is a version-3 store: a resumed sweep skips the finished unit and commits the rest.
  const SweepRunCounts c = run_all(db, {units[0], units[1]});
  EXPECT_EQ(c.skipped, 1);
  EXPECT_EQ(c.ran, 1);
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM configs WHERE status = 'done'"), 2);
  // Opening it again changes nothing.
  EXPECT_NO_THROW(ResultsStore{db});
  EXPECT_EQ(query_rows(db, "PRAGMA user_version")[0][0], "3");
  // A version-2 shard merged into a version-3 database (the shard is migrated first).
  write_version2(dir_ / "shard-v2.sqlite", {units[2], units[3]});
  ResultsStore target(dir_ / "target.sqlite");
  EXPECT_EQ(target.merge_from(dir_ / "shard-v2.sqlite").merged, 1);
  EXPECT_EQ(query_rows(dir_ / "target.sqlite",
                       "SELECT falsify_budget FROM configs WHERE unit_key = '" + units[2].unit_key + "'"),
            (test::Rows{{"0"}}));
  // Other versions are still refused.
  {
    SqliteDb old(dir_ / "v1.sqlite");
    old.exec("CREATE TABLE runs(run_id INTEGER PRIMARY KEY); PRAGMA user_version=1");
  }
  try {
    ResultsStore refused(dir_ / "v1.sqlite");
    ADD_FAILURE() << "version 1 opened";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("results schema version 1, this cmt reads version 3"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace cmt

namespace cmt {
namespace {

TEST_F(SweepStore, FindsRankFilesOfAKilledMpiJob) {
  for (const char* name : {"r.sqlite.rank-0", "r.sqlite.rank-12", "r.sqlite.rank-0-wal", "r.sqlite.rank-x",
                           "rXsqlite.rank-1", "r.sqlite", "other.sqlite.rank-1"})
    test::write_file(dir_ / name, "");
  const std::string db = (dir_ / "r.sqlite").string();
  EXPECT_EQ(leftover_rank_dbs(db), (std::vector<std::string>{db + ".rank-0", db + ".rank-12"}));
  EXPECT_EQ(rank_db_path(db, 3), db + ".rank-3");
}

}  // namespace
}  // namespace cmt
