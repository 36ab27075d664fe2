// The `cmt verify --json` object (docs/contracts.md, docs/verifier.md "Output"): reliable, steps (motion,
// termination = [{atom, name, kind, polygon}], ...), seconds, the verifier options; when unreliable also
// failed_step, failure and outside_goal (the offending termination pieces). `cmt validate` and the sweep's
// results store keep it as the prediction.
#pragma once

#include <nlohmann/json.hpp>

#include "models/loaded_task.h"
#include "verifier/verify.h"

namespace cmt {

// Termination-style pieces as [{atom, name, kind, polygon, holes?, area?}] (points in the task's dimension).
nlohmann::json pieces_json(const LoadedTask& task, const std::vector<ReachedPiece>& pieces);

// with_reached: each step also lists `reached`, every contact point the motion may pass through.
nlohmann::json verify_json(const LoadedTask& task, const VerifyResult& result, double seconds,
                           bool with_reached = false);

}  // namespace cmt
