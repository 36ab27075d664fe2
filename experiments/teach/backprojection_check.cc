// Rollouts from points of a strong backprojection (backprojection_check.h).
#include "experiments/teach/backprojection_check.h"

#include <random>

#include "experiments/common/point_json.h"
#include "experiments/teach/teach_json.h"

namespace cmt {
namespace {

// The start the point stands for (a segment across the slab in a planar task) lies in S.
bool start_inside(const LoadedTask& task, const ReachedSet& strong, const Vec3& p) {
  Region r;
  r.kind = Region::Kind::kPoint;
  r.points = {p};
  r.key = "start";
  return ReachedSet::from_region(task, r).pieces_outside(strong, 0).empty();
}

// A point drawn uniformly on the convex polygon (fan triangles weighted by area).
Vec3 uniform_on(const std::vector<Vec3>& polygon, std::mt19937_64& rng) {
  std::vector<double> areas;
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
    areas.push_back(0.5 * (polygon[k] - polygon[0]).cross(polygon[k + 1] - polygon[0]).norm());
  std::discrete_distribution<std::size_t> pick(areas.begin(), areas.end());
  std::uniform_real_distribution<double> unit(0, 1);
  const std::size_t k = pick(rng) + 1;
  double a = unit(rng), b = unit(rng);
  if (a + b > 1) {
    a = 1 - a;
    b = 1 - b;
  }
  return polygon[0] + a * (polygon[k] - polygon[0]) + b * (polygon[k + 1] - polygon[0]);
}

}  // namespace

std::vector<Vec3> backprojection_sample(const LoadedTask& task, const ReachedSet& strong,
                                        const BackprojectionCheckOptions& options) {
  std::vector<Vec3> corners;
  for (const ReachedPiece& piece : strong.pieces())
    for (const Vec3& p : piece.polygon)
      if (start_inside(task, strong, p)) corners.push_back(p);
  std::vector<Vec3> out;
  const std::size_t want_corners = std::min<std::size_t>(corners.size(), options.points / 2);
  for (std::size_t k = 0; k < want_corners; ++k) out.push_back(corners[k * corners.size() / want_corners]);
  std::vector<int> faces;
  std::vector<double> areas;
  for (int f : strong.atoms())
    if (f < static_cast<int>(task.cspace.faces().size()) && strong.face_area(f) > 0) {
      faces.push_back(f);
      areas.push_back(strong.face_area(f));
    }
  if (faces.empty()) return out;
  std::mt19937_64 rng(options.seed);
  std::discrete_distribution<std::size_t> pick(areas.begin(), areas.end());
  // Rejection sampling: S covers a face in part; give up after 200 draws per wanted point.
  for (int draws = 0; static_cast<int>(out.size()) < options.points && draws < 200 * options.points;
       ++draws) {
    const int f = faces[pick(rng)];
    const Vec3 p = uniform_on(task.cspace.faces()[f].polygon, rng);
    if (strong.face_region_contains(f, p) && start_inside(task, strong, p)) out.push_back(p);
  }
  return out;
}

BackprojectionCheck check_backprojection(const std::string& task_yaml, const LoadedTask& task,
                                         const std::vector<std::string>& chain, const ReachedSet& strong,
                                         const BackprojectionCheckOptions& options) {
  BackprojectionCheck out;
  out.strategy = free_strategy_name(task.task, "backprojected");
  std::filesystem::create_directories(options.dir);
  const std::vector<Vec3> points = backprojection_sample(task, strong, options);
  for (std::size_t i = 0; i < points.size(); ++i) {
    PointCheck c;
    c.start = points[i];
    const std::filesystem::path file =
        options.dir / (task.task.name + "_point" + std::to_string(i + 1) + ".yaml");
    c.task_file = file.string();
    Region start;
    start.kind = Region::Kind::kPoint;
    start.points = {points[i]};
    const std::string text = strategy_task_yaml(task_yaml, task.task.dimension, chain, out.strategy, start);
    ValidateOptions v;
    v.n = options.n;
    v.seed = options.seed + i;
    v.threads = options.threads;
    v.mode = options.mode;
    v.form = options.form;
    c.result = check_task_file(file, text, out.strategy, v, "--check-dir");
    out.rollouts += c.result.rollouts;
    out.successes += c.result.successes;
    out.unstable += c.result.unstable;
    out.failures += c.result.failures();
    out.outside += c.result.outside;
    out.points.push_back(std::move(c));
  }
  return out;
}

nlohmann::json backprojection_check_json(const BackprojectionCheck& check, int dimension) {
  nlohmann::json points = nlohmann::json::array();
  for (const PointCheck& c : check.points) {
    nlohmann::json j = {{"start", point_json(c.start, dimension)}, {"task_file", c.task_file},
                        {"rollouts", c.result.rollouts},           {"successes", c.result.successes},
                        {"unstable", c.result.unstable},           {"outside", c.result.outside}};
    if (!c.result.replay.empty()) j["replay"] = c.result.replay;
    points.push_back(j);
  }
  return {{"strategy", check.strategy},
          {"rollouts", check.rollouts},
          {"successes", check.successes},
          {"unstable", check.unstable},
          {"failures", check.failures},
          {"outside", check.outside},
          {"points", points}};
}

}  // namespace cmt
