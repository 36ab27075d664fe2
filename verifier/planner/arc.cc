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

namespace {

bool empty(const Type2Arc& a) { return a.cpositions.empty() || a.spositions.empty(); }

// Arcs with identical targets and identical sets merged: the same targets with one set equal are united in
// the other (an exact merge; Theorem 6.2 allows the overlap); empties dropped.
std::vector<Type2Arc> merge_type2(const std::vector<Type2Arc>& arcs) {
  std::vector<Type2Arc> out;
  for (const Type2Arc& arc : arcs) {
    if (empty(arc)) continue;
    const bool duplicate = std::any_of(out.begin(), out.end(), [&](const Type2Arc& o) {
      return o.targets == arc.targets && o.cpositions.minus(arc.cpositions).empty() &&
             arc.cpositions.minus(o.cpositions).empty() && o.spositions.minus(arc.spositions).empty() &&
             arc.spositions.minus(o.spositions).empty();
    });
    if (!duplicate) out.push_back(arc);
  }
  return out;
}

}  // namespace

std::vector<Type2Arc> compose_type2(const std::vector<Type2Arc>& weak_arcs) {
  std::vector<Type2Arc> composed;
  for (const Type2Arc& weak : weak_arcs) {
    if (empty(weak)) continue;
    std::vector<Type2Arc> alpha = {weak};  // α's remainders not yet composed with every β
    std::vector<Type2Arc> next;
    for (const Type2Arc& beta : composed) {
      std::vector<Type2Arc> remainders;
      for (const Type2Arc& a : alpha) {
        next.push_back({target_union(a.targets, beta.targets), a.cpositions.intersect(beta.cpositions),
                        a.spositions.intersect(beta.spositions)});
        remainders.push_back({a.targets, a.cpositions.minus(beta.cpositions), a.spositions});
        remainders.push_back({a.targets, a.cpositions, a.spositions.minus(beta.spositions)});
      }
      next.push_back({beta.targets, beta.cpositions.minus(weak.cpositions), beta.spositions});
      next.push_back({beta.targets, beta.cpositions, beta.spositions.minus(weak.spositions)});
      alpha = merge_type2(remainders);
    }
    next.insert(next.end(), alpha.begin(), alpha.end());
    composed = merge_type2(next);
  }
  return composed;
}

}  // namespace cmt::planner
