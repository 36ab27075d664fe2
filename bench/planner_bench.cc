// Buckley's planner (verifier/planner) against the C-space build, in the same run (docs/planner.md "Speed").
// Baseline BM_CSpaceBuild/<task>: CSpace::build of the task. BM_PrimitiveStates/<task>: Table 6.3's
// enumeration (at most 3 atoms). BM_SimulateAtom/cube: the targets and the cell of the hand strategy's p1
// = (0, 0, -3) from the cube's start edge (§6.7, every set built afresh). BM_Plan/cube: the whole §6.3.1 plan
// (simulation, composition, search).
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "models/loaded_task.h"
#include "verifier/planner/primitive_states.h"
#include "verifier/planner/search.h"
#include "verifier/planner/task_atoms.h"

namespace {

const char* const kTasks[] = {"cube", "hole", "tslot"};

std::shared_ptr<const cmt::LoadedTask> task(int index) {
  static std::shared_ptr<const cmt::LoadedTask> loaded[3];
  if (!loaded[index])
    loaded[index] = cmt::load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/" + kTasks[index] + ".yaml");
  return loaded[index];
}

void BM_CSpaceBuild(benchmark::State& state) {
  const auto t = task(static_cast<int>(state.range(0)));
  state.SetLabel(kTasks[state.range(0)]);
  for (auto _ : state) benchmark::DoNotOptimize(cmt::CSpace::build(t->task));
}

void BM_PrimitiveStates(benchmark::State& state) {
  const auto t = task(static_cast<int>(state.range(0)));
  state.SetLabel(kTasks[state.range(0)]);
  const auto& u = t->task.uncertainty;
  for (auto _ : state)
    benchmark::DoNotOptimize(cmt::planner::primitive_states(t->cspace, u.eps_s, u.theta_f, 3));
}

void BM_SimulateAtom(benchmark::State& state) {
  const auto t = task(0);
  const std::vector<int> start = cmt::planner::start_atoms(*t);
  const cmt::Vec3 p1(0, 0, -3);
  for (auto _ : state) {
    cmt::planner::AtomSimulation simulation(t->cspace, t->task.uncertainty);
    benchmark::DoNotOptimize(simulation.targets_at(start, p1));
    benchmark::DoNotOptimize(simulation.cell_at(start, p1));
  }
}

void BM_Plan(benchmark::State& state) {
  const auto t = task(0);
  cmt::planner::PlanRequest request;
  request.start_atoms = cmt::planner::start_atoms(*t);
  request.goal_atom = cmt::planner::goal_atoms(*t);
  request.eps_s = t->task.uncertainty.eps_s;
  request.theta_f = t->task.uncertainty.theta_f;
  for (auto _ : state) {
    cmt::planner::AtomSimulation simulation(t->cspace, t->task.uncertainty);
    benchmark::DoNotOptimize(cmt::planner::plan_sticking(simulation, t->cspace, request));
  }
}

BENCHMARK(BM_CSpaceBuild)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PrimitiveStates)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SimulateAtom)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Plan)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
