// Sweep specs (docs/sweeps.md): strict parsing with file/key/reason errors, override values checked by the
// task loader, the expansion into units (order, counts, stable keys), random draws and shards.
#include "experiments/sweep/spec/sweep_spec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "controllers/random.h"
#include "experiments/sweep/spec/stable_hash.h"
#include "experiments/sweep/spec/sweep_units.h"
#include "models/input_error.h"
#include "models/task_loader.h"
#include "tests/experiments/sweep_test_util.h"

namespace cmt {
namespace {

using test::source_task;

const std::string kTwoBlocks = source_task("two_blocks");
const std::string kCube = source_task("cube");

// The unit key's fields as they were before the falsify search existed (docs/sweeps.md "Unit key"), built by
// hand for two_blocks `down` at n 10, seed 1, uniform, impedance, no sticking trials, counterexample budget
// 400, no verifier budget.
HashInput down_unit_fields(const std::string& yaml) {
  HashInput in;
  in.add("cmt-sweep-unit/2")
      .add(yaml)
      .add("down")
      .add(10)
      .add("1")
      .add("uniform")
      .add("impedance")
      .add(0)
      .add(400)
      .add("0.0");
  return in;
}

// A spec with two_blocks (strategies down, slide) and the given extra lines under the task entry.
std::string two_blocks_spec(const std::string& task_extra, const std::string& top = "n: 10\nseeds: [1]\n") {
  return top + "tasks:\n  - file: " + kTwoBlocks + "\n    strategies: [down, slide]\n" + task_extra;
}

SweepSpec parse(const std::string& text) { return parse_sweep_spec(text, "spec.yaml", "/"); }

// Parsing must fail with this key and a reason containing `reason_part`.
void expect_error(const std::string& text, const std::string& key, const std::string& reason_part) {
  try {
    const SweepSpec spec = parse(text);
    expand_units(spec);
    ADD_FAILURE() << "no error for key " << key << " in:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "spec.yaml") << e.what();
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(e.reason().find(reason_part), std::string::npos) << e.what();
  }
}

TEST(SweepSpec, StructuralErrorsNameFileKeyAndReason) {
  expect_error("n: 10\nseeds: [1]\nseed: 3\ntasks: []\n", "seed", "unknown key");
  expect_error("seeds: [1]\ntasks:\n  - file: " + kTwoBlocks + "\n    strategies: [down]\n", "n",
               "missing required key");
  expect_error(two_blocks_spec("", "n: 0\nseeds: [1]\n"), "n", "must be in [1, 10000000]");
  expect_error(two_blocks_spec("", "n: 2.5\nseeds: [1]\n"), "n", "expected an integer");
  expect_error(two_blocks_spec("", "n: 10\nseeds: []\n"), "seeds", "the list is empty");
  expect_error(two_blocks_spec("", "n: 10\nseeds: [1, -4]\n"), "seeds[1]", "must be in [0, ");
  expect_error(two_blocks_spec("", "n: 10\nseeds: [3, 3]\n"), "seeds[1]", "duplicated seed 3");
  expect_error(two_blocks_spec("", "n: 10\nseeds: [1]\nmode: random\n"), "mode", "uniform or extreme");
  expect_error(two_blocks_spec("", "n: 10\nseeds: [1]\ncontroller: pid\n"), "controller",
               "must be impedance, admittance or position, got 'pid'");
  // two_blocks' strategies are dampers: the position form (springs only) is refused before anything runs.
  expect_error(two_blocks_spec("", "n: 10\nseeds: [1]\ncontroller: position\n"), "tasks[0].strategies[0]",
               "the damper motion 'v1'");
  expect_error(two_blocks_spec("", "n: 10\nseeds: [1]\nsticking_trials: -1\n"), "sticking_trials",
               "must be in [0, ");
  expect_error("n: 10\nseeds: [1]\ntasks: [\n", "tasks", "malformed YAML");
  expect_error("n: 10\nseeds: [1]\ntasks:\n  - file: no_such_task.yaml\n    strategies: [down]\n",
               "tasks[0].file", "cannot open the task file '/no_such_task.yaml'");
  expect_error("n: 10\nseeds: [1]\ntasks:\n  - file: " + kTwoBlocks + "\n    stratgies: [down]\n",
               "tasks[0].stratgies", "unknown key");
  expect_error("n: 10\nseeds: [1]\ntasks:\n  - file: " + kTwoBlocks + "\n    strategies: [down, teach]\n",
               "tasks[0].strategies[1]", "unknown strategy 'teach' (the task has: down, slide, tilt, probe)");
  expect_error(two_blocks_spec("    grid:\n      mu: [0.2]\n"), "tasks[0].grid.mu", "unknown key");
  expect_error(two_blocks_spec("    grid:\n      friction: []\n"), "tasks[0].grid.friction",
               "the list is empty");
  expect_error(two_blocks_spec("    grid:\n      friction: [0.2, high]\n"), "tasks[0].grid.friction[1]",
               "expected a number, got 'high'");
}

TEST(SweepSpec, OverridesThatBreakTheTaskNameTheSpecKey) {
  // theta_v must be < pi/2 (task loader): the second grid value is the culprit.
  expect_error(two_blocks_spec("    grid:\n      theta_v: [0.2, 1.6]\n"), "tasks[0].grid.theta_v[1]",
               "the value 1.6 makes the task invalid: uncertainty.theta_v: must be < pi/2");
  expect_error(two_blocks_spec("    grid:\n      friction: [0.25, -0.1]\n"), "tasks[0].grid.friction[1]",
               "friction: friction coefficient must be >= 0");
  expect_error(two_blocks_spec("    grid:\n      step: [0]\n"), "tasks[0].grid.step[0]",
               "uncertainty.step: the spring interpolation step must be > 0");
  expect_error(two_blocks_spec("    grid:\n      motions:\n        v1: [[0, 0, 0]]\n"),
               "tasks[0].grid.motions.v1[0]", "the commanded velocity direction is the zero vector");
  expect_error(two_blocks_spec("    grid:\n      motions:\n        v1: [[0, -1]]\n"),
               "tasks[0].grid.motions.v1[0]", "expected 3 numbers, got 2");
  expect_error(two_blocks_spec("    grid:\n      motions:\n        v9: [[0, 0, -1]]\n"),
               "tasks[0].grid.motions.v9", "the task has no motion 'v9' (it has: v1, v2, v3)");
  // Random ranges: both ends must be valid.
  expect_error(two_blocks_spec(
                   "    random:\n      count: 3\n      seed: 1\n      ranges:\n        theta_v: [0.1, 2]\n"),
               "tasks[0].random.ranges.theta_v", "the value 2.0 makes the task invalid: uncertainty.theta_v");
  expect_error(
      two_blocks_spec(
          "    random:\n      count: 3\n      seed: 1\n      ranges:\n        friction: [0.4, 0.1]\n"),
      "tasks[0].random.ranges.friction", "the low end exceeds the high end");
  expect_error(
      two_blocks_spec(
          "    random:\n      count: 0\n      seed: 1\n      ranges:\n        friction: [0.1, 0.4]\n"),
      "tasks[0].random.count", "must be in [1, ");
  expect_error(
      two_blocks_spec("    grid:\n      friction: [0.2]\n    random:\n      count: 2\n      seed: 1\n"
                      "      ranges:\n        friction: [0.1, 0.4]\n"),
      "tasks[0].random.ranges.friction", "also in the grid");
}

TEST(SweepSpec, ControllerFormIsAUnitField) {
  const auto impedance = expand_units(parse(two_blocks_spec("")));
  const auto admittance =
      expand_units(parse(two_blocks_spec("", "n: 10\nseeds: [1]\ncontroller: admittance\n")));
  ASSERT_EQ(impedance.size(), 2u);
  ASSERT_EQ(admittance.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(impedance[i].controller, ControllerForm::kImpedance);
    EXPECT_EQ(admittance[i].controller, ControllerForm::kAdmittance);
    EXPECT_EQ(admittance[i].task_yaml, impedance[i].task_yaml);  // the widening is the verifier's business
    EXPECT_NE(admittance[i].unit_key, impedance[i].unit_key);    // different physics: different results
  }
}

TEST(SweepSpec, ATaskEntryMayOverrideTheRolloutCount) {
  // The spec's n (10) is every entry's default; an entry's own n replaces it for that entry's units only,
  // and the count is part of the unit key (another count is another result).
  const std::string spec = "n: 10\nseeds: [1]\ntasks:\n  - file: " + kTwoBlocks +
                           "\n    strategies: [down]\n    n: 3\n  - file: " + kTwoBlocks +
                           "\n    strategies: [slide]\n";
  const auto units = expand_units(parse(spec));
  ASSERT_EQ(units.size(), 2u);
  EXPECT_EQ(units[0].strategy, "down");
  EXPECT_EQ(units[0].n, 3);
  EXPECT_EQ(units[1].strategy, "slide");
  EXPECT_EQ(units[1].n, 10);
  const auto plain = expand_units(parse(two_blocks_spec("")));
  ASSERT_EQ(plain[0].strategy, "down");
  EXPECT_NE(plain[0].unit_key, units[0].unit_key);
  expect_error(two_blocks_spec("    n: 0\n"), "tasks[0].n", "must be in [1, 10000000]");
  expect_error(two_blocks_spec("    n: many\n"), "tasks[0].n", "expected an integer");
}

TEST(SweepSpec, GridExpandsInDocumentedOrder) {
  const SweepSpec spec =
      parse(two_blocks_spec("    grid:\n      friction: [0.2, 0.3]\n      theta_v: [0.1, 0.2, 0.24]\n",
                            "n: 25\nseeds: [1, 2]\nmode: extreme\nsticking_trials: 5\n"));
  const std::vector<SweepUnit> units = expand_units(spec);
  // 2 frictions x 3 angles x 2 strategies x 2 seeds; seeds innermost, then strategies, then the last grid
  // key.
  ASSERT_EQ(units.size(), 24u);
  EXPECT_EQ(units[0].params, nlohmann::json({{"friction", 0.2}, {"theta_v", 0.1}}));
  EXPECT_EQ(units[0].strategy, "down");
  EXPECT_EQ(units[0].seed, 1u);
  EXPECT_EQ(units[1].seed, 2u);
  EXPECT_EQ(units[2].strategy, "slide");
  EXPECT_EQ(units[4].params, nlohmann::json({{"friction", 0.2}, {"theta_v", 0.2}}));
  EXPECT_EQ(units[12].params, nlohmann::json({{"friction", 0.3}, {"theta_v", 0.1}}));
  EXPECT_EQ(units[23].params, nlohmann::json({{"friction", 0.3}, {"theta_v", 0.24}}));
  std::set<std::string> keys;
  for (std::size_t i = 0; i < units.size(); ++i) {
    EXPECT_EQ(units[i].index, static_cast<int>(i));
    EXPECT_EQ(units[i].task, "two_blocks");
    EXPECT_EQ(units[i].n, 25);
    EXPECT_EQ(units[i].mode, SampleMode::kExtreme);
    EXPECT_EQ(units[i].controller, ControllerForm::kImpedance);  // the default
    EXPECT_EQ(units[i].sticking_trials, 5);
    EXPECT_EQ(units[i].unit_key.size(), 32u);
    keys.insert(units[i].unit_key);
  }
  EXPECT_EQ(keys.size(), 24u);
  // The overridden text is a valid task carrying the values; everything else is untouched.
  const Task t = parse_task_string(units[23].task_yaml, "unit 23");
  EXPECT_EQ(t.friction, 0.3);
  EXPECT_EQ(t.uncertainty.theta_v, 0.24);
  EXPECT_EQ(t.uncertainty.eps_s, 0.2);
  EXPECT_EQ(t.uncertainty.theta_f, 0.3);
  EXPECT_EQ(t.motions.size(), 3u);  // two_blocks: v1, v2, v3
  // Same spec, same keys: a rerun recognises its units.
  const std::vector<SweepUnit> again = expand_units(spec);
  for (std::size_t i = 0; i < units.size(); ++i) EXPECT_EQ(again[i].unit_key, units[i].unit_key);
}

TEST(SweepSpec, MotionOverridesKeepTheMotionKind) {
  const SweepSpec spec =
      parse("n: 5\nseeds: [1]\ntasks:\n  - file: " + kCube +
            "\n    strategies: [stick]\n    grid:\n      motions:\n        p1: [[0, 0, -2.5], "
            "[0.25, 0, -3]]\n  - file: " +
            kTwoBlocks + "\n    strategies: [slide]\n    grid:\n      motions:\n        v2: [[-1, 0, -2]]\n");
  const std::vector<SweepUnit> units = expand_units(spec);
  ASSERT_EQ(units.size(), 3u);
  EXPECT_EQ(units[0].params, nlohmann::json({{"motions.p1", {0, 0, -2.5}}}));
  const Task cube = parse_task_string(units[1].task_yaml, "cube");
  ASSERT_EQ(cube.motions.size(), 1u);
  EXPECT_EQ(cube.motions[0].kind, Motion::Kind::kSpring);
  EXPECT_EQ(cube.motions[0].target, Vec3(0.25, 0, -3));  // a spring's commanded position, as given
  const Task blocks = parse_task_string(units[2].task_yaml, "two_blocks");
  const Motion* v2 = blocks.find_motion("v2");
  ASSERT_NE(v2, nullptr);
  EXPECT_EQ(v2->kind, Motion::Kind::kDamper);
  EXPECT_NEAR((v2->target - Vec3(-1, 0, -2) / std::sqrt(5.0)).norm(), 0, 1e-15);  // normalized on load
  EXPECT_EQ(blocks.find_motion("v1")->target, Vec3(0, 0, -1));                    // untouched
}

TEST(SweepSpec, RandomDrawsComeFromTheSeed) {
  auto draws = [&](int seed) {
    std::string random = "    random:\n      count: 4\n      seed: ";
    random += std::to_string(seed);
    random +=
        "\n      ranges:\n        friction: [0.1, 0.4]\n        motions:\n"
        "          v2: {min: [-1, 0, -1], max: [-0.5, 0, -0.5]}\n";
    return expand_units(parse(two_blocks_spec(random)));
  };
  const std::vector<SweepUnit> a = draws(3), b = draws(3), c = draws(4);
  ASSERT_EQ(a.size(), 8u);  // 4 draws x 2 strategies
  for (int j = 0; j < 4; ++j) {
    // Draw j reads its own stream (seed, j): friction first, then the motion's components in order; a
    // component whose range is a single value is that value.
    Rng rng = rollout_stream(3, j);
    const double friction = uniform(rng, 0.1, 0.4);
    const double vx = uniform(rng, -1, -0.5);
    const double vz = uniform(rng, -1, -0.5);
    const nlohmann::json& p = a[2 * j].params;
    EXPECT_EQ(p["friction"].get<double>(), friction);
    EXPECT_EQ(p["motions.v2"], nlohmann::json({vx, 0.0, vz}));
    EXPECT_GE(friction, 0.1);
    EXPECT_LT(friction, 0.4);
    EXPECT_EQ(a[2 * j + 1].params, p);  // both strategies see the same draw
    EXPECT_EQ(b[2 * j].unit_key, a[2 * j].unit_key);
    EXPECT_NE(c[2 * j].params, p);
    // The task text holds the drawn value exactly.
    EXPECT_EQ(parse_task_string(a[2 * j].task_yaml, "draw").friction, friction);
  }
}

TEST(SweepSpec, RepeatedValuesRunOnce) {
  int duplicates = -1;
  const auto units =
      expand_units(parse(two_blocks_spec("    grid:\n      friction: [0.25, 0.3, 0.25]\n")), &duplicates);
  EXPECT_EQ(units.size(), 4u);  // (0.25, 0.3) x (down, slide)
  EXPECT_EQ(duplicates, 2);
  EXPECT_EQ(units[3].index, 3);
}

TEST(SweepSpec, UnitKeyIgnoresCommentsButNotValues) {
  const auto dir = test::fresh_dir("spec-key");
  std::ifstream in(kTwoBlocks);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  test::write_file(dir / "commented.yaml", "# another comment\n" + text + "\n# trailing comment\n");
  const std::string spec_text =
      "n: 10\nseeds: [1]\ntasks:\n  - file: commented.yaml\n    strategies: [down]\n"
      "  - file: " +
      kTwoBlocks + "\n    strategies: [down]\n";
  int duplicates = 0;
  const auto units = expand_units(parse_sweep_spec(spec_text, "spec.yaml", dir), &duplicates);
  EXPECT_EQ(units.size(), 1u);  // the same task text: one unit
  EXPECT_EQ(duplicates, 1);
  const std::string key = units[0].unit_key;
  const std::string yaml = units[0].task_yaml;
  constexpr auto kImp = ControllerForm::kImpedance;  // the spec's default
  EXPECT_NE(make_unit_key(yaml, "down", 10, 2, SampleMode::kUniform, kImp, 0, 400), key);
  EXPECT_NE(make_unit_key(yaml, "down", 11, 1, SampleMode::kUniform, kImp, 0, 400), key);
  EXPECT_NE(make_unit_key(yaml, "down", 10, 1, SampleMode::kExtreme, kImp, 0, 400), key);
  EXPECT_NE(make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, ControllerForm::kAdmittance, 0, 400),
            key);
  EXPECT_NE(make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 1, 400), key);
  EXPECT_NE(make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 0, 399), key);
  EXPECT_NE(make_unit_key(yaml, "slide", 10, 1, SampleMode::kUniform, kImp, 0, 400), key);
  EXPECT_EQ(make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 0, 400), key);
  std::filesystem::remove_all(dir);
}

