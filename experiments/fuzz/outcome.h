// What counts as a failure of one `cmt ... --json` run (docs/fuzzing.md): a signal, an exit status outside
// {0, 1, 2}, stdout that is not exactly one JSON object (with exit 2: one carrying error.message), or the
// hard time-out. A clean `timed_out: true` answer is not a failure; it is counted on its own.
#pragma once

#include <string>

#include "experiments/fuzz/child_process.h"

namespace cmt::fuzz {

struct Outcome {
  bool failure = false;
  bool timed_out = false;  // the answer said timed_out: true (a clean verifier time-out)
  std::string status;      // "0", "1", "2", "exit 139", "signal 11", "hard time-out"
  std::string kind;        // failure kind: hang, signal, exit-status, bad-json, no-error-message
  std::string detail;      // e.g. the signal name or the JSON parse error
};

Outcome check_outcome(const ChildResult& result);

// Whether a candidate run fails the same way as the original (the minimizer keeps a reduction only then).
bool same_failure(const Outcome& original, const Outcome& candidate);

// A short signature grouping failures of one cause: kind, detail and the last stderr line, with the input
// file's path and all digits masked.
std::string failure_class(const Outcome& outcome, const std::string& err, const std::string& input_path);

// The last `lines` lines of text.
std::string tail_lines(const std::string& text, size_t lines);

}  // namespace cmt::fuzz
