// The `cmt teach --json` object (docs/contracts.md): solved, steps (per step motion, chain, solved_regions
// and start_remaining as [{atom, name, kind, polygon}], the measures, failure and blocking pieces, counts and
// seconds), strategy (the taught strategy in the task format's list or branch form, or null), and the taught
// task file that `-o` writes.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "experiments/common/task_motions.h"
#include "verifier/teaching/teaching_session.h"

namespace cmt {

// A strategy as the task format writes it (docs/task-format.md "strategies"): a list of motion names, ending
// in {"branch": [{"when": {"position": [{"box": {min, max}}]}, "then": [...]}, ..., {"else": [...]}]} after
// a motion followed by a sensing test.
nlohmann::json strategy_json(const Strategy& strategy, int dimension);

nlohmann::json teach_step_json(const teaching::Session& session, const teaching::TeachStep& step);
nlohmann::json teach_json(const teaching::Session& session, double seconds);

// The task file text with the teaching session's inline motions and the taught strategy (named
// `strategy_name`) added.
std::string taught_task_yaml(const std::string& task_yaml, const teaching::Session& session,
                             const Strategy& strategy, const std::string& strategy_name);
// The same with the start replaced by `start` (a solved cell, for the pre-image check).
std::string cell_task_yaml(const std::string& task_yaml, const teaching::Session& session,
                           const Strategy& strategy, const std::string& strategy_name, const Region& start);
// The task file text with `strategy` added (named `strategy_name`) and the start replaced by `start`.
std::string strategy_task_yaml(const std::string& task_yaml, int dimension,
                               const std::vector<std::string>& strategy, const std::string& strategy_name,
                               const Region& start);

}  // namespace cmt
