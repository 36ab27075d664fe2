// The verifier's verdicts on the planner's chains of commanded positions (verifier/planner/verifier_check.h),
// memoized, and verified ahead in forked children when the search announces the chains it will ask for next
// (PlanRequest::prefetch): the verifier is single-threaded, so independent checks run in processes. Up to
// `parallel` children run at once: an announced chain's child starts when it is announced, if a slot is free,
// and is collected when the chain is asked for, so the search waits only for the chain it needs. A chain
// whose child failed (or that was never announced) is verified in this process when asked for. The verdicts,
// and so the plan, do not depend on how many run at once.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "experiments/common/verifier_budget.h"
#include "models/loaded_task.h"
#include "verifier/planner/search.h"
#include "verifier/verify.h"

namespace cmt {

class ChainVerdicts {
 public:
  // `parallel`: children at a time for prefetch (1: prefetch does nothing, every chain is verified when
  // asked for, in this process).
  ChainVerdicts(const LoadedTask& task, const VerifyOptions& options, const MotionTermination& terminate,
                int parallel);

  // The verdict on the chain: from the memo, from its child (waiting for it), or verified now (in this
  // process, while the other children run on).
  planner::ChainVerdict get(const std::vector<Vec3>& commanded);
  // Collects the children that have ended, then starts children for the chains not yet known nor running, in
  // order, while fewer than `parallel` run; the rest are not queued (the search announces again each round).
  // When a pipe or a fork fails, prefetching stops for good.
  void prefetch(const std::vector<std::vector<Vec3>>& chains);
  // Kills (and reaps) the children whose chains were never asked for: the search is over.
  void stop() { running_.clear(); }
  // Children started and not yet collected.
  std::size_t running() const { return running_.size(); }
  // Wall-clock seconds spent verifying (in this process or waiting for the children).
  double seconds() const { return seconds_; }

 private:
  // The verdict a child sent, or nothing when it failed (died, threw, or sent no verdict).
  static std::optional<planner::ChainVerdict> collect(const ForkedWork& work);

  const LoadedTask& task_;
  VerifyOptions options_;
  MotionTermination terminate_;
  int parallel_ = 1;
  std::map<std::vector<double>, planner::ChainVerdict> known_;
  std::map<std::vector<double>, std::unique_ptr<ForkedWork>> running_;
  double seconds_ = 0;
};

// A verdict as text and back (the children's results): "reliable\n" then one line per motion, its end atoms
// or "-" where it may fail.
std::string verdict_text(const planner::ChainVerdict& v);
planner::ChainVerdict verdict_from_text(const std::string& text);

}  // namespace cmt