TEST(SweepSpec, FalsifyBudgetsAreUnitFieldsWithPerEntryOverrides) {
  // The spec's budgets are every entry's default; an entry's own `falsify` replaces them (0, 0: no search).
  const std::string spec =
      "n: 10\nseeds: [1]\nfalsify: {budget: 200, coverage_budget: 100}\ntasks:\n"
      "  - file: " +
      kTwoBlocks + "\n    strategies: [down]\n  - file: " + kTwoBlocks +
      "\n    strategies: [slide]\n    falsify: {budget: 0, coverage_budget: 0}\n  - file: " + kCube +
      "\n    strategies: [stick]\n    falsify:\n      budget: 16\n"
      "      coverage_budget: 0\n";
  const SweepSpec parsed = parse(spec);
  EXPECT_EQ(parsed.falsify.budget, 200);
  EXPECT_EQ(parsed.falsify.coverage_budget, 100);
  const auto units = expand_units(parsed);
  ASSERT_EQ(units.size(), 3u);
  EXPECT_EQ(units[0].falsify_budget, 200);
  EXPECT_EQ(units[0].falsify_coverage_budget, 100);
  EXPECT_EQ(units[1].falsify_budget, 0);
  EXPECT_EQ(units[1].falsify_coverage_budget, 0);
  EXPECT_EQ(units[2].falsify_budget, 16);
  EXPECT_EQ(units[2].falsify_coverage_budget, 0);
  // Without the key: no search.
  const auto plain = expand_units(parse(two_blocks_spec("")));
  ASSERT_EQ(plain.size(), 2u);
  EXPECT_EQ(plain[0].falsify_budget + plain[0].falsify_coverage_budget, 0);
  // A search is another result: another key; switched off per entry, the key is the plain one.
  EXPECT_NE(units[0].unit_key, plain[0].unit_key);
  EXPECT_EQ(units[1].unit_key, plain[1].unit_key);
  // Either budget alone changes the key.
  const std::string yaml = plain[0].task_yaml;
  constexpr auto kImp = ControllerForm::kImpedance;
  const std::string base = make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 0, 400, 0);
  EXPECT_NE(make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 0, 400, 0, 1, 0), base);
  EXPECT_NE(make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 0, 400, 0, 0, 1), base);
  EXPECT_NE(make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 0, 400, 0, 1, 0),
            make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 0, 400, 0, 0, 1));
  // The gap budget alone changes the key; a search without one keeps the key it had before the gap budget
  // existed: its fields built by hand (docs/sweeps.md "Unit key").
  const std::string searched = fnv1a128_hex(down_unit_fields(yaml).add("falsify").add(1).add(0).text());
  EXPECT_EQ(make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 0, 400, 0, 1, 0, 0), searched);
  EXPECT_NE(make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 0, 400, 0, 1, 0, 5), searched);
  EXPECT_NE(make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 0, 400, 0, 0, 0, 5), base);
  // So does the failure budget; a search without one keeps its key.
  EXPECT_EQ(make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 0, 400, 0, 1, 0, 0, 0), searched);
  EXPECT_NE(make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 0, 400, 0, 1, 0, 0, 7), searched);
  EXPECT_NE(make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 0, 400, 0, 0, 0, 0, 7), base);
  EXPECT_NE(make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 0, 400, 0, 0, 0, 7, 0),
            make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, kImp, 0, 400, 0, 0, 0, 0, 7));
}

