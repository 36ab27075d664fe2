// Primitive-state enumeration (primitive_states.h, Buckley §6.4.1).
#include "verifier/planner/primitive_states.h"

namespace cmt::planner {
namespace {

// §6.4.1's recursion, unrolled: the primitive states of atoms [first, n) are those of [first + 1, n), then
// {first}, then {first} joined to each state of [first + 1, n) it is confusable with throughout. Built from
// the last atom backwards, each state is extended only while it stays primitive (and within max_atoms).
class Enumerator {
 public:
  Enumerator(const Confusability& confusable, int max_atoms, std::size_t max_states)
      : n_(confusable.atoms()), max_atoms_(max_atoms), max_states_(max_states), confusable_(confusable) {}

  PrimitiveStates run() {
    PrimitiveStates out;
    out.atoms = n_;
    for (int first = n_ - 1; first >= 0 && !out.truncated; --first) {
      const std::size_t previous = out.states.size();  // the states of [first + 1, n)
      add(out, {first});
      for (std::size_t i = 0; i < previous && !out.truncated; ++i) {
        const std::vector<int>& s = out.states[i];
        if (max_atoms_ > 0 && static_cast<int>(s.size()) >= max_atoms_) continue;
        if (!confusable_with_all(first, s)) continue;
        std::vector<int> joined = {first};
        joined.insert(joined.end(), s.begin(), s.end());
        add(out, std::move(joined));
      }
    }
    return out;
  }

 private:
  bool confusable_with_all(int atom, const std::vector<int>& state) const {
    for (int b : state)
      if (!confusable_(atom, b)) return false;
    return true;
  }

  void add(PrimitiveStates& out, std::vector<int> state) const {
    if (out.states.size() >= max_states_) {
      out.truncated = true;
      return;
    }
    if (out.by_size.size() <= state.size()) out.by_size.resize(state.size() + 1, 0);
    ++out.by_size[state.size()];
    out.states.push_back(std::move(state));
  }

  int n_;
  int max_atoms_;
  std::size_t max_states_;
  const Confusability& confusable_;
};

}  // namespace

PrimitiveStates primitive_states(const CSpace& cspace, double eps_s, double theta_f, int max_atoms,
                                 std::size_t max_states) {
  return primitive_states(Confusability(cspace, eps_s, theta_f), max_atoms, max_states);
}

PrimitiveStates primitive_states(const Confusability& confusable, int max_atoms, std::size_t max_states) {
  return Enumerator(confusable, max_atoms, max_states).run();
}

}  // namespace cmt::planner
