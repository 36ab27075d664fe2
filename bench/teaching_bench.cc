// One teaching step (verifier/teaching) against the forward projection it is built on, in the same run: the
// hole teaching session of Buckley §5.2 (docs/teaching.md). Baseline BM_VerifyHoleP1: `verify` of p1 alone
// from the hole's start (one forward projection). BM_TeachHoleP1: the teaching session's step 1 (p1 solves
// nothing: every halving of the start is tried, 9 verifications). BM_TeachHoleP2: step 2 after step 1 (one
// verification of (p2, p1) from the merged start). The ridge's sensed dispatch (Alg 5.1,
// models/tasks/ridge.yaml) against its own baseline BM_VerifyRidgeDown (`verify` of down from the ridge's
// start): BM_TeachRidgeDown, step 2 after `right` (the chains, the dispatch's simulation and continuation
// checks, the dispatch verified from the start). The options are `cmt teach`'s except contact lift and servo
// coast (0).
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "models/loaded_task.h"
#include "verifier/teaching/teaching_session.h"
#include "verifier/verify.h"

namespace {

std::shared_ptr<const cmt::LoadedTask> hole() {
  static const auto task = cmt::load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/hole.yaml");
  return task;
}

cmt::teaching::TeachOptions options() {
  cmt::teaching::TeachOptions o;
  o.verify.spring_model = cmt::SpringModel::kVelocity;
  o.verify.stop_relative_speed = 0.01;  // controllers/termination.h kStopRelativeSpeed
  return o;
}

void BM_VerifyHoleP1(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(cmt::verify_motions(*hole(), {"p1"}, options().verify));
}

void BM_TeachHoleP1(benchmark::State& state) {
  for (auto _ : state) {
    cmt::teaching::Session session(hole(), options());
    benchmark::DoNotOptimize(session.propose("p1"));
  }
}

void BM_TeachHoleP2(benchmark::State& state) {
  for (auto _ : state) {
    state.PauseTiming();
    cmt::teaching::Session session(hole(), options());
    session.propose("p1");
    state.ResumeTiming();
    benchmark::DoNotOptimize(session.propose("p2"));
  }
}

std::shared_ptr<const cmt::LoadedTask> ridge() {
  static const auto task = cmt::load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/ridge.yaml");
  return task;
}

void BM_VerifyRidgeDown(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(cmt::verify_motions(*ridge(), {"down"}, options().verify));
}

void BM_TeachRidgeDown(benchmark::State& state) {
  for (auto _ : state) {
    state.PauseTiming();
    cmt::teaching::Session session(ridge(), options());
    session.propose("right");
    state.ResumeTiming();
    benchmark::DoNotOptimize(session.propose("down"));
  }
}

}  // namespace

BENCHMARK(BM_VerifyHoleP1)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_TeachHoleP1)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_TeachHoleP2)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_VerifyRidgeDown)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_TeachRidgeDown)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_MAIN();
