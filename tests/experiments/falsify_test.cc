// Adversarial rollouts (experiments/falsify/): the cross-entropy method on known functions, and the search
// against a deliberately shrunk prediction, where it must find ends outside that random sampling at the same
// budget mostly misses (docs/falsify.md "Checking the search").
#include "experiments/falsify/falsify.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "experiments/falsify/robustness.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

std::string builtin_path(const std::string& name) {
  return (std::filesystem::path(CMT_SOURCE_DIR) / "models" / "tasks" / (name + ".yaml")).string();
}

// -|x - target|^2 over a batch.
BatchScore quadratic(const std::vector<double>& target, int* calls = nullptr) {
  return [target, calls](const std::vector<std::vector<double>>& xs) {
    if (calls != nullptr) ++*calls;
    std::vector<double> out;
    for (const std::vector<double>& x : xs) {
      double s = 0;
      for (std::size_t k = 0; k < x.size(); ++k) s -= (x[k] - target[k]) * (x[k] - target[k]);
      out.push_back(s);
    }
    return out;
  };
}

TEST(CrossEntropy, FindsTheMaximumOfAQuadraticInsideTheBox) {
  const std::vector<double> target = {0.2, 0.9, 0.5, 0.35, 0.7, 0.1};
  const CrossEntropyResult r = cross_entropy_maximize(6, 800, 3, {}, quadratic(target));
  EXPECT_EQ(r.evaluations, 800);
  for (std::size_t k = 0; k < target.size(); ++k) EXPECT_NEAR(r.best.x[k], target[k], 0.03) << k;
}

TEST(CrossEntropy, ReachesTheBoxBoundaryWhereTheMaximumLiesBeyondIt) {
  // The score grows without bound towards x = (1.5, -0.5): the best point is the box corner (1, 0).
  const CrossEntropyResult r = cross_entropy_maximize(2, 400, 4, {}, quadratic({1.5, -0.5}));
  EXPECT_EQ(r.best.x[0], 1.0);
  EXPECT_EQ(r.best.x[1], 0.0);
}

TEST(CrossEntropy, IsDeterministicAndKeepsItsBudget) {
  int calls = 0;
  const CrossEntropyResult a =
      cross_entropy_maximize(5, 75, 9, {}, quadratic({0.3, 0.3, 0.3, 0.3, 0.3}, &calls));
  const CrossEntropyResult b = cross_entropy_maximize(5, 75, 9, {}, quadratic({0.3, 0.3, 0.3, 0.3, 0.3}));
  EXPECT_EQ(a.evaluations, 75);
  EXPECT_EQ(calls, 5);  // 4 generations of 16 and one of 11
  EXPECT_EQ(a.best.x, b.best.x);
  EXPECT_EQ(a.best.evaluation, b.best.evaluation);
  const CrossEntropyResult c = cross_entropy_maximize(5, 75, 10, {}, quadratic({0.3, 0.3, 0.3, 0.3, 0.3}));
  EXPECT_NE(a.best.x, c.best.x);
}

TEST(CrossEntropy, RestartsWhenASearchStallsAndStopsWhenTold) {
  // A flat score never improves: a search's first generation sets its best, and stall_generations more
  // without improvement end it.
  const BatchScore flat = [](const std::vector<std::vector<double>>& xs) {
    return std::vector<double>(xs.size(), 0);
  };
  CrossEntropyOptions o;
  o.stall_generations = 2;
  const CrossEntropyResult r = cross_entropy_maximize(3, 16 * 7, 1, o, flat);
  EXPECT_EQ(r.searches, 3);  // generations 0-2, 3-5, 6
  int generations = 0;
  const CrossEntropyResult s = cross_entropy_maximize(
      3, 1000, 1, o, flat, [&](const std::vector<CrossEntropyCandidate>&) { return ++generations == 3; });
  EXPECT_EQ(s.evaluations, 48);
}

TEST(CrossEntropy, RefusesAnEmptyProblem) {
  EXPECT_THROW(cross_entropy_maximize(0, 10, 1, {}, quadratic({})), std::invalid_argument);
  EXPECT_THROW(cross_entropy_maximize(2, 0, 1, {}, quadratic({0, 0})), std::invalid_argument);
}

