// The 3-D pages of the teaching system. A teaching session's (`cmt teach --view DIR`, docs/teaching.md "The
// 3-D page"): the task's scene (report/view_data.h) and, per step, layers for the solved and the remaining
// start cells, where the proposed motion may stop from each, and the stops from which the earlier chain fails
// (Buckley's "weak sticking points to avoid", Figs 5.4 and 5.7).
#pragma once

#include <nlohmann/json.hpp>

#include "verifier/teaching/teaching_session.h"

namespace cmt {

nlohmann::json teach_view_data(const teaching::Session& session, const std::string& title);

// One motion of a backprojected chain (`cmt backproject --view DIR`): its base B (the stops outside its
// target: points to avoid), W(B) and the strong backprojection S (Buckley's Figs 5.5 and 5.8).
struct BackprojectionLayers {
  std::string motion;
  std::vector<ReachedPiece> base, weak, strong;
};
// The task's scene and, per motion (from the goal backwards), its three layers; the first motion's shown.
nlohmann::json backprojection_view_data(const LoadedTask& task,
                                        const std::vector<BackprojectionLayers>& steps,
                                        const std::string& title);

}  // namespace cmt
