// cmt-fuzz's parts without cmt: the YAML tree round trip, the mutator's determinism, the answer checks and
// the minimizer.
#include <gtest/gtest.h>

#include <set>

#include "experiments/fuzz/minimizer.h"
#include "experiments/fuzz/mutator.h"
#include "experiments/fuzz/outcome.h"
#include "experiments/fuzz/yaml_tree.h"

namespace cmt::fuzz {
namespace {

const std::string kTasks = std::string(CMT_SOURCE_DIR) + "/models/tasks/";

TEST(YamlTree, WrittenDocumentParsesToTheSameTree) {
  const SeedTask seed = load_seed(kTasks + "two_blocks.yaml");
  const std::string written = to_document(seed.tree);
  EXPECT_EQ(to_document(parse_yaml(written)), written);
  EXPECT_EQ(seed.strategies, (std::vector<std::string>{"down", "slide", "tilt", "probe"}));
}

TEST(YamlTree, NumbersAndStringsStayApart) {
  const YamlValue v = parse_yaml("{a: 1e-320, b: \"1\", c: .inf, d: x1}");
  EXPECT_TRUE(is_number(v.items[0]));
  EXPECT_FALSE(is_number(v.items[1]));
  EXPECT_TRUE(is_number(v.items[2]));
  EXPECT_FALSE(is_number(v.items[3]));
  EXPECT_EQ(to_flow(v), "{a: 1e-320, b: \"1\", c: .inf, d: x1}");
}

TEST(Mutator, InputDependsOnlyOnSeedAndIndex) {
  const std::vector<SeedTask> seeds = {load_seed(kTasks + "two_blocks.yaml"),
                                       load_seed(kTasks + "hole.yaml")};
  for (uint64_t i : {0, 7, 123}) {
    const Mutant a = make_mutant(seeds, 5, i);
    make_mutant(seeds, 5, i + 1);  // another input in between changes nothing
    const Mutant b = make_mutant(seeds, 5, i);
    EXPECT_EQ(a.text, b.text);
    EXPECT_EQ(a.mutations, b.mutations);
    EXPECT_EQ(a.strategy, b.strategy);
    EXPECT_GE(a.mutations.size(), 1u);
    EXPECT_LE(a.mutations.size(), 4u);
  }
  EXPECT_NE(make_mutant(seeds, 5, 1).text, make_mutant(seeds, 6, 1).text);
}

TEST(Mutator, EveryMutationOccurs) {
  const std::vector<SeedTask> seeds = {load_seed(kTasks + "two_blocks.yaml"),
                                       load_seed(kTasks + "hole.yaml")};
  std::set<std::string> seen;
  for (uint64_t i = 0; i < 2000; ++i) {
    for (const auto& name : make_mutant(seeds, 1, i).mutations) seen.insert(name);
  }
  for (const auto& name : mutation_names()) EXPECT_TRUE(seen.count(name)) << name;
}

ChildResult exited(int code, const std::string& out) {
  ChildResult r;
  r.exited = true;
  r.exit_code = code;
  r.out = out;
  return r;
}

TEST(Outcome, FailuresAreSignalsStatusesBadJsonAndHangs) {
  EXPECT_FALSE(check_outcome(exited(0, "{\"atoms\": 3}\n")).failure);
  EXPECT_FALSE(check_outcome(exited(2, "{\"error\": {\"message\": \"bad\"}}")).failure);
  EXPECT_EQ(check_outcome(exited(2, "{\"error\": \"bad\"}")).kind, "no-error-message");
  EXPECT_EQ(check_outcome(exited(1, "{} {}")).kind, "bad-json");
  EXPECT_EQ(check_outcome(exited(0, "[1]")).kind, "bad-json");
  EXPECT_EQ(check_outcome(exited(0, "")).kind, "bad-json");
  EXPECT_EQ(check_outcome(exited(3, "{}")).kind, "exit-status");
  ChildResult crash;
  crash.signal = 11;
  EXPECT_EQ(check_outcome(crash).kind, "signal");
  ChildResult hang;
  hang.killed_on_time = true;
  EXPECT_EQ(check_outcome(hang).kind, "hang");
  const Outcome timed_out = check_outcome(exited(1, "{\"timed_out\": true, \"reliable\": false}"));
  EXPECT_FALSE(timed_out.failure);
  EXPECT_TRUE(timed_out.timed_out);
}

TEST(Outcome, ClassMasksDigitsAndTheInputPath) {
  Outcome o;
  o.kind = "signal";
  o.detail = "Aborted";
  EXPECT_EQ(failure_class(o, "loading /tmp/w/info-17.yaml\nwhat(): bad value 1.5\n", "/tmp/w/info-17.yaml"),
            "signal: Aborted | what(): bad value #.#");
}

TEST(Minimizer, KeepsOnlyWhatTheFailureNeeds) {
  const std::string text =
      "name: x\nbounds: {min: [0, 0, 0], max: [1, 1, 1]}\nmotions: {m: {damper: [1, 2, 3]}}\n";
  auto fails = [](const std::string& t) { return t.find("damper") != std::string::npos; };
  EXPECT_EQ(minimize_text(text, fails, {}), "motions: {m: {damper: []}}\n");
}

TEST(Minimizer, StopsAtItsBudget) {
  size_t calls = 0;
  auto fails = [&](const std::string&) { return ++calls, true; };
  minimize_text(std::string(5000, 'x'), fails, {10, 60});
  EXPECT_LE(calls, 10u);
}

}  // namespace
}  // namespace cmt::fuzz
