#include "models/loaded_task.h"

#include <cmath>
#include <sstream>

#include "models/polygon_distance.h"
#include "models/task_error.h"
#include "models/task_loader.h"
#include "models/task_ranges.h"
#include "models/task_transform.h"

namespace cmt {
namespace {

void check_on_surface(const LoadedTask& task, const Region& region) {
  const double tol = task.surface_tolerance();
  for (const Vec3& p : region_samples(region)) {
    const double d = task.cspace.distance_to_surface(p);
    if (d > tol) {
      std::ostringstream msg;
      msg << "the region is not on the contact surface: point (" << p.x() << ", " << p.y() << ", " << p.z()
          << ") is " << d << " from the nearest face (tolerance " << tol << ")";
      throw TaskError(task.task.source_file, region.key, msg.str());
    }
  }
}

// With model error the goal is the part of its regions on the contact surface in each world (it may vanish
// in some, Donald l.867): at the nominal values some of it must be there. As the verifier locates a partial
// goal (ReachedSet::from_region): a point on some atom; a segment or polygon on a face whose plane holds it
// whole.
bool partly_on_surface(const LoadedTask& task, const Region& region) {
  const double tol = task.surface_tolerance();
  if (region.kind == Region::Kind::kPoint) return task.cspace.distance_to_surface(region.points[0]) <= tol;
  for (const Face& f : task.cspace.faces()) {
    bool in_plane = true;
    for (const Vec3& p : region.points) in_plane = in_plane && std::abs(f.normal.dot(p) - f.offset) <= tol;
    if (!in_plane) continue;
    for (const Vec3& p : region_samples(region))
      if (distance_to_convex_polygon(p, f.polygon, f.normal) <= tol) return true;
  }
  return false;
}

void check_partly_on_surface(const LoadedTask& task, const std::vector<Region>& goal) {
  for (const Region& g : goal)
    if (partly_on_surface(task, g)) return;
  throw TaskError(task.task.source_file, goal.front().key,
                  "the goal is nowhere on the contact surface at the model parameters' nominal values");
}

enum class GoalCheck { kOnSurface, kPartly, kNone };

std::shared_ptr<const LoadedTask> finish(Task task, GoalCheck goal_check) {
  apply_scene_defaults(task);
  check_task_ranges(task);
  CSpace cspace = CSpace::build(task);
  auto loaded = std::make_shared<LoadedTask>(LoadedTask{std::move(task), std::move(cspace)});
  check_on_surface(*loaded, loaded->task.start);
  if (goal_check == GoalCheck::kOnSurface)
    for (const Region& g : loaded->task.goal) check_on_surface(*loaded, g);
  if (goal_check == GoalCheck::kPartly && !loaded->task.goal.empty())
    check_partly_on_surface(*loaded, loaded->task.goal);
  return loaded;
}

std::shared_ptr<const LoadedTask> finish(Task task) {
  const GoalCheck check = task.model_error.empty() ? GoalCheck::kOnSurface : GoalCheck::kPartly;
  return finish(std::move(task), check);
}

}  // namespace

std::vector<Vec3> region_samples(const Region& region, int per_side) {
  std::vector<Vec3> out = region.points;
  if (region.kind == Region::Kind::kSegment) {
    for (int i = 1; i < per_side; ++i) {
      const double t = static_cast<double>(i) / per_side;
      out.push_back((1 - t) * region.points[0] + t * region.points[1]);
    }
  } else if (region.kind == Region::Kind::kPolygon) {
    // Fan triangles from the first vertex, a barycentric grid on each.
    const Vec3& o = region.points[0];
    for (std::size_t k = 1; k + 1 < region.points.size(); ++k)
      for (int i = 0; i <= per_side; ++i)
        for (int j = 0; i + j <= per_side; ++j) {
          const double s = static_cast<double>(i) / per_side, t = static_cast<double>(j) / per_side;
          out.push_back(o + s * (region.points[k] - o) + t * (region.points[k + 1] - o));
        }
  }
  return out;
}

std::shared_ptr<const LoadedTask> load_task_from_task(Task task) { return finish(std::move(task)); }

std::shared_ptr<const LoadedTask> load_task_slice(const Task& task, const std::vector<double>& model_values) {
  return finish(task_at(task, model_values), GoalCheck::kNone);
}

std::shared_ptr<const LoadedTask> load_task(const std::filesystem::path& path) {
  return finish(parse_task_file(path));
}

std::shared_ptr<const LoadedTask> load_task_from_string(const std::string& yaml_text,
                                                        const std::string& label) {
  return finish(parse_task_string(yaml_text, label));
}

}  // namespace cmt
