// The 3-D page of a teaching session (`cmt teach --view DIR`, docs/teaching.md "The 3-D page"): the task's
// scene (report/view_data.h) and, per step, layers for the solved and the remaining start cells, where the
// proposed motion may stop from each, and the stops from which the earlier chain fails (Buckley's "weak
// sticking points to avoid", Figs 5.4 and 5.7).
#pragma once

#include <nlohmann/json.hpp>

#include "verifier/teaching/teaching_session.h"

namespace cmt {

nlohmann::json teach_view_data(const teaching::Session& session, const std::string& title);

}  // namespace cmt