TEST(SweepSpec, FalsifyGapBudgetIsOptional) {
  const std::string spec =
      "n: 10\nseeds: [1]\nfalsify: {budget: 20, coverage_budget: 10, gap_budget: 30}\ntasks:\n"
      "  - file: " +
      kTwoBlocks + "\n    strategies: [down]\n  - file: " + kTwoBlocks +
      "\n    strategies: [slide]\n    falsify: {budget: 20, coverage_budget: 10}\n";
  const SweepSpec parsed = parse(spec);
  EXPECT_EQ(parsed.falsify.gap_budget, 30);
  const auto units = expand_units(parsed);
  ASSERT_EQ(units.size(), 2u);
  EXPECT_EQ(units[0].falsify_gap_budget, 30);
  EXPECT_EQ(units[1].falsify_gap_budget, 0);  // an entry's own falsify without it: no gap search
  const std::string top = "n: 10\nseeds: [1]\n";
  expect_error(two_blocks_spec("", top + "falsify: {budget: 1, coverage_budget: 0, gap_budget: -2}\n"),
               "falsify.gap_budget", "must be in [0, 10000000]");
}

TEST(SweepSpec, FalsifyFailureBudgetIsOptional) {
  const std::string spec =
      "n: 10\nseeds: [1]\nfalsify: {budget: 0, coverage_budget: 0, failure_budget: 40}\ntasks:\n"
      "  - file: " +
      kTwoBlocks + "\n    strategies: [down]\n  - file: " + kTwoBlocks +
      "\n    strategies: [slide]\n    falsify: {budget: 20, coverage_budget: 10}\n";
  const SweepSpec parsed = parse(spec);
  EXPECT_EQ(parsed.falsify.failure_budget, 40);
  EXPECT_TRUE(parsed.falsify.enabled());  // the failure search alone is a search
  const auto units = expand_units(parsed);
  ASSERT_EQ(units.size(), 2u);
  EXPECT_EQ(units[0].falsify_failure_budget, 40);
  EXPECT_EQ(units[1].falsify_failure_budget, 0);  // an entry's own falsify without it: no failure search
  const std::string top = "n: 10\nseeds: [1]\n";
  expect_error(two_blocks_spec("", top + "falsify: {budget: 1, coverage_budget: 0, failure_budget: -1}\n"),
               "falsify.failure_budget", "must be in [0, 10000000]");
}

