// Taught strategies as trees (Buckley §5.1, Alg 5.1): a chain of motions, or a motion followed by a sensed
// dispatch, in the task format's Strategy (models/task.h: nodes in pre-order, branches on sensed position).
#pragma once

#include <string>
#include <vector>

#include "models/task.h"

namespace cmt::teaching {

// The decision-free chain of `motions`, named "taught".
Strategy chain_strategy(std::vector<std::string> motions);

// `motion`, then `rest` (nothing after it when `rest` has no node).
Strategy followed_by(const std::string& motion, const Strategy& rest);

// The part of `strategy` run from node `first` on (its subtree), renumbered from 0.
Strategy subtree(const Strategy& strategy, int first);

// One branch of a sensed dispatch: the test `when` (ignored for the last branch, the `else`) and the strategy
// run when it passes (no node: stop there).
struct DispatchBranch {
  MotionTermination when;
  Strategy then;
};

// `motion`, then one sensing test (Buckley §4.2): the first branch whose test passes; the last branch is the
// `else`. Needs at least two branches.
Strategy dispatch(const std::string& motion, const std::vector<DispatchBranch>& branches);

// The same motions, links and tests (names aside).
bool same_strategy(const Strategy& a, const Strategy& b);

// A one-line text: "p2, p1"; a dispatch as "down, branch {when position in 2 boxes: [lift]; else: []}".
std::string strategy_text(const Strategy& strategy);

}  // namespace cmt::teaching
