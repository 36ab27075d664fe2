// Taught strategies as trees (verifier/teaching/taught_strategy.h): the trees the teaching loop builds are
// the ones the task loader reads from the same strategy written in the task format.
#include "verifier/teaching/taught_strategy.h"

#include <gtest/gtest.h>

#include "models/task_loader.h"

namespace cmt::teaching {
namespace {

constexpr const char* kTask = R"(
name: trees
units: in
friction: 0.3
uncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.1, theta_f: 0.1}
cspace:
  - box: {min: [-1, -1, -1], max: [1, 1, 0]}
bounds: {min: [-2, -2, -1], max: [2, 2, 2]}
start: {point: [0, 0, 0]}
goal: {point: [0, 0, 0]}
motions:
  a: {damper: [0, 0, -1]}
  b: {damper: [1, 0, -1]}
  c: {damper: [-1, 0, -1]}
strategies:
  tree:
    - a
    - b
    - branch:
        - when: {position: {box: {min: [-1, -1, -1], max: [0, 1, 1]}}}
          then: [c, a]
        - else: []
  inner:
    - b
    - branch:
        - when: {position: {box: {min: [-1, -1, -1], max: [0, 1, 1]}}}
          then: [c, a]
        - else: []
)";

MotionTermination left_box() {
  MotionTermination t;
  t.position.push_back({Vec3(-1, -1, -1), Vec3(0, 1, 1)});
  return t;
}

TEST(TaughtStrategy, TreesMatchTheLoadersReadingOfTheSameStrategy) {
  const Task task = parse_task_string(kTask, "trees");
  const Strategy inner = dispatch("b", {{left_box(), chain_strategy({"c", "a"})}, {{}, Strategy{}}});
  const Strategy tree = followed_by("a", inner);
  EXPECT_TRUE(same_strategy(tree, *task.find_strategy("tree")));
  EXPECT_TRUE(same_strategy(inner, *task.find_strategy("inner")));
  EXPECT_TRUE(same_strategy(subtree(tree, 1), inner));
  EXPECT_FALSE(same_strategy(tree, inner));
  EXPECT_TRUE(tree.conditional());
  EXPECT_EQ(tree.motions, (std::vector<std::string>{"a", "b", "c", "a"}));
  EXPECT_EQ(strategy_text(tree), "a, b, branch {when position in 1 box: [c, a]; else: []}");

  MotionTermination wider = left_box();
  wider.position[0].max.x() = 0.5;
  EXPECT_FALSE(same_strategy(inner, dispatch("b", {{wider, chain_strategy({"c", "a"})}, {{}, Strategy{}}})));
  EXPECT_THROW(dispatch("b", {{left_box(), Strategy{}}}), std::invalid_argument);
}

TEST(TaughtStrategy, ChainsStayDecisionFree) {
  const Strategy chain = followed_by("a", chain_strategy({"b", "c"}));
  EXPECT_FALSE(chain.conditional());
  EXPECT_TRUE(same_strategy(chain, Strategy::sequence("x", {"a", "b", "c"})));
  EXPECT_TRUE(same_strategy(followed_by("a", Strategy{}), chain_strategy({"a"})));
  EXPECT_TRUE(same_strategy(subtree(chain, 1), chain_strategy({"b", "c"})));
  EXPECT_TRUE(subtree(chain, -1).nodes.empty());
  EXPECT_EQ(strategy_text(chain), "a, b, c");
}

}  // namespace
}  // namespace cmt::teaching
