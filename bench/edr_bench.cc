// EDR verification (verifier/edr) at Donald's slice counts (4, 16 and 72, Donald l.3726-3730) against one
// forward projection in the same run, first-order model, on the built-in model-error tasks:
//  - models/tasks/step_offset.yaml (Donald's Example (1)), strategy `edr` = (left). Baseline
//    BM_VerifyNominal: `verify` of the motion in the nominal slice (one forward projection). BM_Edr/N:
//    `verify_edr` on N evenly spaced slices of alpha (each slice: the task read and its C-space built, one
//    forward projection, the damper backprojections P and P~, and the cross-slice distinguishability test).
//  - models/tasks/hole_width.yaml (Donald's Example (6), the width), strategy `edr` = (left, down):
//    BM_VerifyNominalHoleWidth and BM_EdrHoleWidth/N likewise (two forward projections per slice).
//  - models/tasks/twin_universe.yaml (Donald's Example (3)), strategy `edr` = (down, up_left): its parameter
//    is discrete (J = {1, 2}), so BM_EdrTwinUniverse runs its two worlds, against
//    BM_VerifyNominalTwinUniverse.
// The growth with N is the report (docs/edr.md "Speed").
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "models/loaded_task.h"
#include "models/model_error.h"
#include "verifier/edr/edr.h"
#include "verifier/verify.h"

namespace {

std::shared_ptr<const cmt::LoadedTask> builtin(const std::string& name) {
  static std::map<std::string, std::shared_ptr<const cmt::LoadedTask>> tasks;
  auto& task = tasks[name];
  if (!task) task = cmt::load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/" + name + ".yaml");
  return task;
}

const std::vector<std::string>& strategy(const std::string& name) {
  static const std::map<std::string, std::vector<std::string>> motions = {
      {"step_offset", {"left"}}, {"hole_width", {"left", "down"}}, {"twin_universe", {"down", "up_left"}}};
  return motions.at(name);
}

void verify_nominal(benchmark::State& state, const std::string& name) {
  for (auto _ : state) benchmark::DoNotOptimize(cmt::verify_motions(*builtin(name), strategy(name)));
}

// N evenly spaced values of the task's first parameter, ends included.
void edr_on_slices(benchmark::State& state, const std::string& name) {
  const cmt::ModelParameter& p = builtin(name)->task.model_error.at(0);
  const int n = static_cast<int>(state.range(0));
  std::vector<std::vector<double>> slices;
  for (int i = 0; i < n; ++i) slices.push_back({p.min + (p.max - p.min) * i / (n - 1)});
  for (auto _ : state)
    benchmark::DoNotOptimize(cmt::verify_edr(builtin(name)->task, strategy(name), slices, cmt::EdrOptions{}));
  state.counters["slices"] = n;
}

void BM_VerifyNominal(benchmark::State& state) { verify_nominal(state, "step_offset"); }
void BM_Edr(benchmark::State& state) { edr_on_slices(state, "step_offset"); }
void BM_VerifyNominalHoleWidth(benchmark::State& state) { verify_nominal(state, "hole_width"); }
void BM_EdrHoleWidth(benchmark::State& state) { edr_on_slices(state, "hole_width"); }
void BM_VerifyNominalTwinUniverse(benchmark::State& state) { verify_nominal(state, "twin_universe"); }

void BM_EdrTwinUniverse(benchmark::State& state) {
  const cmt::Task& task = builtin("twin_universe")->task;
  const auto slices = cmt::model_slices(task, 2);
  for (auto _ : state)
    benchmark::DoNotOptimize(cmt::verify_edr(task, strategy("twin_universe"), slices, cmt::EdrOptions{}));
  state.counters["slices"] = static_cast<double>(slices.size());
}

}  // namespace

BENCHMARK(BM_VerifyNominal)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_Edr)->Arg(4)->Arg(16)->Arg(72)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_VerifyNominalHoleWidth)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_EdrHoleWidth)->Arg(4)->Arg(16)->Arg(72)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_VerifyNominalTwinUniverse)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_EdrTwinUniverse)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_MAIN();
