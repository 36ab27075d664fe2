// Adversarial-rollout speed (docs/falsify.md "Speed"), as ratios within one run (the machines are shared):
//   BM_SampledRollouts  - 16 hole `teach` rollouts with sampled errors (the Monte Carlo engine);
//   BM_ScriptedRollouts - 16 with errors from fixed random error vectors (sim/error_vector.h).
//     Both count simulation steps as items (the two sets of rollouts differ, so per-step cost is what
//     compares): the vector's decoding costs nothing per step when the rates agree; rollouts/s is in the
//     `rollouts_per_second` counter.
//   BM_SearchOverhead   - everything a search does besides its rollouts, per evaluation: the cross-entropy
//     bookkeeping over the 44-number vectors of hole `teach` and scoring two motion ends against the
//     prediction (signed distances), with the rollouts replaced by fixed ends.
//   BM_SceneBuild       - the MuJoCo scene a run_falsify call builds once.
// Search overhead share = SearchOverhead time per item / (that + ScriptedRollouts time per rollout).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "experiments/falsify/falsify.h"
#include "experiments/falsify/robustness.h"
#include "models/loaded_task.h"
#include "sim/error_vector.h"
#include "sim/rollout.h"
#include "verifier/verify.h"

namespace {

constexpr int kRollouts = 16;

struct Fixture {
  std::shared_ptr<const cmt::LoadedTask> task;
  std::shared_ptr<const cmt::RolloutScene> scene;
  const cmt::Strategy* teach = nullptr;
  cmt::VerifyResult prediction;
  std::vector<std::vector<double>> vectors;
};

const Fixture& fixture() {
  static const Fixture f = [] {
    Fixture x;
    const std::filesystem::path file =
        std::filesystem::path(CMT_SOURCE_DIR) / "models" / "tasks" / "hole.yaml";
    x.task = cmt::load_task(file);
    cmt::SimOptions sim;
    sim.form = cmt::ControllerForm::kImpedance;
    x.scene = cmt::RolloutScene::build(x.task, sim);
    x.teach = x.task->task.find_strategy("teach");
    // The impedance form's verifier model, as cmt falsify and cmt validate use it.
    const cmt::VerifierModel model = cmt::make_verifier_model(x.task, cmt::ControllerForm::kImpedance);
    x.prediction = cmt::verify_strategy(*model.task, *x.teach, model.verify_options());
    const cmt::ErrorVectorLayout layout(x.task->task, *x.teach, cmt::default_error_shape(false, 0.2));
    cmt::Rng rng = cmt::rollout_stream(1, 0);
    for (int i = 0; i < kRollouts; ++i) {
      std::vector<double> v(static_cast<std::size_t>(layout.size()));
      for (double& u : v) u = cmt::uniform01(rng);
      x.vectors.push_back(std::move(v));
    }
    return x;
  }();
  return f;
}

void run_rollouts(benchmark::State& state, bool scripted) {
  const Fixture& f = fixture();
  cmt::RolloutRunner runner(f.scene);
  const cmt::ErrorVectorLayout layout(f.task->task, *f.teach, cmt::default_error_shape(false, 0.2));
  const long before = runner.total_steps();
  for (auto _ : state)
    for (int i = 0; i < kRollouts; ++i) {
      if (!scripted) {
        benchmark::DoNotOptimize(runner.run(*f.teach, 1, i));
        continue;
      }
      cmt::ScriptedErrors errors(f.task->task, layout, f.vectors[static_cast<std::size_t>(i)]);
      benchmark::DoNotOptimize(runner.run(*f.teach, errors, i));
    }
  state.SetItemsProcessed(runner.total_steps() - before);
  state.counters["rollouts_per_second"] =
      benchmark::Counter(static_cast<double>(state.iterations() * kRollouts), benchmark::Counter::kIsRate);
}

void BM_SampledRollouts(benchmark::State& state) { run_rollouts(state, false); }
BENCHMARK(BM_SampledRollouts)->Unit(benchmark::kMillisecond);

void BM_ScriptedRollouts(benchmark::State& state) { run_rollouts(state, true); }
BENCHMARK(BM_ScriptedRollouts)->Unit(benchmark::kMillisecond);

void BM_SearchOverhead(benchmark::State& state) {
  const Fixture& f = fixture();
  const std::vector<cmt::PredictedStep> steps = cmt::predicted_steps(f.prediction);
  const double tolerance = 1e-4 * f.task->cspace.scale();
  // Ends on the predicted sets' first pieces: each scored like a rollout's end.
  std::vector<cmt::Vec3> ends;
  for (const cmt::PredictedStep& s : steps) ends.push_back(s.pieces.front().polygon.front());
  const cmt::BatchScore score = [&](const std::vector<std::vector<double>>& xs) {
    std::vector<double> out;
    for (std::size_t i = 0; i < xs.size(); ++i) {
      double best = -1e300;
      for (std::size_t k = 0; k < steps.size(); ++k)
        best = std::max(best, cmt::signed_distance(f.task->cspace, steps[k], ends[k], tolerance));
      out.push_back(best);
    }
    return out;
  };
  const int dimension = static_cast<int>(f.vectors.front().size());
  for (auto _ : state)
    benchmark::DoNotOptimize(cmt::cross_entropy_maximize(dimension, 2 * kRollouts, 1, {}, score));
  state.SetItemsProcessed(state.iterations() * 2 * kRollouts);
}
BENCHMARK(BM_SearchOverhead)->Unit(benchmark::kMillisecond);

void BM_SceneBuild(benchmark::State& state) {
  const Fixture& f = fixture();
  for (auto _ : state) benchmark::DoNotOptimize(cmt::RolloutScene::build(f.task, f.scene->options()));
}
BENCHMARK(BM_SceneBuild)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
