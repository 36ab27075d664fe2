// EDR verification (verifier/edr) at Donald's slice counts (4, 16 and 72, Donald l.3726-3730) against one
// forward projection in the same run, first-order model, on the built-in model-error tasks:
//  - models/tasks/step_offset.yaml (Donald's Example (1)), strategy `edr` = (left). Baseline
//    BM_VerifyNominal: `verify` of the motion in the nominal slice (one forward projection). BM_Edr/N:
//    `verify_edr` on N evenly spaced slices of alpha (each slice: the task read and its C-space built, one
//    forward projection, the damper backprojections P and P~, and the cross-slice distinguishability test).
//  - models/tasks/hole_width.yaml (Donald's Example (6), the width), strategy `edr` = (left, down):
//    BM_VerifyNominalHoleWidth and BM_EdrHoleWidth/N likewise (two forward projections per slice).
// The growth with N is the report (docs/edr.md "Speed").
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "models/loaded_task.h"
#include "verifier/edr/edr.h"
#include "verifier/verify.h"

namespace {

std::shared_ptr<const cmt::LoadedTask> step_offset() {
  static const auto task = cmt::load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/step_offset.yaml");
  return task;
}

void BM_VerifyNominal(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(cmt::verify_motions(*step_offset(), {"left"}));
}

void BM_Edr(benchmark::State& state) {
  const cmt::ModelParameter& alpha = step_offset()->task.model_error.at(0);
  const int n = static_cast<int>(state.range(0));
  std::vector<std::vector<double>> slices;
  for (int i = 0; i < n; ++i) slices.push_back({alpha.min + (alpha.max - alpha.min) * i / (n - 1)});
  for (auto _ : state)
    benchmark::DoNotOptimize(cmt::verify_edr(step_offset()->task, {"left"}, slices, cmt::EdrOptions{}));
  state.counters["slices"] = n;
}

std::shared_ptr<const cmt::LoadedTask> hole_width() {
  static const auto task = cmt::load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/hole_width.yaml");
  return task;
}

void BM_VerifyNominalHoleWidth(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(cmt::verify_motions(*hole_width(), {"left", "down"}));
}

void BM_EdrHoleWidth(benchmark::State& state) {
  const cmt::ModelParameter& w = hole_width()->task.model_error.at(0);
  const int n = static_cast<int>(state.range(0));
  std::vector<std::vector<double>> slices;
  for (int i = 0; i < n; ++i) slices.push_back({w.min + (w.max - w.min) * i / (n - 1)});
  for (auto _ : state)
    benchmark::DoNotOptimize(
        cmt::verify_edr(hole_width()->task, {"left", "down"}, slices, cmt::EdrOptions{}));
  state.counters["slices"] = n;
}

}  // namespace

BENCHMARK(BM_VerifyNominal)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_Edr)->Arg(4)->Arg(16)->Arg(72)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_VerifyNominalHoleWidth)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_EdrHoleWidth)->Arg(4)->Arg(16)->Arg(72)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_MAIN();
