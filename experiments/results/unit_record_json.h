// A unit's results (UnitRecord) as JSON and back, exactly: the verifier budget (verifier_budget.h) computes
// a unit in a child process and sends its record to the parent, which commits it like any other. Doubles
// keep every bit (shortest round-trip text; non-finite values, which JSON lacks, as strings).
#pragma once

#include <string>

#include "experiments/results/results_store.h"

namespace cmt {

std::string unit_record_to_text(const UnitRecord& record);
// Throws std::runtime_error on text that unit_record_to_text did not write.
UnitRecord unit_record_from_text(const std::string& text);

}  // namespace cmt