TEST(SignedDistance, IsTheDepthInsideAndTheDistanceOutside) {
  const auto task = load_task(builtin_path("two_blocks"));
  VerifyResult prediction;
  VerifyStep step{"m", ReachedSet(task->cspace)};
  const int e23 = task->cspace.nearest_atom(Vec3(-1.5, 0, 0), 1e-9);
  ASSERT_GE(e23, 0);
  step.termination.add_edge_interval(e23, 0.25, 0.75);  // y in [-2, 2] along the 8-long edge
  prediction.steps.push_back(step);
  const std::vector<PredictedStep> steps = predicted_steps(prediction);
  EXPECT_NEAR(signed_distance(task->cspace, steps[0], Vec3(-1.5, 0, 0), 1e-6), -2, 1e-12);
  EXPECT_NEAR(signed_distance(task->cspace, steps[0], Vec3(-1.5, 1.5, 0), 1e-6), -0.5, 1e-12);
  EXPECT_NEAR(signed_distance(task->cspace, steps[0], Vec3(-1.5, 2.5, 0), 1e-6), 0.5, 1e-12);
}

// two_blocks `slide` (a damper off block B's top into the gap, sliding to block A's wall): the verifier
// predicts the whole concave edge e23, y in [-4, 4]. The prediction cut at y <= 1 misses ends that drift
// beyond y = 1, which random errors produce in about 1 rollout of 7 (uniform) or 6 (extreme) and the search
// seeks (about 3 in 8 at this budget).
TEST(Falsify, FindsEndsOutsideAShrunkPredictionThatRandomSamplingMostlyMisses) {
  const auto task = load_task(builtin_path("two_blocks"));
  const Strategy& strategy = task->task.strategy_named("slide");
  VerifyResult prediction = verify_strategy(*task, strategy);
  ASSERT_TRUE(prediction.reliable);
  AxisBox keep{Vec3(-10, -10, -10), Vec3(10, 1, 10)};
  prediction.steps[0].termination = prediction.steps[0].termination.within_box(keep);
  FalsifyOptions o;
  o.threads = 2;
  o.coverage_budget = 0;
  o.seed = 5;
  const int budget = 64;
  FalsifyOptions searched = o, uniform = o;
  searched.budget = budget;
  searched.random = 0;
  uniform.budget = 0;
  uniform.random = budget;
  uniform.mode = SampleMode::kUniform;
  FalsifyOptions extreme = uniform;
  extreme.mode = SampleMode::kExtreme;
  const FalsifyResult s = run_falsify(task, strategy, prediction, searched);
  const FalsifyResult u = run_falsify(task, strategy, prediction, uniform);
  const FalsifyResult e = run_falsify(task, strategy, prediction, extreme);
  EXPECT_EQ(s.rollouts, budget);
  EXPECT_GE(s.outside, 10);
  EXPECT_GT(s.outside, 2 * u.outside) << "search " << s.outside << ", uniform random " << u.outside;
  EXPECT_GT(s.outside, e.outside) << "search " << s.outside << ", extreme random " << e.outside;
  ASSERT_FALSE(s.findings.empty());
  EXPECT_EQ(s.findings.front().how, "falsify");
  EXPECT_GT(s.findings.front().end.y(), 1);
  EXPECT_GT(s.best_signed_distance[0], 0);
  // The search's ends, for the report's figure: one per stable rollout, its ends outside the ones counted.
  EXPECT_EQ(static_cast<int>(s.search_ends.size()), s.rollouts - s.unstable);
  int ends_outside = 0;
  for (const SearchEnd& e : s.search_ends) {
    EXPECT_EQ(e.how, "falsify");
    EXPECT_EQ(e.step, 0);
    EXPECT_EQ(e.inside, distance_to_prediction(prediction.steps[0], e.end) <=
                            kContactRelativeTolerance * task->cspace.scale())
        << e.end.transpose() << " distance " << distance_to_prediction(prediction.steps[0], e.end);
    ends_outside += !e.inside;
  }
  EXPECT_EQ(ends_outside, s.outside);
  EXPECT_TRUE(std::any_of(s.search_ends.begin(), s.search_ends.end(),
                          [&](const SearchEnd& e) { return !e.inside && e.end == s.findings.front().end; }));
  // The finding replays from its vector alone.
  const ErrorVectorLayout layout(task->task, strategy, s.shape);
  ScriptedErrors errors(task->task, layout, s.findings.front().errors);
  SimOptions sim;
  sim.form = o.form;
  RolloutRunner runner(RolloutScene::build(task, sim));
  EXPECT_EQ(runner.run(strategy, errors, 0).motions.front().end, s.findings.front().end);
}

