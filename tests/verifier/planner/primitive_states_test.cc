// Primitive states (verifier/planner/primitive_states.h) against Buckley's Table 6.3 cube row, and the
// properties that make the enumeration right: every state primitive, every confusable pair a state, no
// repeats.
#include "verifier/planner/primitive_states.h"

#include <gtest/gtest.h>

#include <set>

#include "models/loaded_task.h"
#include "tests/models/test_tasks.h"
#include "verifier/sensing.h"

namespace cmt::planner {
namespace {

constexpr double kEpsS = 0.2, kThetaF = 0.3;  // Table 6.3's sensing errors (the cube task's too)

const CSpace& cube() {
  static const auto t = load_task_from_string(test::kCubeYaml, "cube.yaml");
  return t->cspace;
}

// Buckley Table 6.3, cube (1 in clearance, mu = .25, eps_s = .2 in, theta_f = .3 rad): 26 atoms, 258
// primitive states, 226 with at most 3 atoms, 122 with at most 2.
TEST(PrimitiveStates, CubeReproducesTable63) {
  const PrimitiveStates all = primitive_states(cube(), kEpsS, kThetaF);
  EXPECT_EQ(all.atoms, 26);
  EXPECT_FALSE(all.truncated);
  EXPECT_EQ(all.states.size(), 258u);
  ASSERT_GE(all.by_size.size(), 4u);
  EXPECT_EQ(all.by_size[1], 26);
  EXPECT_EQ(all.by_size[1] + all.by_size[2], 122);
  EXPECT_EQ(all.by_size[1] + all.by_size[2] + all.by_size[3], 226);
  EXPECT_EQ(primitive_states(cube(), kEpsS, kThetaF, 3).states.size(), 226u);
  EXPECT_EQ(primitive_states(cube(), kEpsS, kThetaF, 2).states.size(), 122u);
}

TEST(PrimitiveStates, EveryStateIsPrimitiveEveryConfusablePairIsAStateAndNoneRepeats) {
  const CSpace& c = cube();
  const PrimitiveStates all = primitive_states(c, kEpsS, kThetaF);
  std::set<std::vector<int>> seen;
  for (const std::vector<int>& s : all.states) {
    EXPECT_TRUE(std::is_sorted(s.begin(), s.end()));
    EXPECT_TRUE(seen.insert(s).second) << "repeated state";
    for (std::size_t i = 0; i < s.size(); ++i)
      for (std::size_t j = i + 1; j < s.size(); ++j) EXPECT_TRUE(confusable(c, s[i], s[j], kEpsS, kThetaF));
  }
  long long pairs = 0;
  for (int a = 0; a < c.atom_count(); ++a)
    for (int b = a + 1; b < c.atom_count(); ++b)
      if (confusable(c, a, b, kEpsS, kThetaF)) {
        ++pairs;
        EXPECT_TRUE(seen.count({a, b})) << c.atom_name(a) << " " << c.atom_name(b);
      }
  EXPECT_EQ(all.by_size[2], pairs);
  // A maximal state cannot take another atom: each state of the largest size is confusable with no other
  // atom.
  const std::size_t largest = all.by_size.size() - 1;
  for (const std::vector<int>& s : all.states) {
    if (s.size() != largest) continue;
    for (int a = 0; a < c.atom_count(); ++a) {
      if (std::find(s.begin(), s.end(), a) != s.end()) continue;
      bool all_confusable = true;
      for (int b : s) all_confusable = all_confusable && confusable(c, a, b, kEpsS, kThetaF);
      EXPECT_FALSE(all_confusable);
    }
  }
}

TEST(PrimitiveStates, PerfectSensingLeavesOnlyAtomsThatShareAFace) {
  // With eps_s = theta_f = 0 two atoms are confusable only where they touch and their cones meet: still
  // every single atom, and far fewer pairs than with Table 6.3's errors.
  const PrimitiveStates perfect = primitive_states(cube(), 0, 0);
  const PrimitiveStates table = primitive_states(cube(), kEpsS, kThetaF);
  EXPECT_EQ(perfect.by_size[1], 26);
  EXPECT_LE(perfect.states.size(), table.states.size());
}

TEST(PrimitiveStates, MaxStatesTruncates) {
  const PrimitiveStates some = primitive_states(cube(), kEpsS, kThetaF, 0, 40);
  EXPECT_TRUE(some.truncated);
  EXPECT_EQ(some.states.size(), 40u);
}

}  // namespace
}  // namespace cmt::planner
