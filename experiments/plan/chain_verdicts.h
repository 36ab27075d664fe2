// The verifier's verdicts on the planner's chains of commanded positions (verifier/planner/verifier_check.h),
// memoized, and verified ahead in forked children when the search announces the chains it will ask for next
// (PlanRequest::prefetch): the verifier is single-threaded, so independent checks run in processes. Up to
// `parallel` children run at once, each started as soon as a slot is free and collected when its chain is
// asked for, so the search waits only for the chain it needs. The verdicts, and so the plan, do not depend on
// how many run at once.
#pragma once

#include <map>
#include <memory>
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

  // The verdict on the chain: from the memo, from its child (waiting for it), or verified now.
  planner::ChainVerdict get(const std::vector<Vec3>& commanded);
  // Starts children for the chains not yet known nor running, in order, while fewer than `parallel` run
  // (after collecting those that have ended).
  void prefetch(const std::vector<std::vector<Vec3>>& chains);
  // Kills the children whose chains were never asked for (the search is over).
  void stop() { running_.clear(); }
  // Children started and not yet collected.
  std::size_t running() const { return running_.size(); }
  // Wall-clock seconds spent verifying (in this process or waiting for the children).
  double seconds() const { return seconds_; }

 private:
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
