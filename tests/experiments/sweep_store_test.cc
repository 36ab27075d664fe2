// The results store and the sweep runner with a fake executor (no verifier, no MuJoCo): atomic commits,
// resume after a crash without loss or duplicates, merging shards, CSV export.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "experiments/results/results_store.h"
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
      "has_counterexample,verify_seconds,rollout_seconds");
  // Unit 0: down, friction 0.2, seed 1: the fake's values (coverage 1/(1+0) = 1).
  EXPECT_EQ(summary[1], "1," + units[0].unit_key +
                            ",two_blocks,down,6,1,uniform,impedance,0,0.2,0,\"ends \"\"outside\"\", "
                            "e.g.\nthe floor\",0.25,6,3,0,6,3,0.5,1.0,0.1,0.001,0,1,0.5,0.25");
  // Unit 2: slide, reliable, no failure text (empty field), coverage 1/3 in shortest round-trip form.
  EXPECT_EQ(summary[2],
            "3," + units[2].unit_key +
                ",two_blocks,slide,6,1,uniform,impedance,0,0.2,1,,0.25,6,3,0,6,3,0.5,0.3333333333333333,0.1,"
                "0.001,0,0,0.5,0.25");

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
