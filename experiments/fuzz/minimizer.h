// A greedy minimizer for failing task files: removes YAML map entries and list items while the failure
// persists, then lines, then byte ranges. Bounded in tries and seconds, so a slow failure (a hang) still
// finishes.
#pragma once

#include <functional>
#include <string>

namespace cmt::fuzz {

struct MinimizeBudget {
  size_t tries = 300;
  double seconds = 300;
};

// The smallest text found for which still_fails holds; `text` itself must fail.
std::string minimize_text(const std::string& text, const std::function<bool(const std::string&)>& still_fails,
                          const MinimizeBudget& budget);

}  // namespace cmt::fuzz
