#include "experiments/fuzz/minimizer.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "experiments/fuzz/yaml_tree.h"

namespace cmt::fuzz {

namespace {

// Counts tries and time; every candidate goes through it.
class Tester {
 public:
  Tester(const std::function<bool(const std::string&)>& still_fails, const MinimizeBudget& budget)
      : still_fails_(still_fails), budget_(budget), start_(std::chrono::steady_clock::now()) {}

  bool exhausted() const {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    return tries_ >= budget_.tries || elapsed >= budget_.seconds;
  }

  bool fails(const std::string& candidate) {
    if (exhausted()) return false;
    ++tries_;
    return still_fails_(candidate);
  }

 private:
  const std::function<bool(const std::string&)>& still_fails_;
  MinimizeBudget budget_;
  std::chrono::steady_clock::time_point start_;
  size_t tries_ = 0;
};

// Every container in DFS order, so removal positions can be addressed as (container, item).
void containers(YamlValue& v, std::vector<YamlValue*>& out) {
  if (v.kind == YamlValue::Kind::kMap || v.kind == YamlValue::Kind::kSequence) out.push_back(&v);
  for (auto& item : v.items) containers(item, out);
}

void erase_item(YamlValue& container, size_t i) {
  if (container.kind == YamlValue::Kind::kMap) container.keys.erase(container.keys.begin() + i);
  container.items.erase(container.items.begin() + i);
}

// Removes map entries and list items, outermost first, as long as the written document still fails. Removing
// an item of container c leaves the DFS positions of c and of the containers before it unchanged.
void reduce_tree(YamlValue& root, Tester& tester) {
  for (size_t c = 0; !tester.exhausted(); ++c) {
    std::vector<YamlValue*> all;
    containers(root, all);
    if (c >= all.size()) break;
    for (size_t i = 0; i < all[c]->items.size() && !tester.exhausted();) {
      YamlValue candidate = root;
      std::vector<YamlValue*> copy;
      containers(candidate, copy);
      erase_item(*copy[c], i);
      if (tester.fails(to_document(candidate))) {
        root = std::move(candidate);
        all.clear();
        containers(root, all);
      } else {
        ++i;
      }
    }
  }
}

std::string concat(const std::vector<std::string>& parts) {
  std::string out;
  for (const auto& p : parts) out += p;
  return out;
}

// Removes chunks of the given units (lines or bytes), halving the chunk size down to one unit.
std::vector<std::string> reduce_units(std::vector<std::string> units, Tester& tester) {
  for (size_t chunk = std::max<size_t>(1, units.size() / 2); chunk >= 1 && !tester.exhausted(); chunk /= 2) {
    for (size_t at = 0; at < units.size() && !tester.exhausted();) {
      std::vector<std::string> candidate(units.begin(), units.begin() + at);
      candidate.insert(candidate.end(), units.begin() + std::min(units.size(), at + chunk), units.end());
      if (tester.fails(concat(candidate)))
        units = std::move(candidate);
      else
        at += chunk;
    }
    if (chunk == 1) break;
  }
  return units;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  size_t start = 0;
  while (start < text.size()) {
    const size_t end = text.find('\n', start);
    const size_t stop = end == std::string::npos ? text.size() : end + 1;
    lines.push_back(text.substr(start, stop - start));
    start = stop;
  }
  return lines;
}

}  // namespace

std::string minimize_text(const std::string& text, const std::function<bool(const std::string&)>& still_fails,
                          const MinimizeBudget& budget) {
  Tester tester(still_fails, budget);
  std::string best = text;
  if (bracket_depth(text) <= 200) {
    try {
      YamlValue tree = parse_yaml(text);
      const std::string written = to_document(tree);
      if (tester.fails(written)) {
        reduce_tree(tree, tester);
        best = to_document(tree);
      }
    } catch (const std::exception&) {
      // not YAML: lines and bytes only
    }
  }
  best = concat(reduce_units(lines_of(best), tester));
  if (best.size() > 40 && !tester.exhausted()) {
    std::vector<std::string> bytes;
    for (char c : best) bytes.push_back(std::string(1, c));
    best = concat(reduce_units(bytes, tester));
  }
  return best;
}

}  // namespace cmt::fuzz
