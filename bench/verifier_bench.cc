// Verifier primitives on the hole task (Buckley §5.2/§6.3.3): classifying every atom under one command, and
// building the spring sticking regions of every atom. Ratios against the same run's baseline: building the
// task's C-space (BM_BuildHoleCSpace).
#include <benchmark/benchmark.h>

#include "models/loaded_task.h"
#include "verifier/atom_cone.h"
#include "verifier/damper.h"
#include "verifier/spring.h"

namespace {

const cmt::LoadedTask& hole() {
  static const auto task = cmt::load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/hole.yaml");
  return *task;
}

void BM_BuildHoleCSpace(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(cmt::CSpace::build(hole().task));
}

// Building every atom's cone (with its polyhedral approximations) and classifying once.
void BM_AtomConesAndClassifyOnce(benchmark::State& state) {
  const auto& t = hole();
  const cmt::Vec3 v = cmt::Vec3(0.3, 0.2, -1).normalized();
  for (auto _ : state) {
    const cmt::AtomCones cones(t.cspace);
    for (int id = 0; id < cones.size(); ++id)
      benchmark::DoNotOptimize(cmt::classify_damper(cones, id, v, t.task.uncertainty.theta_v));
  }
}

// Steady state: the cone table exists (as in a verifier run); classify every atom for one command.
void BM_ClassifyDamperAllAtoms(benchmark::State& state) {
  const auto& t = hole();
  const cmt::AtomCones cones(t.cspace);
  cmt::Vec3 v = cmt::Vec3(0.3, 0.2, -1).normalized();
  for (int id = 0; id < cones.size(); ++id) cmt::classify_damper(cones, id, v, t.task.uncertainty.theta_v);
  for (auto _ : state)
    for (int id = 0; id < cones.size(); ++id)
      benchmark::DoNotOptimize(cmt::classify_damper(cones, id, v, t.task.uncertainty.theta_v));
}

void BM_SpringRegionsAllAtoms(benchmark::State& state) {
  const auto& t = hole();
  for (auto _ : state)
    for (int id = 0; id < t.cspace.atom_count(); ++id)
      benchmark::DoNotOptimize(cmt::spring_sticking_regions(t.cspace, id, t.task.uncertainty));
}

void BM_ClassifySpringGivenRegions(benchmark::State& state) {
  const auto& t = hole();
  std::vector<cmt::SpringStickingRegions> regions;
  for (int id = 0; id < t.cspace.atom_count(); ++id)
    regions.push_back(cmt::spring_sticking_regions(t.cspace, id, t.task.uncertainty));
  const cmt::Vec3 p(0, 2, -1);
  for (auto _ : state)
    for (const auto& r : regions) benchmark::DoNotOptimize(cmt::classify_spring(r, p));
}

}  // namespace

BENCHMARK(BM_BuildHoleCSpace)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AtomConesAndClassifyOnce)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ClassifyDamperAllAtoms)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SpringRegionsAllAtoms)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ClassifySpringGivenRegions)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
