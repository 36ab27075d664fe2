// Primitive states of Buckley's planner (ch. 6, §6.4–6.4.1): a state is a set of atoms the robot may be in;
// it is primitive when no two of its atoms are disambiguable by position and force sensing (Def 6.1,
// verifier/sensing.h), so sensing cannot split it further. Table 6.3 counts them per environment.
#pragma once

#include <cstddef>
#include <vector>

#include "models/cspace.h"
#include "verifier/planner/confusability.h"

namespace cmt::planner {

struct PrimitiveStates {
  int atoms = 0;
  // Each state's atom ids, ascending; states in the order §6.4.1's recursion forms them (see the .cc).
  std::vector<std::vector<int>> states;
  // by_size[k]: the number of primitive states of k atoms (by_size[0] = 0).
  std::vector<long long> by_size;
  bool truncated = false;  // max_states was reached: `states` and `by_size` count only those found
};

// Buckley §6.4.1 over every atom of the C-space: S1 = {first atom}; the primitive states of the other atoms;
// and S1 added to each of those whose atoms are all confusable with it (adding one atom to a primitive state
// keeps it primitive exactly when the new atom is confusable with each of its atoms, so no non-primitive set
// is ever extended). States have at most `max_atoms` atoms (0: no limit); at most `max_states` are listed.
PrimitiveStates primitive_states(const CSpace& cspace, double eps_s, double theta_f, int max_atoms = 0,
                                 std::size_t max_states = 1'000'000);
// The same over a table already built.
PrimitiveStates primitive_states(const Confusability& confusable, int max_atoms = 0,
                                 std::size_t max_states = 1'000'000);

}  // namespace cmt::planner
