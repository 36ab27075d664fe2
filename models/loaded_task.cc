#include "models/loaded_task.h"

#include <sstream>

#include "models/task_error.h"
#include "models/task_loader.h"
#include "models/task_ranges.h"
#include "models/task_transform.h"

namespace cmt {
namespace {

void check_on_surface(const LoadedTask& lt, const Region& region) {
  const double tol = lt.surface_tolerance();
  for (const Vec3& p : region_samples(region)) {
    const double d = lt.cspace.distance_to_surface(p);
    if (d > tol) {
      std::ostringstream msg;
      msg << "the region is not on the contact surface: point (" << p.x() << ", " << p.y() << ", " << p.z()
          << ") is " << d << " from the nearest face (tolerance " << tol << ")";
      throw TaskError(lt.task.source_file, region.key, msg.str());
    }
  }
}

std::shared_ptr<const LoadedTask> finish(Task task, bool goal_on_surface = true) {
  apply_scene_defaults(task);
  check_task_ranges(task);
  CSpace cspace = CSpace::build(task);
  auto loaded = std::make_shared<LoadedTask>(LoadedTask{std::move(task), std::move(cspace)});
  check_on_surface(*loaded, loaded->task.start);
  if (goal_on_surface)
    for (const Region& g : loaded->task.goal) check_on_surface(*loaded, g);
  return loaded;
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
  return finish(task_at(task, model_values), /*goal_on_surface=*/false);
}

std::shared_ptr<const LoadedTask> load_task(const std::filesystem::path& path) {
  return finish(parse_task_file(path));
}

std::shared_ptr<const LoadedTask> load_task_from_string(const std::string& yaml_text,
                                                        const std::string& label) {
  return finish(parse_task_string(yaml_text, label));
}

}  // namespace cmt
