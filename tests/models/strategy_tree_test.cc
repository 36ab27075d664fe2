// Conditional strategies in task files (docs/task-format.md "Conditional strategies", Buckley §4.2): the tree
// the loader builds (node numbering, links, branch tests) and every grammar rule's error.
#include <gtest/gtest.h>

#include "models/loaded_task.h"
#include "models/task_error.h"
#include "models/task_loader.h"
#include "tests/models/test_tasks.h"

namespace cmt {
namespace {

// The hole task with its strategies replaced by `strategies` (YAML text under the key).
std::string with_strategies(const std::string& strategies) {
  std::string yaml = test::kHoleYaml;
  const auto at = yaml.find("strategies:");
  return yaml.substr(0, at) + "strategies:\n" + strategies;
}

void expect_error(const std::string& strategies, const std::string& key, const std::string& reason) {
  try {
    load_task_from_string(with_strategies(strategies), "bad.yaml");
    ADD_FAILURE() << "no error; expected key '" << key << "' reason '" << reason << "'";
  } catch (const TaskError& e) {
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(e.reason().find(reason), std::string::npos) << "reason was: " << e.reason();
  }
}

TEST(StrategyTree, ASequenceIsAChainOfNodes) {
  auto task = load_task_from_string(test::kHoleYaml, "hole.yaml");
  const Strategy& s = *task->task.find_strategy("teach");
  EXPECT_FALSE(s.conditional());
  ASSERT_EQ(s.nodes.size(), 2u);
  EXPECT_EQ(s.nodes[0].motion, "p2");
  EXPECT_EQ(s.nodes[0].parent, -1);
  EXPECT_EQ(s.nodes[0].next, 1);
  EXPECT_EQ(s.nodes[1].motion, "p1");
  EXPECT_EQ(s.nodes[1].parent, 0);
  EXPECT_EQ(s.nodes[1].next, -1);
  EXPECT_TRUE(s.nodes[1].branches.empty());
  EXPECT_EQ(s.motions, (std::vector<std::string>{"p2", "p1"}));
}

TEST(StrategyTree, BranchesBecomeATreeInFileOrder) {
  auto task = load_task_from_string(with_strategies(R"(
  probe:
    - p2
    - branch:
        - when: {position: {box: {min: [-1, -1, -3], max: [1, 1, -1.5]}}}
          then: []
        - when:
            force: [{direction: [1, 0, 0], angle: 0.5}, {direction: [-1, 0, 0], angle: 0.5}]
            position: [{box: {min: [-2, -2, -3], max: [2, 2, 0]}}]
          then:
            - p1
            - branch:
                - when: {force: {direction: [0, 0, 1], angle: 0.3}}
                  then: [p2, p1]
                - else: []
        - else: [p1]
)"),
                                    "tree.yaml");
  const Strategy& s = *task->task.find_strategy("probe");
  EXPECT_TRUE(s.conditional());
  // Pre-order: 0 p2, 1 p1 (branch 1), 2 p2 (inner branch 0), 3 p1 (its next), 4 p1 (else).
  ASSERT_EQ(s.nodes.size(), 5u);
  const std::vector<std::string> motions = {"p2", "p1", "p2", "p1", "p1"};
  const std::vector<int> parent = {-1, 0, 1, 2, 0}, branch = {-1, 1, 0, -1, 2}, next = {-1, -1, 3, -1, -1};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(s.nodes[i].motion, motions[i]) << i;
    EXPECT_EQ(s.nodes[i].parent, parent[i]) << i;
    EXPECT_EQ(s.nodes[i].branch, branch[i]) << i;
    EXPECT_EQ(s.nodes[i].next, next[i]) << i;
  }
  EXPECT_EQ(s.motions, motions);
  const auto& top = s.nodes[0].branches;
  ASSERT_EQ(top.size(), 3u);
  EXPECT_EQ(top[0].first, -1);  // then: [] stops
  EXPECT_FALSE(top[0].otherwise);
  ASSERT_EQ(top[0].when.position.size(), 1u);
  EXPECT_EQ(top[0].when.position[0].min, Vec3(-1, -1, -3));
  EXPECT_TRUE(top[0].when.force.empty());
  EXPECT_EQ(top[1].first, 1);
  EXPECT_EQ(top[1].when.force.size(), 2u);
  EXPECT_EQ(top[1].when.position.size(), 1u);
  EXPECT_TRUE(top[2].otherwise);
  EXPECT_EQ(top[2].first, 4);
  EXPECT_EQ(top[1].key, "strategies.probe[1].branch[1]");
  const auto& inner = s.nodes[1].branches;
  ASSERT_EQ(inner.size(), 2u);
  EXPECT_EQ(inner[0].first, 2);
  EXPECT_EQ(inner[0].when.force[0].direction, Vec3(0, 0, 1));
  EXPECT_TRUE(inner[1].otherwise);
  EXPECT_EQ(inner[1].first, -1);
}

TEST(StrategyTree, EveryGrammarRuleHasAnError) {
  const std::string test = "{position: {box: {min: [-1, -1, -3], max: [1, 1, 0]}}}";
  expect_error("  s:\n    - branch: [{when: " + test + ", then: []}]\n", "strategies.s[0]",
               "put a motion before it");
  expect_error("  s:\n    - p1\n    - branch: [{when: " + test + ", then: [{branch: [{else: []}]}]}]\n",
               "strategies.s[1].branch[0].then[0]", "put a motion before it");
  expect_error("  s:\n    - p1\n    - branch: [{when: " + test + ", then: []}]\n    - p2\n",
               "strategies.s[2]", "nothing may follow a branch");
  expect_error("  s:\n    - p1\n    - branch: [{else: [p2]}, {when: " + test + ", then: []}]\n",
               "strategies.s[1].branch[1]", "the 'else' branch must be the last one");
  expect_error("  s:\n    - p1\n    - branch: [{else: [p2]}]\n", "strategies.s[1].branch[0]",
               "at least one 'when' test");
  expect_error("  s:\n    - p1\n    - branch: [{when: " + test + ", then: [], else: []}]\n",
               "strategies.s[1].branch[0]", "an 'else' branch has no 'when' or 'then'");
  expect_error("  s:\n    - p1\n    - branch: [{when: " + test + "}]\n", "strategies.s[1].branch[0].then",
               "missing required key");
  expect_error("  s:\n    - p1\n    - branch: [{then: [p2]}]\n", "strategies.s[1].branch[0]",
               "a branch is either");
  expect_error("  s:\n    - p1\n    - branch: [{when: " + test + ", then: [p3]}]\n",
               "strategies.s[1].branch[0].then[0]", "unknown motion 'p3'");
  expect_error("  s:\n    - p1\n    - branch: []\n", "strategies.s[1].branch", "the list is empty");
  expect_error("  s:\n    - p1\n    - branch: [{when: {}, then: []}]\n", "strategies.s[1].branch[0].when",
               "give position");
  expect_error("  s:\n    - p1\n    - branch: [{when: " + test + ", then: [], otherwise: []}]\n",
               "strategies.s[1].branch[0].otherwise", "unknown key");
  expect_error("  s:\n    - p1\n    - {branch: [{else: []}], fork: 1}\n", "strategies.s[1].fork",
               "unknown key");
  expect_error("  s:\n    - p1\n    - branch: [{when: " + test + ", then: p2}]\n",
               "strategies.s[1].branch[0].then", "expected a list");
}

}  // namespace
}  // namespace cmt