TEST(SweepSpec, FalsifyErrorsNameFileKeyAndReason) {
  const std::string top = "n: 10\nseeds: [1]\n";
  expect_error(two_blocks_spec("", top + "falsify: {budget: -1, coverage_budget: 0}\n"), "falsify.budget",
               "must be in [0, 10000000]");
  expect_error(two_blocks_spec("", top + "falsify: {budget: 10, coverage_budget: 1.5}\n"),
               "falsify.coverage_budget", "expected an integer");
  expect_error(two_blocks_spec("", top + "falsify: {budget: 10, coverage_budget: 20000000}\n"),
               "falsify.coverage_budget", "must be in [0, 10000000]");
  expect_error(two_blocks_spec("", top + "falsify: {budget: 10, coverage_budget: 5, random: 3}\n"),
               "falsify.random", "unknown key");
  expect_error(two_blocks_spec("", top + "falsify: {budget: 10}\n"), "falsify.coverage_budget",
               "missing required key");
  expect_error(two_blocks_spec("", top + "falsify: 200\n"), "falsify", "expected a mapping");
  expect_error(two_blocks_spec("    falsify: {budget: ten, coverage_budget: 0}\n"), "tasks[0].falsify.budget",
               "expected an integer, got 'ten'");
  expect_error(two_blocks_spec("    falsify: {budjet: 1, coverage_budget: 0}\n"), "tasks[0].falsify.budjet",
               "unknown key");
}

