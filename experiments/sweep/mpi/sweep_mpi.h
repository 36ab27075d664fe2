// `cmt sweep` under mpirun (docs/sweeps.md "MPI"): rank r runs the units with index mod K == r into its own
// database DB.rank-r; after all ranks finish, rank 0 merges them into DB and deletes them. Only rank 0 opens
// DB, so the main file is never written by two nodes at once (SQLite locking is unreliable on network file
// systems); DB's folder must be shared by the ranks. Rank files left by a killed job are merged at the start
// of the next one, so nothing committed is lost.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/sweep/sweep_runner.h"

namespace cmt {

class MpiSession;

// Returns the summary JSON (rank 0; other ranks get an empty object). `threads` 0: hardware threads shared
// among the ranks of a node.
nlohmann::json run_sweep_mpi(const MpiSession& mpi, const SweepSpec& spec,
                             const std::vector<SweepUnit>& units, const std::string& db, int threads,
                             const UnitExecutor& execute);

// The database files a rank of an MPI sweep into `db` writes, and those left behind by earlier jobs.
std::string rank_db_path(const std::string& db, int rank);
std::vector<std::string> leftover_rank_dbs(const std::string& db);

}  // namespace cmt
