// C-space construction cost, reported as ratios against a baseline measured in the same run (the YAML parse
// of the same task), because these machines are shared and noisy (docs/verifier-speed.md).
#include <benchmark/benchmark.h>

#include <cmath>
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

// A C-space task of n disjoint boxes on a grid with gaps (widths 1 to 1.5, heights 1 to 2.5), the hostile
// input of many mostly disjoint obstacles; bounds enclose them with a margin.
std::string disjoint_boxes_yaml(int n) {
  const int side = static_cast<int>(std::ceil(std::sqrt(n)));
  std::ostringstream y;
  y << "name: boxes\nunits: in\nfriction: 0.25\n"
    << "uncertainty: {eps_s: 0.2, eps_p: 0.2, theta_v: 0.25, theta_f: 0.3}\ncspace:\n";
  for (int k = 0; k < n; ++k) {
    const double x = 2.0 * (k % side), yy = 2.0 * (k / side), z = 0.5 * (k % 2);
    y << "  - box: {min: [" << x << ", " << yy << ", " << z << "], max: [" << x + 1.0 + 0.25 * (k % 3) << ", "
      << yy + 1.0 + 0.25 * ((k / 3) % 3) << ", " << z + 1.0 + 0.5 * (k % 4) << "]}\n";
  }
  y << "bounds: {min: [-1, -1, -1], max: [" << 2 * side << ", " << 2 * side << ", 4]}\n"
    << "start: {point: [0.5, 0.5, 1]}\ngoal: {point: [0.5, 0.5, 1]}\n"
    << "motions:\n  v1: {damper: [0, 0, -1]}\nstrategies:\n  down: [v1]\n";
  return y.str();
}

// Construction time for n disjoint boxes; the ratio of the two arguments' times reads the growth exponent
// (near-linear construction: about 4x from 500 to 2000 boxes; quadratic: 16x).
void BM_BuildDisjointBoxes(benchmark::State& state) {
  const cmt::Task task =
      cmt::parse_task_string(disjoint_boxes_yaml(static_cast<int>(state.range(0))), "boxes");
  for (auto _ : state) benchmark::DoNotOptimize(cmt::CSpace::build(task));
  state.SetComplexityN(state.range(0));
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
BENCHMARK(BM_BuildDisjointBoxes)->Arg(500)->Arg(2000)->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK(BM_VertexConeClassify);
BENCHMARK_MAIN();
