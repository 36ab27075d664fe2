#include "models/task_transform.h"

#include <cmath>
#include <stdexcept>

namespace cmt {
namespace {

// The map, leaving y alone for planar tasks.
struct PlanarAwareTransform {
  TaskTransform map;
  bool planar = false;
  Vec3 point(const Vec3& x) const {
    Vec3 y = map.point(x);
    if (planar) y.y() = x.y();
    return y;
  }
  Vec3 direction(const Vec3& d) const { return map.direction(d); }
};

}  // namespace

bool is_quarter_turn_rotation(const Eigen::Matrix3d& r) {
  for (int i = 0; i < 3; ++i) {
    int nonzero = 0;
    for (int j = 0; j < 3; ++j) {
      if (r(i, j) == 0) continue;
      if (std::abs(r(i, j)) != 1) return false;
      ++nonzero;
    }
    if (nonzero != 1) return false;
  }
  return r.determinant() == 1;
}

namespace {

AxisBox map_box(const AxisBox& b, const PlanarAwareTransform& m) {
  const Vec3 a = m.point(b.min), c = m.point(b.max);
  return {a.cwiseMin(c), a.cwiseMax(c)};
}

void map_part(ConvexPart& part, const PlanarAwareTransform& m) {
  part.box = map_box(part.box, m);
  for (Vec3& v : part.vertices) v = m.point(v);
}

void map_termination(MotionTermination& t, const PlanarAwareTransform& m) {
  for (AxisBox& b : t.position) b = map_box(b, m);
  for (ForceCone& f : t.force) f.direction = m.direction(f.direction);
}

void map_region(Region& r, const PlanarAwareTransform& m) {
  for (Vec3& p : r.points) p = m.point(p);
}

}  // namespace

TaskTransform TaskTransform::quarter_turns(int axis, int turns) {
  TaskTransform t;
  const int k = ((turns % 4) + 4) % 4;
  Eigen::Matrix3d q = Eigen::Matrix3d::Zero();
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;  // the quarter turn maps e_a -> e_b, e_b -> -e_a
  q(axis, axis) = 1;
  q(b, a) = 1;
  q(a, b) = -1;
  for (int i = 0; i < k; ++i) t.rotation = q * t.rotation;
  return t;
}

TaskTransform TaskTransform::change_units(LengthUnit from, LengthUnit to) {
  TaskTransform t;
  t.scale = meters_per_unit(from) / meters_per_unit(to);
  t.units = to;
  return t;
}

TaskTransform TaskTransform::after(const TaskTransform& first) const {
  TaskTransform t;
  t.rotation = rotation * first.rotation;
  t.scale = scale * first.scale;
  t.offset = point(first.offset);
  t.units = units ? units : first.units;
  return t;
}

Task transformed(const Task& task, const TaskTransform& map) {
  if (!is_quarter_turn_rotation(map.rotation))
    throw std::invalid_argument("task transform: the rotation must be a signed permutation with det +1");
  if (!(map.scale > 0)) throw std::invalid_argument("task transform: the scale must be positive");
  if (task.dimension == 2 && (map.rotation(1, 1) != 1 || map.offset.y() != 0))
    throw std::invalid_argument("task transform: a planar task turns only about y and moves only in x and z");
  // A planar task's y is the extrusion axis, clipped to a slab of fixed half-depth (kPlanarClipHalfDepth, in
  // any units): its y coordinates are not lengths of the task and stay as they are.
  PlanarAwareTransform m{map, task.dimension == 2};
  Task out = task;
  // The copy is the nominal slice as a plain task: the model error's source text is not transformed.
  out.model_error.clear();
  out.model_values.clear();
  out.model_coordinates.clear();
  out.model_source.clear();
  if (map.units) out.units = *map.units;
  out.uncertainty.eps_s *= map.scale;
  out.uncertainty.eps_p *= map.scale;
  out.uncertainty.step *= map.scale;
  for (auto* parts : {&out.robot, &out.environment, &out.cspace})
    for (ConvexPart& p : *parts) map_part(p, m);
  if (task.physical()) {  // the robot's parts are relative to its reference point: turned and scaled only
    PlanarAwareTransform about_origin = m;
    about_origin.map.offset = Vec3::Zero();
    out.robot = task.robot;
    for (ConvexPart& p : out.robot) map_part(p, about_origin);
  }
  if (out.bounds) *out.bounds = map_box(*out.bounds, m);
  out.axes = map.rotation * task.axes;
  map_region(out.start, m);
  for (Region& g : out.goal) map_region(g, m);
  for (Motion& mo : out.motions) {
    mo.target = mo.kind == Motion::Kind::kSpring ? m.point(mo.target) : m.direction(mo.target);
    map_termination(mo.terminate, m);
  }
  for (Strategy& s : out.strategies)
    for (StrategyNode& n : s.nodes)
      for (StrategyBranch& b : n.branches) map_termination(b.when, m);
  return out;
}

Task geometry_in_own_axes(const Task& task) {
  Task out = task;
  out.axes = Eigen::Matrix3d::Identity();
  if (task.axes.isIdentity()) return out;
  TaskTransform to_own;
  to_own.rotation = task.axes.transpose();
  const PlanarAwareTransform m{to_own, task.dimension == 2};
  for (auto* parts : {&out.robot, &out.environment, &out.cspace})
    for (ConvexPart& p : *parts) map_part(p, m);
  if (out.bounds) *out.bounds = map_box(*out.bounds, m);
  return out;
}

}  // namespace cmt
