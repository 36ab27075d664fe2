// Which pairs of atoms sensing cannot tell apart (Buckley Def 6.1, §6.4.1): the table behind primitive states
// and an arc's heads. Immutable once built; every pair is decided once, each atom's friction cone built once.
#pragma once

#include <vector>

#include "models/cspace.h"

namespace cmt::planner {

class Confusability {
 public:
  // Every pair of the C-space's atoms under position error eps_s and force error theta_f.
  Confusability(const CSpace& cspace, double eps_s, double theta_f);

  int atoms() const { return n_; }
  // An atom is confusable with itself.
  bool operator()(int a, int b) const { return a == b || confusable_[index(a, b)]; }

 private:
  std::size_t index(int a, int b) const { return static_cast<std::size_t>(a) * n_ + b; }

  int n_ = 0;
  std::vector<bool> confusable_;
};

}  // namespace cmt::planner
