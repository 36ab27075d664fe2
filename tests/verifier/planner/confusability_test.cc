// The pairwise confusability table (verifier/planner/confusability.h) against Def 6.1 pair by pair.
#include "verifier/planner/confusability.h"

#include <gtest/gtest.h>

#include "models/loaded_task.h"
#include "verifier/sensing.h"

namespace cmt::planner {
namespace {

TEST(Confusability, EveryPairIsDef61sAnswerAndTheTableIsSymmetric) {
  const auto t = load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/cube.yaml");
  const CSpace& c = t->cspace;
  const double eps_s = 0.1, theta_f = 0.2;
  const Confusability table(c, eps_s, theta_f);
  ASSERT_EQ(table.atoms(), c.atom_count());
  int confusable_pairs = 0;
  for (int a = 0; a < c.atom_count(); ++a) {
    for (int b = a + 1; b < c.atom_count(); ++b) {
      EXPECT_EQ(table(a, b), confusable(c, a, b, eps_s, theta_f)) << c.atom_name(a) << " " << c.atom_name(b);
      EXPECT_EQ(table(a, b), table(b, a));
      confusable_pairs += table(a, b);
    }
  }
  EXPECT_GT(confusable_pairs, 0);
  EXPECT_LT(confusable_pairs, c.atom_count() * (c.atom_count() - 1) / 2);
}

}  // namespace
}  // namespace cmt::planner