// two_blocks `slide`: the verifier (default options) predicts the concave edge e23 for |y| <= 1.69, which
// the rollouts reach throughout. The baseline here keeps only the random rollouts that ended at y < 0. The
// gap search must find errors that carry the end to y > 0 and cover at least .11 more of the edge (the y > 0
// half is .5). Its targets lie on the prediction, and a gap counts as reached exactly when its closest end is
// within the coverage radius.
TEST(Falsify, GapSearchFillsTheGapsARandomBaselineLeft) {
  const auto task = load_task(builtin_path("two_blocks"));
  const Strategy& strategy = task->task.strategy_named("slide");
  const VerifyResult prediction = verify_strategy(*task, strategy);
  FalsifyOptions o;
  o.threads = 2;
  o.seed = 3;
  o.budget = 0;
  o.coverage_budget = 0;
  o.gap_budget = 192;
  o.gap_rollouts = 48;
  SimOptions sim;
  sim.form = o.form;
  sim.mode = o.mode;
  std::vector<RolloutOutcome> baseline;
  for (RolloutOutcome& ro : run_rollouts(RolloutScene::build(task, sim), strategy, 100, o.seed, o.threads))
    if (!ro.unstable && ro.motions.front().end.y() < 0) baseline.push_back(std::move(ro));
  ASSERT_GE(baseline.size(), 30u);
  const FalsifyResult g = run_falsify(task, strategy, prediction, o, baseline);
  EXPECT_LT(g.coverage_before, 0.55);
  EXPECT_GT(g.coverage_after, g.coverage_before + 0.11)
      << "before " << g.coverage_before << ", after " << g.coverage_after;
  ASSERT_FALSE(g.gaps.empty());
  int spent = 0, reached_beyond_zero = 0;
  for (const CoverageGap& gap : g.gaps) {
    spent += gap.rollouts;
    EXPECT_EQ(gap.step, 0);
    EXPECT_LE(distance_to_prediction(prediction.steps[0], gap.point), 1e-9);
    EXPECT_GT(gap.gap, g.coverage_radius);
    EXPECT_EQ(gap.reached, gap.closest <= g.coverage_radius);
    reached_beyond_zero += gap.reached && gap.point.y() > 0;
  }
  EXPECT_GE(reached_beyond_zero, 1);
  EXPECT_EQ(spent, g.rollouts);
  EXPECT_LE(g.rollouts, o.gap_budget);
  EXPECT_EQ(static_cast<int>(g.search_ends.size()), g.rollouts - g.unstable);
  for (const SearchEnd& e : g.search_ends) EXPECT_EQ(e.how, "gap");
}

// The same strategy under the verifier model `cmt falsify` uses (slow slides count as stops,
// docs/verifier.md) is predicted on the whole edge, y in [-4, 4], while the rollouts end within about 1.7 of
// y = 0. The gap search's first target is an end of the edge; its search cannot come near it, and the points
// it came no closer to are skipped; the second target is the other end, and then nothing is left to target:
// two of the three searches the budget allows, not a third beside the first.
TEST(Falsify, GapSearchNamesThePartsOfThePredictionItCannotReach) {
  const auto task = load_task(builtin_path("two_blocks"));
  FalsifyOptions o;
  o.threads = 2;
  o.seed = 3;
  o.random = 100;
  o.budget = 0;
  o.coverage_budget = 0;
  o.gap_budget = 144;
  o.gap_rollouts = 48;
  const FalsifyResult g = run_falsify(task, "slide", o);
  ASSERT_EQ(g.gaps.size(), 2u);
  for (const CoverageGap& gap : g.gaps) {
    EXPECT_FALSE(gap.reached);
    EXPECT_GT(std::abs(gap.point.y()), 3.9);
    EXPECT_GT(gap.closest, 1);
  }
  EXPECT_LT(g.gaps[0].point.y() * g.gaps[1].point.y(), 0);  // opposite ends
  EXPECT_EQ(g.rollouts, 96);
}

