// C-space construction cost, reported as ratios against a baseline measured in the same run (the YAML parse
// of the same task), because these machines are shared and noisy (DEVELOPERS.md "Fast").
#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>

#include "models/cspace.h"
#include "models/friction_cone.h"
#include "models/task_loader.h"

namespace {

std::string read(const std::string& name) {
  std::ifstream in(std::string(CMT_SOURCE_DIR) + "/models/tasks/" + name + ".yaml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void BM_ParseTask(benchmark::State& state, const std::string& name) {
  const std::string text = read(name);
  for (auto _ : state) benchmark::DoNotOptimize(cmt::parse_task_string(text, name));
}

void BM_BuildCSpace(benchmark::State& state, const std::string& name) {
  const cmt::Task task = cmt::parse_task_string(read(name), name);
  for (auto _ : state) benchmark::DoNotOptimize(cmt::CSpace::build(task));
}

void BM_VertexConeClassify(benchmark::State& state) {
  const double phi = std::atan(0.48);
  const cmt::FrictionCone cone = cmt::FrictionCone::sum(
      {{cmt::Vec3::UnitX(), phi}, {cmt::Vec3::UnitY(), phi}, {cmt::Vec3::UnitZ(), phi}});
  cmt::Vec3 d(0.3, 0.2, 1.0);
  for (auto _ : state) {
    benchmark::DoNotOptimize(cone.classify(d));
    d.x() = -d.x();
  }
}

}  // namespace

BENCHMARK_CAPTURE(BM_ParseTask, hole, std::string("hole"));
BENCHMARK_CAPTURE(BM_BuildCSpace, cube, std::string("cube"));
BENCHMARK_CAPTURE(BM_BuildCSpace, hole, std::string("hole"));
BENCHMARK_CAPTURE(BM_BuildCSpace, tslot, std::string("tslot"));
BENCHMARK(BM_VertexConeClassify);
BENCHMARK_MAIN();
