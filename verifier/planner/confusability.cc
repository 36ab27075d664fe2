// The pairwise confusability table (confusability.h).
#include "verifier/planner/confusability.h"

#include <optional>

#include "verifier/atom_cone.h"
#include "verifier/sensing.h"

namespace cmt::planner {

Confusability::Confusability(const CSpace& cspace, double eps_s, double theta_f) : n_(cspace.atom_count()) {
  confusable_.assign(static_cast<std::size_t>(n_) * n_, false);
  // Each atom's friction cone built once, when a pair first needs it (building one is the costly part).
  std::vector<std::optional<FrictionCone>> cones(static_cast<std::size_t>(n_));
  const auto cone = [&](int atom) -> const FrictionCone& {
    auto& c = cones[static_cast<std::size_t>(atom)];
    if (!c) c = atom_friction_cone(cspace, atom);
    return *c;
  };
  for (int a = 0; a < n_; ++a)
    for (int b = a + 1; b < n_; ++b)
      if (!disambiguable(cspace, a, b, eps_s, theta_f, cone)) {
        confusable_[index(a, b)] = true;
        confusable_[index(b, a)] = true;
      }
}

}  // namespace cmt::planner