// Databases written before the falsify search existed must resume: a unit without a search keeps its key.
TEST(SweepSpec, UnitKeyWithoutFalsifyIsTheOneBeforeTheSearchExisted) {
  const auto units = expand_units(parse(two_blocks_spec("")));
  ASSERT_EQ(units[0].strategy, "down");
  // `cmt sweep --list` of this unit by the program built before the falsify keys were added.
  EXPECT_EQ(units[0].unit_key, "57cb2f78eef15965852ab58bf069ade8");
  // The key's fields as they were (docs/sweeps.md "Unit key"), built by hand.
  const std::string yaml = units[0].task_yaml;
  const std::string before = fnv1a128_hex(down_unit_fields(yaml).text());
  EXPECT_EQ(units[0].unit_key, before);
  EXPECT_EQ(
      make_unit_key(yaml, "down", 10, 1, SampleMode::kUniform, ControllerForm::kImpedance, 0, 400, 0, 0, 0),
      before);
}

TEST(StableHash, Fnv1a128TestVectors) {
  // The offset basis is the hash of the empty string; "a" and "foobar" are from the FNV reference test
  // vectors (IETF draft-eastlake-fnv, FNV-1a 128-bit).
  EXPECT_EQ(fnv1a128_hex(""), "6c62272e07bb014262b821756295c58d");
  EXPECT_EQ(fnv1a128_hex("a"), "d228cb696f1a8caf78912b704e4a8964");
  EXPECT_EQ(fnv1a128_hex("foobar"), "343e1662793c64bf6f0d3597ba446f18");
}

