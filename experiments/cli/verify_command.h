// `cmt verify TASK --strategy NAME --json` (docs/contracts.md) and `cmt verify TASK --motion NAME --json`
// (one motion from the task's start): Buckley's verifier for decision-free strategies of generalized-damper
// motions. Fields: reliable, steps (motion, termination = [{atom, kind, polygon}]), seconds; when unreliable
// also failed_step, failure and outside_goal (the offending termination pieces). The verifier runs under a
// wall-clock limit (--time-limit, default kDefaultVerifyTimeLimit): every answer has timed_out, and one that
// ran out of time is not reliable, with timed_out true, time_limit, an empty steps list and exit status 1.
// `cmt verify TASK --strategy NAME --edr [--resolution K] --json`: the EDR verdict over the task's
// model-error slices (experiments/edr/edr_verdict.h, the fields of `cmt edr` and `reliable`); the strategy's
// last motion carries `edr: true`. Also under --time-limit (past it: not reliable, timed_out true). Exit 0
// EDR-reliable, 1 not, 2 bad input.
#pragma once

#include <chrono>
#include <nlohmann/json.hpp>

#include "models/loaded_task.h"
#include "verifier/verify.h"

namespace cmt {

inline constexpr double kDefaultVerifyTimeLimit = 600;  // seconds

// The verification in a forked child under the wall-clock limit `time_limit` (s): verify_json, the time-out
// answer (timed_out true, not reliable), or {"error": message} for a motion the verifier does not support.
nlohmann::json verify_json_within_time_limit(const LoadedTask& task, const Strategy& strategy,
                                             const VerifyOptions& options, double time_limit,
                                             bool with_reached, std::chrono::steady_clock::time_point start);

}  // namespace cmt
