// cmt sweep SPEC --db DB [--shard i/N] [--threads T] [--list] [--json] (docs/sweeps.md): validates every unit
// of a sweep spec into a SQLite results database, skipping units already done there; under mpirun the units
// are split across the ranks (experiments/sweep/mpi/sweep_mpi.h).
#include <unistd.h>

#include <algorithm>
#include <iostream>
#include <thread>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/sweep/mpi/mpi_launch.h"
#include "experiments/sweep/mpi/sweep_mpi.h"
#include "experiments/sweep/sweep_executor.h"
#include "experiments/sweep/sweep_progress.h"
#include "models/task_error.h"

namespace cmt {

namespace {

nlohmann::json unit_json(const SweepUnit& u) {
  return {{"index", u.index},
          {"unit_key", u.unit_key},
          {"task", u.task},
          {"task_file", u.task_file},
          {"strategy", u.strategy},
          {"params", u.params},
          {"n", u.n},
          {"seed", u.seed},
          {"mode", sample_mode_name(u.mode)},
          {"controller", controller_form_name(u.controller)},
          {"sticking_trials", u.sticking_trials},
          {"counterexample_budget", u.counterexample_budget},
          {"verify_budget_seconds", u.verify_budget_seconds},
          {"falsify",
           {{"budget", u.falsify_budget},
            {"coverage_budget", u.falsify_coverage_budget},
            {"gap_budget", u.falsify_gap_budget},
            {"failure_budget", u.falsify_failure_budget}}}};
}

void print_summary(const nlohmann::json& j, bool json) {
  if (json) {
    print_json(j);
    return;
  }
  std::cout << "sweep " << j["spec"].get<std::string>() << " -> " << j["db"].get<std::string>() << ": "
            << j["ran"] << " units run, " << j["skipped"] << " skipped (already done), " << j["done_in_db"]
            << " done and " << j["pending_in_db"] << " pending in the database, "
            << format_duration(j["seconds"].get<double>()) << "\n";
}

}  // namespace

void add_sweep_command(CLI::App& app, CommandState& state) {
  struct Options {
    std::string spec, db, shard;
    int threads = 0;
    bool list = false;
  };
  auto o = std::make_shared<Options>();
  auto* cmd =
      app.add_subcommand("sweep", "Validate every unit of a sweep spec into a SQLite results database");
  cmd->add_option("SPEC", o->spec, "sweep spec YAML file (docs/sweeps.md)")->required();
  cmd->add_option("--db", o->db, "results database (created if missing; finished units are skipped)");
  cmd->add_option("--shard", o->shard, "run only units with index mod N == i (i/N, 0 <= i < N)");
  cmd->add_option("--threads", o->threads,
                  "rollout threads per unit (default: hardware threads); results do not depend on it");
  cmd->add_flag("--list", o->list, "list the units (of the shard) as JSON and exit; needs no --db");
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([o, &state] {
    if (o->threads < 0)
      throw CLI::ValidationError("--threads", "must be >= 0, got " + std::to_string(o->threads));
    const Shard shard = o->shard.empty() ? Shard{} : parse_shard(o->shard);
    const SweepSpec spec = load_sweep_spec(o->spec);
    int duplicates = 0;
    const std::vector<SweepUnit> units = expand_units(spec, &duplicates);
    if (duplicates > 0)
      std::cerr << "cmt sweep: " << duplicates << " units repeat earlier ones (same values) and run once\n";

    std::vector<SweepUnit> mine;
    for (const SweepUnit& u : units)
      if (shard.contains(u.index)) mine.push_back(u);
    if (o->list) {
      nlohmann::json list = nlohmann::json::array();
      for (const SweepUnit& u : mine) list.push_back(unit_json(u));
      print_json({{"spec", spec.path},
                  {"shard", shard.text()},
                  {"total", units.size()},
                  {"duplicates", duplicates},
                  {"units", list}});
      state.exit_status = kExitSuccess;
      return;
    }
    if (o->db.empty()) throw CLI::ValidationError("--db", "give the results database (or --list)");

    if (launched_by_mpi()) {
      if (!o->shard.empty())
        throw CLI::ValidationError("--shard", "cannot be combined with mpirun: the ranks split the units");
      MpiSession mpi;
      try {
        const nlohmann::json j =
            run_sweep_mpi(mpi, spec, units, o->db, o->threads, make_validation_executor());
        if (mpi.rank() == 0) print_summary(j, state.json);
      } catch (const std::exception& e) {
        // One rank failing must not leave the others waiting in a collective call.
        report_bad_input("rank " + std::to_string(mpi.rank()) + ": " + e.what(), state.json);
        mpi.abort(kExitBadInput);
      }
      state.exit_status = kExitSuccess;
      return;
    }

    const auto start = std::chrono::steady_clock::now();
    ResultsStore store(o->db);
    const auto run_id = store.add_run(spec.path, spec.text, o->shard.empty() ? "" : shard.text());
    store.register_units(run_id, mine);
    SweepRunOptions options;
    options.threads =
        o->threads > 0 ? o->threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    options.progress_bar = isatty(STDERR_FILENO);
    const std::set<std::string> done = store.done_keys();
    const SweepRunCounts counts = run_units(store, mine, done, make_validation_executor(), options);
    if (counts.skipped > 0)
      std::cerr << "cmt sweep: skipped " << counts.skipped << " units already done in " << o->db << "\n";
    print_summary(
        {{"db", o->db},
         {"spec", spec.path},
         {"shard", shard.text()},
         {"threads", options.threads},
         {"total", units.size()},
         {"duplicates", duplicates},
         {"units", counts.units},
         {"skipped", counts.skipped},
         {"ran", counts.ran},
         {"taken", counts.taken},
         {"done_in_db", store.count_units("done")},
         {"pending_in_db", store.count_units("pending")},
         {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()}},
        state.json);
    state.exit_status = kExitSuccess;
  });
}

}  // namespace cmt