TEST(StableHash, FieldsAreUnambiguous) {
  EXPECT_EQ(HashInput().add("ab").add("c").text(), "2:ab\n1:c\n");
  EXPECT_NE(HashInput().add("ab").add("c").text(), HashInput().add("a").add("bc").text());
  EXPECT_EQ(HashInput().add(-12).text(), "3:-12\n");
}

TEST(Shard, ParsesAndPartitions) {
  const Shard s = parse_shard("1/3");
  EXPECT_EQ(s.index, 1);
  EXPECT_EQ(s.count, 3);
  for (const std::string bad : {"3/3", "0/0", "a/b", "-1/2", "1", "1/2/3", ""}) {
    try {
      parse_shard(bad);
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "--shard") << bad;
    }
  }
  // Every index in exactly one of the 3 shards: 0 3 6 9 | 1 4 7 | 2 5 8.
  std::vector<int> owner(10, -1);
  for (int shard = 0; shard < 3; ++shard)
    for (int i = 0; i < 10; ++i)
      if (Shard{shard, 3}.contains(i)) {
        EXPECT_EQ(owner[i], -1);
        owner[i] = shard;
      }
  EXPECT_EQ(owner, (std::vector<int>{0, 1, 2, 0, 1, 2, 0, 1, 2, 0}));
}

}  // namespace
}  // namespace cmt
