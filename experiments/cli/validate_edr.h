// `cmt validate TASK --strategy NAME --edr -n N --seed S [--per-world K] [--resolution R] [--refine D]
// [--mode M]
// [--threads T] --json` (docs/contracts.md): an EDR strategy against MuJoCo rollouts in worlds drawn
// uniformly over the model parameters' intervals (experiments/edr/edr_check.h, docs/edr.md "Physics check").
// The strategy's last motion must carry the EDR termination predicate (`edr: true`).
#pragma once
#include <cstdint>
#include <string>

#include "controllers/error_model.h"
#include "experiments/edr/edr_verdict.h"

namespace cmt {

struct ValidateEdrOptions {
  std::string task, strategy;
  int rollouts = 1000, per_world = 20, resolution = 5, threads = 1;
  int refine_depth = EdrVerdictRequest{}.refine_depth;  // slicing-gap refinement (cmt edr --refine)
  std::uint64_t seed = 1;
  SampleMode mode = SampleMode::kUniform;
  bool json = false;
};

// Prints the result and returns the exit status: 1 when physics contradicts the verifier (a motion end
// outside a world's predicted termination set, or a forbidden outcome of a strategy verified EDR-reliable),
// else 0. Bad input throws InputError.
int validate_edr(const ValidateEdrOptions& options);

}  // namespace cmt
