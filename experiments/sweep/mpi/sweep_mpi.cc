#include "experiments/sweep/mpi/sweep_mpi.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <regex>
#include <sstream>
#include <thread>

#include "experiments/sweep/mpi/mpi_launch.h"

namespace cmt {

namespace {

void remove_db_files(const std::string& path) {
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) std::filesystem::remove(path + suffix);
}

std::string join_keys(const std::set<std::string>& keys) {
  std::string s;
  for (const std::string& k : keys) s += k + "\n";
  return s;
}

std::set<std::string> split_keys(const std::string& text) {
  std::set<std::string> keys;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) keys.insert(line);
  return keys;
}

}  // namespace

std::string rank_db_path(const std::string& db, int rank) { return db + ".rank-" + std::to_string(rank); }

std::vector<std::string> leftover_rank_dbs(const std::string& db) {
  const std::filesystem::path p(db);
  const std::filesystem::path dir = p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
  const std::regex name(
      std::regex_replace(p.filename().string(), std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
      R"(\.rank-[0-9]+)");
  std::vector<std::string> found;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.is_regular_file() && std::regex_match(e.path().filename().string(), name))
      found.push_back((dir / e.path().filename()).string());
  std::sort(found.begin(), found.end());
  return found;
}

nlohmann::json run_sweep_mpi(const MpiSession& mpi, const SweepSpec& spec,
                             const std::vector<SweepUnit>& units, const std::string& db, int threads,
                             const UnitExecutor& execute) {
  const int rank = mpi.rank(), size = mpi.size();
  const auto start = std::chrono::steady_clock::now();
  // Phase 1 (rank 0): fold in what a killed job committed, register the job's units, tell every rank
  // which are done.
  std::string done_text;
  long long resumed = 0;
  if (rank == 0) {
    ResultsStore store(db);
    for (const std::string& f : leftover_rank_dbs(db)) {
      resumed += store.merge_from(f).merged;
      remove_db_files(f);
    }
    const auto run_id = store.add_run(spec.path, spec.text, "mpi " + std::to_string(size) + " ranks");
    store.register_units(run_id, units);
    done_text = join_keys(store.done_keys());
  }
  const std::set<std::string> done = split_keys(mpi.broadcast(done_text));

  // Phase 2 (every rank): its share of the units into its own file.
  std::vector<SweepUnit> mine;
  for (const SweepUnit& u : units)
    if (u.index % size == rank) mine.push_back(u);
  SweepRunOptions options;
  const int hardware = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  options.threads = threads > 0 ? threads : std::max(1, hardware / mpi.local_size());
  options.progress_bar = rank == 0 && isatty(STDERR_FILENO);
  options.log_prefix = "[rank " + std::to_string(rank) + "] ";
  SweepRunCounts counts;
  {
    const std::string file = rank_db_path(db, rank);
    remove_db_files(file);  // rank 0 merged any earlier one in phase 1
    ResultsStore store(file);
    store.register_units(0, mine);
    counts = run_units(store, mine, done, execute, options);
  }

  // Phase 3: wait for every rank (the sums are collective), then rank 0 merges the rank files.
  const long long skipped = mpi.sum(counts.skipped), ran = mpi.sum(counts.ran), taken = mpi.sum(counts.taken);
  if (rank != 0) return nlohmann::json::object();
  ResultsStore store(db);
  for (int r = 0; r < size; ++r) {
    const std::string file = rank_db_path(db, r);
    store.merge_from(file);
    remove_db_files(file);
  }
  return {{"db", db},
          {"spec", spec.path},
          {"ranks", size},
          {"threads", options.threads},
          {"units", units.size()},
          {"skipped", skipped},
          {"resumed_from_rank_files", resumed},
          {"ran", ran},
          {"taken", taken},
          {"done_in_db", store.count_units("done")},
          {"pending_in_db", store.count_units("pending")},
          {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()}};
}

}  // namespace cmt
