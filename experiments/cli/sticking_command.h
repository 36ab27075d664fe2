// `cmt sticking TASK --motion NAME --json` (docs/contracts.md): per atom {atom, kind, class} with class
// must/may/never under the motion's error bounds; damper motions add each face's sliding cone, spring motions
// each face's weak and strong sticking configurations (Buckley Fig 3.16) as polygons.
#pragma once

#include <nlohmann/json.hpp>

#include "experiments/report/view_data.h"
#include "models/loaded_task.h"

namespace cmt {

nlohmann::json sticking_json(const LoadedTask& task, const Motion& motion);

// The stick class of an atom under a motion of a task, from sticking_json (cached per task and motion), for
// the 3-D pages (experiments/report/view_data.h). The task must outlive the returned function's use.
report::StickClassOf verifier_stick_classes();

}  // namespace cmt
