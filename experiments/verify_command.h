// `cmt verify TASK --strategy NAME --json` (contracts.md) and `cmt verify TASK --motion NAME --json` (one
// motion from the task's start): Buckley's verifier for decision-free strategies of generalized-damper
// motions. Fields: reliable, steps (motion, termination = [{atom, kind, polygon}]), seconds; when unreliable
// also failed_step, failure and outside_goal (the offending termination pieces).
#pragma once

#include <nlohmann/json.hpp>

#include "models/loaded_task.h"
#include "verifier/verify.h"

namespace cmt {

// with_reached: each step also lists `reached`, every contact point the motion may pass through.
nlohmann::json verify_json(const LoadedTask& task, const VerifyResult& result, double seconds,
                           bool with_reached = false);

}  // namespace cmt
