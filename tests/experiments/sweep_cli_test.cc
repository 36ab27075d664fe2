// cmt sweep end to end (docs/sweeps.md): a sweep killed with SIGKILL and run again loses and duplicates
// nothing and gives the results of an uninterrupted run; two shards merged, and an mpirun with two ranks,
// give the results of one run (the MPI job also folding in a killed job's rank file); CSV export; bad specs
// exit with status 2 naming file and key. Small, fast units only: two_blocks (damper) and cube (spring)
// verify in ~1-3 s.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <thread>

#include "tests/experiments/cmt_runner.h"
#include "tests/experiments/sweep_test_util.h"

extern char** environ;

namespace cmt {
namespace {

using test::query_count;

// Four units: two_blocks down and slide, cube stick at two frictions.
std::string four_unit_spec() {
  return "n: 10\nseeds: [1]\ncounterexample_budget: 10\ntasks:\n  - file: " +
         test::source_task("two_blocks") +
         "\n    strategies: [down, slide]\n  - file: " + test::source_task("cube") +
         "\n    strategies: [stick]\n    grid:\n      friction: [0.25, 0.3]\n";
}

std::string two_unit_spec() {
  return "n: 10\nseeds: [1]\ncounterexample_budget: 10\ntasks:\n  - file: " +
         test::source_task("two_blocks") + "\n    strategies: [down, slide]\n";
}

nlohmann::json run_json(const std::string& args, int expected_status) {
  const test::Result r = test::run(args + " --json");
  EXPECT_EQ(r.status, expected_status) << args << "\n" << r.out;
  return r.out.empty() ? nlohmann::json() : nlohmann::json::parse(r.out);
}

class SweepCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_dir("sweep-cli"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

// Polls the database until `done` units are committed (or the process exits, or 120 s pass).
bool wait_for_done(const std::string& db, pid_t pid, long long done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    try {
      if (query_count(db, "SELECT count(*) FROM configs WHERE status = 'done'") >= done) return true;
    } catch (const std::exception&) {  // not created yet
    }
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

TEST_F(SweepCli, KillNineThenResumeLosesNothing) {
  const std::string spec = test::write_file(dir_ / "spec.yaml", four_unit_spec()).string();
  const std::string db = path("killed.sqlite"), reference = path("reference.sqlite");

  // Start a sweep, kill it with SIGKILL as soon as one unit is committed (the next one is in flight).
  const std::string log = path("killed.log");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  std::vector<std::string> args = {CMT_BINARY, "sweep", spec, "--db", db, "--threads", "1"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, CMT_BINARY, &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  const bool committed = wait_for_done(db, pid, 1);
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(committed) << "no unit was committed before the sweep ended";
  ASSERT_TRUE(WIFSIGNALED(status)) << "the sweep finished before it was killed";
  const long long done_before = query_count(db, "SELECT count(*) FROM configs WHERE status = 'done'");
  EXPECT_GE(done_before, 1);
  EXPECT_LT(done_before, 4);

  // Rerun: the finished units are skipped, the rest run.
  const nlohmann::json rerun = run_json("sweep " + spec + " --db " + db + " --threads 1", 0);
  EXPECT_EQ(rerun["skipped"], done_before);
  EXPECT_EQ(rerun["ran"], 4 - done_before);
  EXPECT_EQ(rerun["done_in_db"], 4);
  EXPECT_EQ(rerun["pending_in_db"], 0);
  // Every unit exactly once, with one metrics and prediction row each.
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM configs"), 4);
  EXPECT_EQ(query_count(db, "SELECT count(DISTINCT unit_key) FROM configs"), 4);
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM metrics"), 4);
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM predictions"), 4);
  // A third run has nothing left to do.
  const nlohmann::json third = run_json("sweep " + spec + " --db " + db, 0);
  EXPECT_EQ(third["skipped"], 4);
  EXPECT_EQ(third["ran"], 0);

  // The same results as an uninterrupted run (with another thread count).
  const nlohmann::json ref = run_json("sweep " + spec + " --db " + reference + " --threads 2", 0);
  EXPECT_EQ(ref["ran"], 4);
  const test::Rows results = test::unit_results(db);
  EXPECT_EQ(results.size(), 4u);
  EXPECT_EQ(results, test::unit_results(reference));
  EXPECT_EQ(test::rollout_results(db), test::rollout_results(reference));
  // 10 rollouts of one motion per unit.
  EXPECT_EQ(query_count(db, "SELECT count(*) FROM rollouts"), 40);
}

TEST_F(SweepCli, TwoShardsMergedEqualOneRun) {
  const std::string spec = test::write_file(dir_ / "spec.yaml", two_unit_spec()).string();
  const nlohmann::json s0 =
      run_json("sweep " + spec + " --db " + path("s0.sqlite") + " --shard 0/2 --threads 1", 0);
  const nlohmann::json s1 =
      run_json("sweep " + spec + " --db " + path("s1.sqlite") + " --shard 1/2 --threads 1", 0);
  EXPECT_EQ(s0["units"], 1);
  EXPECT_EQ(s1["units"], 1);
  const nlohmann::json merged =
      run_json("merge " + path("merged.sqlite") + " " + path("s0.sqlite") + " " + path("s1.sqlite"), 0);
  EXPECT_EQ(merged["done_in_db"], 2);
  EXPECT_EQ(merged["inputs"][0]["merged"], 1);
  EXPECT_EQ(merged["inputs"][1]["merged"], 1);
  run_json("sweep " + spec + " --db " + path("one.sqlite") + " --threads 2", 0);
  EXPECT_EQ(test::unit_results(path("merged.sqlite")), test::unit_results(path("one.sqlite")));
  EXPECT_EQ(test::rollout_results(path("merged.sqlite")), test::rollout_results(path("one.sqlite")));
  // A merge input that does not exist is bad input, and creates nothing.
  run_json("merge " + path("merged.sqlite") + " " + path("missing.sqlite"), 2);
  EXPECT_FALSE(std::filesystem::exists(path("missing.sqlite")));
}

TEST_F(SweepCli, MpirunTwoRanksResumeAndMergeIntoOneDatabase) {
  const std::string mpirun = CMT_MPIRUN;  // found at configure time (openmpi-bin, scripts/setup.sh)
  const std::string spec = test::write_file(dir_ / "spec.yaml", two_unit_spec()).string();
  // What a killed job leaves behind: a rank file holding unit 0 (here made by a plain shard run).
  const nlohmann::json leftover =
      run_json("sweep " + spec + " --db " + path("mpi.sqlite.rank-7") + " --shard 0/2 --threads 1", 0);
  ASSERT_EQ(leftover["ran"], 1);
  // Containers (CI) run as root, which OpenMPI refuses unless told; --oversubscribe allows 2 ranks on 1 core.
  const std::string cmd = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + mpirun +
                          " -np 2 --oversubscribe " + CMT_BINARY + " sweep " + spec + " --db " +
                          path("mpi.sqlite") + " --threads 1 --json 2>" + path("mpi.log");
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buf[4096];
  while (fgets(buf, sizeof buf, pipe)) out += buf;
  const int raw = pclose(pipe);
  ASSERT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << out;
  const nlohmann::json j = nlohmann::json::parse(out);  // rank 0 alone prints
  EXPECT_EQ(j["ranks"], 2);
  EXPECT_EQ(j["resumed_from_rank_files"], 1);
  EXPECT_EQ(j["skipped"], 1);
  EXPECT_EQ(j["ran"], 1);
  EXPECT_EQ(j["done_in_db"], 2);
  EXPECT_EQ(j["pending_in_db"], 0);
  // The rank files (the leftover too) are merged and gone. Runs: the job's and the leftover's shard run.
  for (const auto& e : std::filesystem::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".rank-"), std::string::npos) << e.path();
  EXPECT_EQ(query_count(path("mpi.sqlite"), "SELECT count(*) FROM runs WHERE shard = 'mpi 2 ranks'"), 1);
  EXPECT_EQ(query_count(path("mpi.sqlite"), "SELECT count(*) FROM configs"), 2);

  run_json("sweep " + spec + " --db " + path("one.sqlite") + " --threads 1", 0);
  EXPECT_EQ(test::unit_results(path("mpi.sqlite")), test::unit_results(path("one.sqlite")));
  EXPECT_EQ(test::rollout_results(path("mpi.sqlite")), test::rollout_results(path("one.sqlite")));
}

// The verifier time budget (docs/sweeps.md): a budget the verifier meets changes no result (the unit runs
// in a child process and its rows come back bit for bit); one it cannot meet (1 ms: loading the task alone
// takes longer) records "verifier: timed out" with the same rollouts, unscored.
TEST_F(SweepCli, VerifierBudgetTimesOutIntoAResultRow) {
  const auto results = [](const std::string& db) {
    return test::query_rows(
        db,
        "SELECT c.task, c.strategy, p.reliable, p.failure, p.verifier_theta_v, m.rollouts, "
        "m.successes, m.unstable, m.ends, m.outside, m.soundness, m.coverage, "
        "m.coverage_radius, m.soundness_bug, m.counterexample FROM configs c JOIN "
        "predictions p USING (config_id) JOIN metrics m USING (config_id) ORDER BY "
        "c.unit_index");
  };
  const auto ends = [](const std::string& db, const std::string& scored) {
    return test::query_rows(
        db, "SELECT c.strategy, r.rollout, r.motion, r.end_x, r.end_y, r.end_z, r.atom, " + scored +
                " r.termination, r.success FROM rollouts r JOIN configs c USING "
                "(config_id) ORDER BY c.unit_index, r.rollout, r.motion");
  };
  const std::string plain = test::write_file(dir_ / "plain.yaml", two_unit_spec()).string();
  const std::string roomy =
      test::write_file(dir_ / "roomy.yaml", "verify_budget_seconds: 600\n" + two_unit_spec()).string();
  const std::string tight =
      test::write_file(dir_ / "tight.yaml", "verify_budget_seconds: 0.001\n" + two_unit_spec()).string();
  run_json("sweep " + plain + " --db " + path("plain.sqlite") + " --threads 2", 0);
  run_json("sweep " + roomy + " --db " + path("roomy.sqlite") + " --threads 2", 0);
  run_json("sweep " + tight + " --db " + path("tight.sqlite") + " --threads 2", 0);
  EXPECT_EQ(results(path("roomy.sqlite")), results(path("plain.sqlite")));
  EXPECT_EQ(ends(path("roomy.sqlite"), "r.inside, r.distance,"),
            ends(path("plain.sqlite"), "r.inside, r.distance,"));

  EXPECT_EQ(query_count(path("tight.sqlite"), "SELECT count(*) FROM configs WHERE status = 'done'"), 2);
  EXPECT_EQ(query_count(path("tight.sqlite"),
                        "SELECT count(*) FROM predictions WHERE reliable = 0 AND failure LIKE "
                        "'verifier: timed out after 0.001 s%'"),
            2);
  // Every end unscored (no prediction), no counterexample search; the rollouts are the same physics.
  EXPECT_EQ(query_count(path("tight.sqlite"), "SELECT sum(ends) + sum(outside) FROM metrics"), 0);
  EXPECT_EQ(query_count(path("tight.sqlite"), "SELECT count(*) FROM rollouts WHERE inside IS NOT NULL"), 0);
  EXPECT_EQ(query_count(path("tight.sqlite"), "SELECT sum(rollouts) FROM metrics"), 20);
  EXPECT_EQ(ends(path("tight.sqlite"), ""), ends(path("plain.sqlite"), ""));
  // A budget of 0 or less is refused (leave the key out for no limit).
  const std::string zero =
      test::write_file(dir_ / "zero.yaml", "verify_budget_seconds: 0\n" + two_unit_spec()).string();
  run_json("sweep " + zero + " --db " + path("zero.sqlite"), 2);
}

// The failure search as a spec key (docs/sweeps.md): two_blocks `down` is verified unreliable (it may stick
// on B's top, where it starts), so a unit with a failure budget runs it and stores its fields in
// metrics.falsify; the falsification and coverage phases are off.
TEST_F(SweepCli, FailureBudgetRunsTheFailureSearchUnderAnUnreliableVerdict) {
  const std::string spec =
      test::write_file(dir_ / "failure.yaml",
                       "n: 6\nseeds: [1]\nfalsify: {budget: 0, coverage_budget: 0, failure_budget: 24}\n"
                       "tasks:\n  - file: " +
                           test::source_task("two_blocks") + "\n    strategies: [down]\n")
          .string();
  run_json("sweep " + spec + " --db " + path("failure.sqlite") + " --threads 2", 0);
  const auto rows = test::query_rows(path("failure.sqlite"), "SELECT falsify FROM metrics");
  ASSERT_EQ(rows.size(), 1u);
  const nlohmann::json f = nlohmann::json::parse(rows[0][0]);
  EXPECT_EQ(f["failure_budget"], 24);
  EXPECT_TRUE(f["failure_searched"].get<bool>());
  EXPECT_GT(f["failure_rollouts"].get<int>(), 0);
  EXPECT_LE(f["failure_rollouts"].get<int>(), 24);
  EXPECT_EQ(f["random_rollouts"], 6);  // the validation's rollouts are the baseline
}

// A unit with a falsify budget (docs/falsify.md "In sweeps and the report"): the search runs after the
// validation against its prediction, with its rollouts as the baseline, in the forked child under a verifier
// budget or in the process without one, with the same result for any thread count; a verifier that timed
// out gives no search; the report lists it.
TEST_F(SweepCli, FalsifySearchRunsAfterTheValidationAndReachesTheReport) {
  const std::string unit =
      "n: 10\nseeds: [1]\nfalsify: {budget: 16, coverage_budget: 16, gap_budget: 8}\ntasks:\n  - file: " +
      test::source_task("two_blocks") + "\n    strategies: [slide]\n";
  const std::string forked =
      test::write_file(dir_ / "forked.yaml", "verify_budget_seconds: 600\n" + unit).string();
  const std::string plain = test::write_file(dir_ / "plain.yaml", unit).string();
  const std::string tight =
      test::write_file(dir_ / "tight.yaml", "verify_budget_seconds: 0.001\n" + unit).string();
  run_json("sweep " + forked + " --db " + path("forked.sqlite") + " --threads 2", 0);
  run_json("sweep " + plain + " --db " + path("plain.sqlite") + " --threads 1", 0);
  run_json("sweep " + tight + " --db " + path("tight.sqlite") + " --threads 2", 0);
  const auto search = [&](const std::string& db) {
    const auto rows = test::query_rows(
        db,
        "SELECT c.falsify_budget, c.falsify_coverage_budget, m.coverage, m.falsify FROM configs c JOIN "
        "metrics m USING (config_id)");
    EXPECT_EQ(rows.size(), 1u);
    EXPECT_EQ(rows[0][0], "16");
    EXPECT_EQ(rows[0][1], "16");
    return rows[0];
  };
  const auto a = search(path("forked.sqlite")), b = search(path("plain.sqlite"));
  nlohmann::json fa = nlohmann::json::parse(a[3]), fb = nlohmann::json::parse(b[3]);
  EXPECT_EQ(fa["task"], "two_blocks");
  EXPECT_EQ(fa["random_rollouts"], 10);  // the validation's rollouts are the baseline
  EXPECT_FALSE(fa.contains("threads"));
  EXPECT_GE(fa["rollouts"].get<int>(), 16);
  EXPECT_LE(fa["rollouts"].get<int>(), 40);
  EXPECT_EQ(fa["gap_budget"], 8);
  int gap_rollouts = 0;
  for (const auto& g : fa["gaps"]) gap_rollouts += g["rollouts"].get<int>();
  EXPECT_GT(gap_rollouts, 0);  // the gap search ran in the unit
  EXPECT_LE(gap_rollouts, 8);
  EXPECT_EQ(fa["outside"], 0);                                      // slide is sound
  EXPECT_EQ(fa["coverage_before"].get<double>(), std::stod(a[2]));  // the validation's own coverage
  // One end per stable search rollout (slide has one motion), each with its phase, for the report's figure.
  EXPECT_EQ(fa["search_ends"].size(), fa["rollouts"].get<std::size_t>() - fa["unstable"].get<std::size_t>());
  for (const auto& e : fa["search_ends"])
    EXPECT_TRUE(e["how"] == "falsify" || e["how"] == "coverage" || e["how"] == "gap");
  for (const char* timing : {"verify_seconds", "random_seconds", "search_seconds", "coverage_seconds",
                             "gap_seconds", "failure_seconds"}) {
    fa.erase(timing);
    fb.erase(timing);
  }
  EXPECT_EQ(fa, fb);  // forked at 2 threads = in process at 1
  // No prediction, no search.
  EXPECT_EQ(test::query_rows(path("tight.sqlite"), "SELECT m.falsify FROM metrics m"),
            (test::Rows{{"NULL"}}));

  const test::Result report = test::run("report " + path("forked.sqlite") + " -o " + path("report"));
  EXPECT_EQ(report.status, 0) << report.out;
  std::ifstream in(dir_ / "report" / "index.html");
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t section = html.find("<h2 id=\"falsify\">Adversarial rollouts</h2>");
  ASSERT_NE(section, std::string::npos) << html;
  EXPECT_NE(html.find("<td>two_blocks / slide</td><td>reliable</td><td>" +
                          std::to_string(fa["rollouts"].get<int>()),
                      section),
            std::string::npos);
  EXPECT_TRUE(std::filesystem::is_regular_file(dir_ / "report" / "figures" / "config_1_falsify_0.png"));
}

TEST_F(SweepCli, ExportCsvWritesEveryTable) {
  const std::string spec = test::write_file(dir_ / "spec.yaml", "n: 5\nseeds: [3]\ntasks:\n  - file: " +
                                                                    test::source_task("two_blocks") +
                                                                    "\n    strategies: [slide]\n")
                               .string();
  run_json("sweep " + spec + " --db " + path("r.sqlite") + " --threads 1", 0);
  const nlohmann::json j = run_json("export-csv " + path("r.sqlite") + " -o " + path("csv"), 0);
  ASSERT_EQ(j["files"].size(), 6u);
  for (const char* name : {"runs", "configs", "predictions", "rollouts", "metrics", "summary"})
    EXPECT_TRUE(std::filesystem::is_regular_file(dir_ / "csv" / (std::string(name) + ".csv"))) << name;
  std::ifstream in(dir_ / "csv" / "rollouts.csv");
  int lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  EXPECT_EQ(lines, 1 + 5);  // header + 5 rollouts of the one-motion strategy
  std::ifstream summary(dir_ / "csv" / "summary.csv");
  std::string header, row;
  std::getline(summary, header);
  std::getline(summary, row);
  EXPECT_EQ(header.rfind("config_id,unit_key,task,strategy,n,seed,mode,controller,sticking_trials,reliable,"
                         "failure,verifier_theta_v,",
                         0),
            0u)
      << header;
  // slide is reliable; the impedance form (the default) is verified with the task's theta_v .25
  EXPECT_NE(row.find(",two_blocks,slide,5,3,uniform,impedance,0,1,,0.25,"), std::string::npos) << row;
  run_json("export-csv " + path("missing.sqlite") + " -o " + path("csv2"), 2);
}

TEST_F(SweepCli, BadSpecsExitWithStatusTwo) {
  const std::string bad_override =
      test::write_file(dir_ / "bad.yaml", two_unit_spec() + "    grid:\n      theta_v: [0.2, 1.7]\n")
          .string();
  nlohmann::json j = run_json("sweep " + bad_override + " --db " + path("r.sqlite"), 2);
  EXPECT_EQ(j["error"]["file"], bad_override);
  EXPECT_EQ(j["error"]["key"], "tasks[0].grid.theta_v[1]");
  EXPECT_NE(j["error"]["reason"].get<std::string>().find("must be < pi/2"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(path("r.sqlite")));  // rejected before any work

  const std::string unknown =
      test::write_file(dir_ / "unknown.yaml", "n: 5\nseeds: [1]\nrollouts: 3\n").string();
  j = run_json("sweep " + unknown + " --db " + path("r.sqlite"), 2);
  EXPECT_EQ(j["error"]["key"], "rollouts");
  run_json("sweep " + path("no-such-spec.yaml") + " --db " + path("r.sqlite"), 2);
  const std::string good = test::write_file(dir_ / "good.yaml", two_unit_spec()).string();
  j = run_json("sweep " + good + " --db " + path("r.sqlite") + " --shard 2/2", 2);
  EXPECT_EQ(j["error"]["key"], "--shard");
  // --list needs no database and shows the shard's units.
  j = run_json("sweep " + good + " --list --shard 1/2", 0);
  ASSERT_EQ(j["units"].size(), 1u);
  EXPECT_EQ(j["units"][0]["strategy"], "slide");
  EXPECT_EQ(j["units"][0]["counterexample_budget"], 10);
  EXPECT_EQ(j["units"][0]["controller"], "impedance");
  EXPECT_EQ(
      j["units"][0]["falsify"],
      (nlohmann::json{{"budget", 0}, {"coverage_budget", 0}, {"gap_budget", 0}, {"failure_budget", 0}}));
  EXPECT_EQ(j["total"], 2);
  // Budgets as the spec sets them.
  const std::string searched =
      test::write_file(dir_ / "searched.yaml",
                       two_unit_spec() +
                           "falsify: {budget: 8, coverage_budget: 4, "
                           "gap_budget: 2, failure_budget: 3}\nverify_budget_seconds: 30\n")
          .string();
  j = run_json("sweep " + searched + " --list", 0);
  ASSERT_EQ(j["units"].size(), 2u);
  EXPECT_EQ(
      j["units"][1]["falsify"],
      (nlohmann::json{{"budget", 8}, {"coverage_budget", 4}, {"gap_budget", 2}, {"failure_budget", 3}}));
  EXPECT_EQ(j["units"][1]["verify_budget_seconds"], 30.0);
}

}  // namespace
}  // namespace cmt