// two_blocks `slide` with its goal cut at y = 1: the motion may end on the gap's foot edge beyond it (the
// verifier's model predicts the whole edge), and random errors put the end there in about 1 rollout of 7.
// The verdict is unreliable; the failure search (no random rollouts) must find a failing rollout, aiming at
// the part of the edge outside the goal, and stop at the generation that holds it; its replay reproduces the
// end. The task's own goal gives a reliable verdict, under which the failure search does not run.
TEST(Falsify, FailureSearchFindsAFailureUnderAnUnreliableVerdict) {
  std::ifstream in(builtin_path("two_blocks"));
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string goal = "polygon: [[-1.5, -4, 0], [1.5, -4, 0], [1.5, 4, 0], [-1.5, 4, 0]]";
  const std::size_t at = yaml.find(goal);
  ASSERT_NE(at, std::string::npos);
  yaml.replace(at, goal.size(), "polygon: [[-1.5, -4, 0], [1.5, -4, 0], [1.5, 1, 0], [-1.5, 1, 0]]");
  const auto cut = load_task_from_string(yaml, "two_blocks_cut");
  FalsifyOptions o;
  o.threads = 2;
  o.seed = 4;
  o.random = o.budget = o.coverage_budget = o.gap_budget = 0;
  o.failure_budget = 96;
  const FalsifyResult r = run_falsify(cut, "slide", o);
  ASSERT_FALSE(r.prediction.reliable);
  EXPECT_TRUE(r.failure_searched);
  ASSERT_TRUE(r.first_failure.has_value());
  EXPECT_EQ(r.first_failure->how, "failure");
  EXPECT_GT(r.first_failure->end.y(), 1);
  EXPECT_GE(r.failures, 1);
  EXPECT_FALSE(r.false_alarm());
  EXPECT_LT(r.failure_rollouts, o.failure_budget);  // stopped at the generation with the failure
  EXPECT_EQ(r.failure_rollouts, r.rollouts);
  EXPECT_LT(r.failure_closest, 0.01);  // some end came to the edge beyond the goal
  // The failure replays from its vector alone.
  const Strategy& strategy = cut->task.strategy_named("slide");
  const ErrorVectorLayout layout(cut->task, strategy, r.shape);
  ScriptedErrors errors(cut->task, layout, r.first_failure->errors);
  SimOptions sim;
  sim.form = o.form;
  RolloutRunner runner(RolloutScene::build(cut, sim));
  const RolloutOutcome replay = runner.run(strategy, errors, 0);
  EXPECT_FALSE(replay.success);
  EXPECT_EQ(replay.end, r.first_failure->end);

  const FalsifyResult reliable = run_falsify(load_task(builtin_path("two_blocks")), "slide", o);
  EXPECT_TRUE(reliable.prediction.reliable);
  EXPECT_FALSE(reliable.failure_searched);
  EXPECT_EQ(reliable.rollouts, 0);
  EXPECT_FALSE(reliable.false_alarm());
}

TEST(Falsify, ResultsDoNotDependOnTheThreadCount) {
  const auto task = load_task(builtin_path("two_blocks"));
  const Strategy& strategy = task->task.strategy_named("slide");
  const VerifyResult prediction = verify_strategy(*task, strategy);
  FalsifyOptions o;
  o.budget = 20;
  o.coverage_budget = 0;
  o.gap_budget = 16;
  o.gap_rollouts = 8;
  o.random = 40;  // a radius small enough to leave gaps
  o.threads = 1;
  const FalsifyResult one = run_falsify(task, strategy, prediction, o);
  o.threads = 2;
  const FalsifyResult two = run_falsify(task, strategy, prediction, o);
  EXPECT_EQ(one.best_errors, two.best_errors);
  EXPECT_EQ(one.best_signed_distance, two.best_signed_distance);
  EXPECT_EQ(one.coverage_after, two.coverage_after);
  ASSERT_FALSE(one.gaps.empty());
  ASSERT_EQ(one.gaps.size(), two.gaps.size());
  for (std::size_t k = 0; k < one.gaps.size(); ++k) {
    EXPECT_EQ(one.gaps[k].point, two.gaps[k].point);
    EXPECT_EQ(one.gaps[k].closest, two.gaps[k].closest);
  }
  ASSERT_EQ(one.search_ends.size(), two.search_ends.size());
  for (std::size_t k = 0; k < one.search_ends.size(); ++k) {
    EXPECT_EQ(one.search_ends[k].how, two.search_ends[k].how);
    EXPECT_EQ(one.search_ends[k].end, two.search_ends[k].end);
  }
}

}  // namespace
}  // namespace cmt
