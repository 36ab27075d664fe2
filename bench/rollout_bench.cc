// Rollout engine speed (docs/rollouts.md "Speed"), as ratios within one run (the machines are shared):
//   BM_BareStep   - a bare mj_step loop that replays the applied forces the engine recorded for the hole
//                   task's `teach` rollouts 0..7: the same trajectories, so the same contacts and solver
//                   work;
//   BM_EngineStep - the engine running those rollouts (sensing, controller, errors, monitors, checks).
// Both count simulation steps as items: engine overhead per step = BareStep items/s / EngineStep items/s - 1.
//   BM_Rollouts/threads:T - whole rollouts (hole teach, 16 per iteration) on T threads: rollouts/s, and the
//                   parallel efficiency rate(2) / (2 rate(1)).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "models/loaded_task.h"
#include "sim/mujoco_guard.h"
#include "sim/rollout.h"

namespace {

using cmt::Vec3;

constexpr int kRollouts = 8;
constexpr std::uint64_t kSeed = 1;

struct Fixture {
  std::shared_ptr<const cmt::LoadedTask> task;
  std::shared_ptr<const cmt::RolloutScene> scene;
  const cmt::Strategy* teach = nullptr;
  std::vector<Vec3> starts;
  std::vector<std::vector<Vec3>> forces;  // per rollout, per step
  long steps = 0;
};

const Fixture& fixture() {
  static const Fixture f = [] {
    Fixture x;
    x.task = cmt::load_task(std::filesystem::path(CMT_SOURCE_DIR) / "models" / "tasks" / "hole.yaml");
    x.scene = cmt::RolloutScene::build(x.task);
    x.teach = x.task->task.find_strategy("teach");
    cmt::RolloutRunner runner(x.scene);
    for (int i = 0; i < kRollouts; ++i) {
      std::vector<Vec3> applied;
      runner.record_applied_forces(&applied);
      x.starts.push_back(runner.run(*x.teach, kSeed, i).start);
      x.steps += static_cast<long>(applied.size());
      x.forces.push_back(std::move(applied));
    }
    return x;
  }();
  return f;
}

void BM_BareStep(benchmark::State& state) {
  const Fixture& f = fixture();
  cmt::MujocoData data(f.scene->model());
  const mjModel* m = f.scene->model()->get();
  mjData* d = data.get();
  const double s = f.scene->meters_per_unit();
  for (auto _ : state) {
    for (int i = 0; i < kRollouts; ++i) {
      mj_resetData(m, d);
      for (int k = 0; k < 3; ++k) d->qpos[k] = f.starts[i][k] * s;
      for (const Vec3& force : f.forces[i]) {
        d->qfrc_applied[0] = force[0];
        d->qfrc_applied[1] = force[1];
        d->qfrc_applied[2] = force[2];
        mj_step(m, d);
      }
    }
    benchmark::DoNotOptimize(d->qpos[0]);
  }
  state.SetItemsProcessed(state.iterations() * f.steps);
}

void BM_EngineStep(benchmark::State& state) {
  const Fixture& f = fixture();
  cmt::RolloutRunner runner(f.scene);
  long steps = 0;
  for (auto _ : state) {
    const long before = runner.total_steps();
    for (int i = 0; i < kRollouts; ++i) benchmark::DoNotOptimize(runner.run(*f.teach, kSeed, i));
    steps += runner.total_steps() - before;
  }
  if (steps != state.iterations() * f.steps) state.SkipWithError("the engine took other steps than recorded");
  state.SetItemsProcessed(steps);
}

void BM_Rollouts(benchmark::State& state) {
  const Fixture& f = fixture();
  const int threads = static_cast<int>(state.range(0));
  const int n = 16;
  for (auto _ : state) benchmark::DoNotOptimize(cmt::run_rollouts(f.scene, *f.teach, n, kSeed, threads));
  state.SetItemsProcessed(state.iterations() * n);
  state.counters["threads"] = threads;
}

}  // namespace

BENCHMARK(BM_BareStep)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_EngineStep)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_Rollouts)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(3.0);
BENCHMARK_MAIN();
