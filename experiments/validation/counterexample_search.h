// The counterexample search of `cmt validate` (docs/validation.md "Counterexamples"): when the verifier says
// a strategy is unreliable but no rollout failed, up to a budget of extra rollouts looks for a failing one.
// Every search rollout is rollout 0 of a derived seed, so `cmt rollout TASK --strategy S -n 1 --seed SEED
// --mode MODE` replays it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "experiments/validation/validation.h"

namespace cmt {

// Search rollouts run in batches of this many (in parallel); the search stops after the batch holding the
// first failure, so what it runs depends on the batch size, never on the thread count.
inline constexpr int kSearchBatch = 8;
// Local search: candidate starts within this fraction of the start region's diameter of the current centre.
inline constexpr double kLocalStartFraction = 0.1;
// Candidates whose start is predicted and rejected, per rollout of budget, before a phase gives up.
inline constexpr int kMaxScanPerRollout = 1000;

struct SearchResult {
  std::optional<Counterexample> counterexample;
  SearchReport report;
};

// The master seed of search candidate k of a phase (1 extreme, 2 start vertices, 3 local search).
std::uint64_t search_seed(std::uint64_t seed, int phase, std::uint64_t k);

// `rollouts` are the validation's rollouts (run under options.seed and options.mode), the start of the local
// search. Throws what run_rollouts throws.
SearchResult search_counterexample(std::shared_ptr<const LoadedTask> task, const Strategy& strategy,
                                   const ValidateOptions& options, const VerifyResult& prediction,
                                   const std::vector<RolloutOutcome>& rollouts, double contact_tolerance);

}  // namespace cmt
