// Runs the units of a sweep into a results store (docs/sweeps.md "Running"): units one after another, each
// committed in its own transaction as soon as it finishes; units already done in the store are skipped.
// The executor of a unit is a parameter: `cmt sweep` passes the real validation (sweep_executor.h), tests a
// fake one.
#pragma once

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "experiments/results/results_store.h"
#include "experiments/sweep/spec/sweep_units.h"

namespace cmt {

// Computes one unit's results with `threads` worker threads (results must not depend on it).
using UnitExecutor = std::function<UnitRecord(const SweepUnit& unit, int threads)>;

struct SweepRunOptions {
  int threads = 1;
  bool progress_bar = false;  // stderr is a terminal
  std::string log_prefix;     // "[rank i] " under MPI
};

struct SweepRunCounts {
  int units = 0;    // given to this run
  int skipped = 0;  // already done before it started
  int ran = 0;      // computed and committed by this run
  int taken = 0;    // computed, but another process committed the unit first (nothing written)
  double seconds = 0;
};

// Runs every unit of `units` whose key is not in `done`, in order. An exception from the executor or the
// store stops the run (units committed so far stay), rethrown with the unit named.
SweepRunCounts run_units(ResultsStore& store, const std::vector<SweepUnit>& units,
                         const std::set<std::string>& done, const UnitExecutor& execute,
                         const SweepRunOptions& options);

// "two_blocks/down seed 1 {"friction":0.3}": a unit for messages.
std::string describe_unit(const SweepUnit& unit);

}  // namespace cmt
