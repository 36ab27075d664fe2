// Generalized-damper forward projection (verifier/damper_projection.h) on two_blocks (Buckley Fig 4.1) and
// on synthetic scenes: a k x k grid of unit C-space boxes on a floor (k = 1, 4, 13: 14, ~110, ~1000 faces).
// Ratios against the same run's baseline: building the scene's C-space (BM_BuildCSpace/k). And the whole
// verification of the hole task's taught strategy (two spring motions, Buckley §5.2) and of the conditional
// two_blocks `probe` (§4.2), against the hole's and two_blocks' C-space builds.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <sstream>
#include <string>

#include "models/loaded_task.h"
#include "verifier/atom_cone.h"
#include "verifier/damper_projection.h"
#include "verifier/verify.h"

namespace {

// A built-in task (models/tasks/NAME.yaml), loaded once.
const cmt::LoadedTask& builtin(const std::string& name) {
  static std::map<std::string, std::shared_ptr<const cmt::LoadedTask>> cache;
  auto& t = cache[name];
  if (!t) t = cmt::load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/" + name + ".yaml");
  return *t;
}
const cmt::LoadedTask& two_blocks() { return builtin("two_blocks"); }

// Boxes of height 1 + (i + j) % 3 on a 2k+1 wide floor, 1 apart; the start is the top of box (0, 0); the
// motion slides down-left (v2 of two_blocks), mu = .25, theta_v = .25.
std::string grid_yaml(int k) {
  std::ostringstream y;
  y << "name: grid\nunits: in\nfriction: 0.25\nuncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.25, theta_f: "
       "0.1}\ncspace:\n";
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      y << "  - box: {min: [" << 2 * i + 1 << ", " << 2 * j + 1 << ", 0], max: [" << 2 * i + 2 << ", "
        << 2 * j + 2 << ", " << 1 + (i + j) % 3 << "]}\n";
  y << "bounds: {min: [0, 0, 0], max: [" << 2 * k + 1 << ", " << 2 * k + 1 << ", 5]}\n";
  y << "start: {point: [1.5, 1.5, 1]}\ngoal: {point: [0.5, 0.5, 0]}\n";
  y << "motions:\n  m: {damper: [1, 1, -1]}\nstrategies:\n  s: [m]\n";
  return y.str();
}

const cmt::LoadedTask& grid(int k) {
  static std::map<int, std::shared_ptr<const cmt::LoadedTask>> cache;
  auto& t = cache[k];
  if (!t) t = cmt::load_task_from_string(grid_yaml(k), "grid");
  return *t;
}

void project(benchmark::State& state, const cmt::LoadedTask& t, const cmt::Vec3& v) {
  const cmt::AtomCones cones(t.cspace);
  const cmt::ReachedSet start = cmt::ReachedSet::from_region(t, t.task.start);
  for (auto _ : state) benchmark::DoNotOptimize(cmt::forward_project_damper(t, cones, start, v));
  state.counters["faces"] = static_cast<double>(t.cspace.faces().size());
}

void BM_BuildCSpaceTwoBlocks(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(cmt::CSpace::build(two_blocks().task));
}
void BM_ProjectTwoBlocksDown(benchmark::State& state) { project(state, two_blocks(), cmt::Vec3(0, 0, -1)); }
void BM_ProjectTwoBlocksSlide(benchmark::State& state) {
  project(state, two_blocks(), cmt::Vec3(-1, 0, -1).normalized());
}
void BM_BuildCSpaceGrid(benchmark::State& state) {
  const auto& t = grid(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(cmt::CSpace::build(t.task));
  state.counters["faces"] = static_cast<double>(t.cspace.faces().size());
}
void BM_ProjectGrid(benchmark::State& state) {
  const auto& t = grid(static_cast<int>(state.range(0)));
  project(state, t, t.task.motions[0].target);
}

const cmt::LoadedTask& hole() { return builtin("hole"); }
void BM_BuildCSpaceHole(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(cmt::CSpace::build(hole().task));
}
void BM_VerifyHoleTeach(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(cmt::verify_strategy(hole(), *hole().task.find_strategy("teach")));
}
// The same strategy under the velocity-form spring model (docs/verifier.md), and the cube's sticking motion
// under both models.
void BM_VerifyHoleTeachVelocity(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(
        cmt::verify_strategy(hole(), *hole().task.find_strategy("teach"), {cmt::SpringModel::kVelocity}));
}
const cmt::LoadedTask& cube() { return builtin("cube"); }
void BM_BuildCSpaceCube(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(cmt::CSpace::build(cube().task));
}
void BM_VerifyCubeStick(benchmark::State& state) {
  const auto model = state.range(0) == 0 ? cmt::SpringModel::kViaPoint : cmt::SpringModel::kVelocity;
  for (auto _ : state)
    benchmark::DoNotOptimize(cmt::verify_strategy(cube(), *cube().task.find_strategy("stick"), {model}));
}
const cmt::LoadedTask& tslot() { return builtin("tslot"); }
void BM_BuildCSpaceTslot(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(cmt::CSpace::build(tslot().task));
}
// tslot `insert` under the velocity model (as `cmt verify` runs it), the slowest built-in verification.
void BM_VerifyTslotInsert(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(cmt::verify_strategy(tslot(), *tslot().task.find_strategy("insert"),
                                                  {cmt::SpringModel::kVelocity, 0.01}));
}
void BM_VerifyTwoBlocksProbe(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(cmt::verify_strategy(two_blocks(), *two_blocks().task.find_strategy("probe")));
}

}  // namespace

BENCHMARK(BM_BuildCSpaceTwoBlocks)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ProjectTwoBlocksDown)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_ProjectTwoBlocksSlide)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_BuildCSpaceGrid)->Arg(1)->Arg(4)->Arg(13)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_ProjectGrid)->Arg(1)->Arg(4)->Arg(13)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_BuildCSpaceHole)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_VerifyHoleTeach)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_VerifyHoleTeachVelocity)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_BuildCSpaceCube)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_VerifyCubeStick)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_VerifyTwoBlocksProbe)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_BuildCSpaceTslot)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_VerifyTslotInsert)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_MAIN();
