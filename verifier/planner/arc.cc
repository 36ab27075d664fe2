// Arc composition (arc.h, Buckley §6.6.2, Table 6.4).
#include "verifier/planner/arc.h"

#include <algorithm>

namespace cmt::planner {

std::vector<int> target_union(const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<int> out;
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

std::vector<Arc> merge_identical_targets(const std::vector<Arc>& arcs) {
  std::vector<Arc> out;
  for (const Arc& arc : arcs) {
    if (arc.cpositions.empty()) continue;
    auto same = std::find_if(out.begin(), out.end(), [&](const Arc& o) { return o.targets == arc.targets; });
    if (same == out.end())
      out.push_back(arc);
    else
      same->cpositions = same->cpositions.unite(arc.cpositions);
  }
  return out;
}

std::vector<Arc> compose_type1(const std::vector<Arc>& weak_arcs) {
  std::vector<Arc> composed;  // Ψ2: nonoverlapping
  for (Arc alpha : merge_identical_targets(weak_arcs)) {
    std::vector<Arc> next;
    for (const Arc& beta : composed) {
      if (alpha.cpositions.empty()) {
        next.push_back(beta);
        continue;
      }
      Arc both{target_union(alpha.targets, beta.targets), alpha.cpositions.intersect(beta.cpositions)};
      Arc beta_only{beta.targets, beta.cpositions.minus(alpha.cpositions)};
      alpha.cpositions = alpha.cpositions.minus(beta.cpositions);
      if (!both.cpositions.empty()) next.push_back(std::move(both));
      if (!beta_only.cpositions.empty()) next.push_back(std::move(beta_only));
    }
    if (!alpha.cpositions.empty()) next.push_back(std::move(alpha));
    composed = std::move(next);
  }
  return merge_identical_targets(composed);
}

}  // namespace cmt::planner
