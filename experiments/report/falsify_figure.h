// The report's per-motion figures of an adversarial search (`cmt falsify`, docs/falsify.md "In sweeps and
// the report"): one motion's predicted termination set, the unit's random rollout ends of that motion, the
// search's ends by phase, the predicted pieces no rollout reached and the gaps no search covered.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/report/cspace_figure.h"
#include "experiments/report/predicted_sets.h"
#include "experiments/report/results_db.h"

namespace cmt::report {

struct FalsifyMotionFigure {
  int step = 0;
  std::string motion;
  PredictedSets prediction;        // the motion's step alone
  std::vector<RolloutRow> random;  // the random ends of the motion, time-outs left out (motion renumbered 0)
  SearchLayer search;
  View view = View::kFront;  // widest_view of the motion's set
};

// One figure per step of `prediction` that the search measured (a step with a piece in `falsify`'s
// `pieces`, or a search end or gap of it). `falsify` is `cmt falsify --json`'s object; an older one without
// `search_ends` gives figures without search ends. Throws std::invalid_argument naming the JSON path when the
// object does not have that shape.
std::vector<FalsifyMotionFigure> falsify_motion_figures(const nlohmann::json& falsify,
                                                        const PredictedSets& prediction,
                                                        const std::vector<RolloutRow>& rollouts,
                                                        const Task& task);

}  // namespace cmt::report
