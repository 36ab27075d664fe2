#include "models/task_loader.h"

#include <yaml-cpp/yaml.h>

#include <Eigen/Dense>
#include <cmath>
#include <fstream>
#include <numbers>
#include <regex>
#include <set>
#include <sstream>

#include "models/task_error.h"
#include "models/task_ranges.h"
#include "models/task_transform.h"
#include "models/yaml_document.h"
#include "models/yaml_node.h"

namespace cmt {
namespace {

// Relative tolerance for "the polygon's points lie in one plane": distance to the best-fit plane over the
// polygon's diameter. Looser than the contact tolerance because hand-written decimals are rounded.
constexpr double kPolygonPlanarityTolerance = 1e-9;

using Node = YamlNode;

class Parser {
 public:
  Parser(std::string file_label, const std::vector<double>* model_values)
      : file_(std::move(file_label)), requested_values_(model_values) {}

  Task parse(const YAML::Node& root_node) {
    Node root(root_node, "", &file_);
    if (!root_node.IsDefined() || root_node.IsNull()) root.fail("the file is empty");
    root.require_map({"name", "description", "units", "friction", "uncertainty", "dimension", "robot",
                      "environment", "cspace", "bounds", "axes", "start", "goal", "motions", "strategies",
                      "model_error"});
    Task task;
    task.source_file = file_;
    task.name = root.at("name").string();
    if (!std::regex_match(task.name, std::regex("[a-z0-9_-]+")))
      root.at("name").fail("must match [a-z0-9_-]+, got '" + task.name + "'");
    if (root.has("description")) task.description = root.at("description").string();
    if (root.has("dimension")) {
      const double d = root.at("dimension").number();
      if (d != 2 && d != 3) root.at("dimension").fail("must be 2 or 3");
      task.dimension = static_cast<int>(d);
    }
    dimension_ = task.dimension;
    if (root.has("units")) {
      const std::string u = root.at("units").string();
      if (u == "in")
        task.units = LengthUnit::kInch;
      else if (u == "mm")
        task.units = LengthUnit::kMillimeter;
      else if (u == "m")
        task.units = LengthUnit::kMeter;
      else
        root.at("units").fail("must be one of in, mm, m; got '" + u + "'");
    }
    if (root.has("friction")) task.friction = friction(root.at("friction"));
    task.uncertainty = parse_uncertainty(root.at("uncertainty"));
    if (root.has("model_error")) parse_model_error(root.at("model_error"), task);
    if (requested_values_ && requested_values_->size() != task.model_error.size())
      root.fail("a slice needs " + std::to_string(task.model_error.size()) + " model parameter values, got " +
                std::to_string(requested_values_->size()));
    model_ = &task;

    const bool physical = root.has("robot") || root.has("environment");
    if (physical && root.has("cspace"))
      root.at("cspace").fail("give either robot + environment (physical parts) or cspace, not both");
    // Parts, bounds and goal may be affine in the model parameters; their coordinates and the start's are
    // recorded (ModelCoordinate::role) to find the critical slices.
    affine_ = true;
    if (physical) {
      role_ = ModelCoordinate::Role::kRobot;
      task.robot = parse_parts(root.at("robot"), task.friction, /*robot=*/true);
      if (task.robot.empty()) root.at("robot").fail("the robot needs at least one part");
      role_ = ModelCoordinate::Role::kEnvironment;
      task.environment = parse_parts(root.at("environment"), task.friction, /*robot=*/false);
    } else if (root.has("cspace") || root.raw()["cspace"].IsDefined()) {
      role_ = ModelCoordinate::Role::kConfiguration;
      if (root.has("cspace")) task.cspace = parse_parts(root.at("cspace"), task.friction, /*robot=*/false);
    } else {
      root.fail("missing geometry: give robot + environment (physical parts) or cspace (C-space obstacles)");
    }
    role_ = ModelCoordinate::Role::kConfiguration;
    if (root.has("bounds")) task.bounds = parse_box(root.at("bounds"), {"min", "max"});
    if (root.has("axes")) task.axes = parse_axes(root.at("axes"));
    if (task.cspace.empty() && task.environment.empty() && !task.bounds)
      root.fail("no obstacles and no bounds: the configuration space has no contact surface");

    affine_ = false;
    task.start = parse_region(root.at("start"));
    affine_ = true;
    const Node goal = root.at("goal");
    if (goal.is_sequence()) {
      if (goal.size() == 0) goal.fail("the goal list is empty");
      check_size(goal, goal.size(), kMaxGoalRegions, "goal regions");
      for (std::size_t i = 0; i < goal.size(); ++i) task.goal.push_back(parse_region(goal.item(i)));
    } else {
      task.goal.push_back(parse_region(goal));
    }
    affine_ = false;
    role_ = ModelCoordinate::Role::kNone;
    if (root.has("motions")) parse_motions(root.at("motions"), task);
    if (root.has("strategies")) parse_strategies(root.at("strategies"), task);
    return task;
  }

 private:
  double nonnegative(const Node& n, const std::string& what) const {
    const double v = n.number();
    if (v < 0) n.fail(what + " must be >= 0, got " + format(v));
    return v;
  }
  double friction(const Node& n) const {
    const double mu = nonnegative(n, "friction coefficient");
    if (mu > kMaxFriction) n.fail("friction coefficient " + format(mu) + " exceeds " + format(kMaxFriction));
    return mu;
  }
  static std::string format(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }

  // model_error: {name: [min, max]}, {name: {interval: [min, max], nominal: v}} or {name: {values: [v1, v2,
  // ...], nominal: v}} (docs/task-format.md).
  void parse_model_error(const Node& n, Task& task) const {
    const std::vector<std::string> names = n.keys();
    if (names.empty()) n.fail("no model parameters (omit model_error for a task without model error)");
    check_size(n, names.size(), kMaxModelParameters, "model parameters");
    for (const std::string& name : names) {
      const Node item = n.at(name);
      if (!std::regex_match(name, std::regex("[a-z_][a-z0-9_]*")))
        item.fail("a model parameter name must match [a-z_][a-z0-9_]*");
      ModelParameter p = item.is_map() && item.has("values") ? parse_discrete_parameter(item)
                                                             : parse_interval_parameter(item);
      p.name = name;
      if (item.is_map() && item.has("nominal")) {
        p.nominal = item.at("nominal").number();
        if (!p.admits(p.nominal))
          item.at("nominal").fail(p.discrete()
                                      ? "must be one of the values"
                                      : "must lie in [" + format(p.min) + ", " + format(p.max) + "]");
      }
      task.model_error.push_back(p);
    }
    if (requested_values_ && requested_values_->size() != task.model_error.size())
      n.fail("a slice needs " + std::to_string(task.model_error.size()) + " model parameter values, got " +
             std::to_string(requested_values_->size()));
    for (std::size_t i = 0; i < task.model_error.size(); ++i) {
      const ModelParameter& p = task.model_error[i];
      const double v = requested_values_ ? (*requested_values_)[i] : p.nominal;
      if (!p.admits(v))
        n.at(p.name).fail("slice value " + format(v) +
                          (p.discrete() ? " is not one of the values"
                                        : " is outside [" + format(p.min) + ", " + format(p.max) + "]"));
      task.model_values.push_back(v);
    }
  }
  static ModelParameter parse_interval_parameter(const Node& item) {
    ModelParameter p;
    const Node interval = item.is_map() ? item.at("interval") : item;
    if (item.is_map()) item.require_map({"interval", "nominal"});
    const std::vector<double> ends = interval.numbers();
    if (ends.size() != 2)
      interval.fail("an interval is [min, max], got " + std::to_string(ends.size()) + " numbers");
    p.min = ends[0];
    p.max = ends[1];
    if (!(p.min <= p.max)) interval.fail("min " + format(p.min) + " must be <= max " + format(p.max));
    if (std::max(std::abs(p.min), std::abs(p.max)) > kMaxCoordinate)
      interval.fail("magnitude exceeds " + format(kMaxCoordinate));
    p.nominal = (p.min + p.max) / 2;
    return p;
  }
  // A discrete parameter (a finite J, e.g. Donald's twin universe J = {1, 2}): increasing values.
  static ModelParameter parse_discrete_parameter(const Node& item) {
    item.require_map({"values", "nominal"});
    const Node values = item.at("values");
    ModelParameter p;
    p.values = values.numbers();  // not empty
    check_size(values, p.values.size(), kMaxModelSlices, "values");
    for (std::size_t i = 0; i < p.values.size(); ++i) {
      if (std::abs(p.values[i]) > kMaxCoordinate) values.fail("magnitude exceeds " + format(kMaxCoordinate));
      if (i > 0 && !(p.values[i - 1] < p.values[i]))
        values.fail("values must increase: " + format(p.values[i - 1]) + " then " + format(p.values[i]));
    }
    p.min = p.values.front();
    p.max = p.values.back();
    p.nominal = p.values.front();
    return p;
  }

  // A coordinate: a number, or (with model_error, in the parts, the bounds and the goal) an affine expression
  // in the model parameters, read at the task's model values and recorded for the critical slices.
  double model_coordinate(const Node& n, int axis) const {
    if (!model_ || model_->model_error.empty() || !n.raw().IsScalar()) return n.number();
    double number = 0;
    if (YAML::convert<double>::decode(n.raw(), number)) {
      if (role_ != ModelCoordinate::Role::kNone)
        model_->model_coordinates.push_back(
            {axis, AffineValue{number, std::vector<double>(model_->model_error.size(), 0)}, role_});
      return n.number();
    }
    if (!affine_)
      n.fail("expected a number: only parts, bounds and goal regions may depend on the model parameters");
    AffineValue value;
    try {
      value = parse_affine(n.raw().Scalar(), model_->model_error);
    } catch (const std::invalid_argument& e) {
      n.fail(std::string("not a number or an affine expression in the model parameters: ") + e.what());
    }
    model_->model_coordinates.push_back({axis, value, role_});
    return value.at(model_->model_values);
  }

  Uncertainty parse_uncertainty(const Node& n) const {
    n.require_map({"eps_s", "eps_p", "theta_v", "theta_f", "step"});
    Uncertainty u;
    u.eps_s = nonnegative(n.at("eps_s"), "the position-sensing error bound");
    u.eps_p = nonnegative(n.at("eps_p"), "the positioning error bound");
    u.theta_v = nonnegative(n.at("theta_v"), "the velocity error angle");
    if (u.theta_v >= kMaxThetaV) n.at("theta_v").fail(theta_v_range_reason(u.theta_v));
    u.theta_f = nonnegative(n.at("theta_f"), "the force-sensing error angle");
    if (u.theta_f >= std::numbers::pi) n.at("theta_f").fail("must be < pi radians, got " + format(u.theta_f));
    u.step = 0;  // absent: apply_scene_defaults (models/task_ranges.h) sets it from eps_p and the scene
    if (n.has("step")) {
      u.step = n.at("step").number();
      if (u.step <= 0) n.at("step").fail("the spring interpolation step must be > 0, got " + format(u.step));
    }
    return u;
  }

  // A vector in the task's dimension; planar [x, z] is lifted to (x, planar_y, z).
  Vec3 parse_vector(const Node& n, double planar_y = 0) const {
    if (!n.is_sequence()) n.fail("expected a list of " + std::to_string(dimension_) + " numbers");
    if (static_cast<int>(n.size()) != dimension_)
      n.fail("expected " + std::to_string(dimension_) + " numbers, got " + std::to_string(n.size()));
    const auto coordinate = [&](std::size_t i) {
      const double v = model_coordinate(n.item(i), i == 1 && dimension_ == 2 ? 2 : static_cast<int>(i));
      if (std::abs(v) > kMaxCoordinate)
        n.item(i).fail("magnitude " + format(std::abs(v)) + " exceeds the largest accepted coordinate " +
                       format(kMaxCoordinate) + " (docs/task-format.md \"Accepted ranges and sizes\")");
      return v;
    };
    if (dimension_ == 2) return Vec3(coordinate(0), planar_y, coordinate(1));
    return Vec3(coordinate(0), coordinate(1), coordinate(2));
  }
  // The task's own axes (Task::axes): three world vectors, its x, y and z axes, each a signed world axis,
  // together a proper rotation; a planar task turns only about y, so its y axis is [0, 1, 0]. Always three
  // numbers per axis, also in a planar task.
  Eigen::Matrix3d parse_axes(const Node& n) const {
    if (!n.is_sequence() || n.size() != 3)
      n.fail("expected three axes [x axis, y axis, z axis], each [x, y, z]");
    Eigen::Matrix3d r;
    for (std::size_t j = 0; j < 3; ++j) {
      const Node axis = n.item(j);
      if (!axis.is_sequence() || axis.size() != 3)
        axis.fail("expected a world axis [x, y, z] such as [0, -1, 0]");
      for (std::size_t i = 0; i < 3; ++i) {
        const double v = axis.item(i).number();
        if (v != 0 && v != 1 && v != -1)
          axis.item(i).fail("each entry is 0, 1 or -1 (an axis is a signed world axis)");
        r(static_cast<int>(i), static_cast<int>(j)) = v;
      }
    }
    if (!is_quarter_turn_rotation(r))
      n.fail("the axes must be signed world axes forming a right-handed frame (a rotation by quarter turns)");
    if (dimension_ == 2 && r.col(1) != Eigen::Vector3d::UnitY())
      n.item(1).fail("a planar task turns only about y: its y axis is [0, 1, 0]");
    return r;
  }
  // A direction (damper velocity, force cone axis), normalized.
  // `edr: true`: the motion carries the EDR termination predicate (task.h Motion::edr_signal).
  static bool parse_edr_signal(const Node& n) {
    const std::string v = n.string();
    if (v != "true" && v != "false") n.fail("expected true or false, got '" + v + "'");
    return v == "true";
  }

  Vec3 parse_direction(const Node& n, const std::string& what) const {
    Vec3 d = parse_vector(n);
    if (!(d.norm() >= kMinDirectionLength))
      n.fail(what + " is the zero vector (or shorter than " + format(kMinDirectionLength) + ")");
    return d.normalized();
  }
  // At most `limit` items (docs/task-format.md "Accepted ranges and sizes").
  static void check_size(const Node& n, std::size_t size, std::size_t limit, const std::string& what) {
    if (size > limit)
      n.fail("too many " + what + ": " + std::to_string(size) + ", at most " + std::to_string(limit));
  }

  AxisBox parse_box(const Node& n, const std::set<std::string>& allowed, double planar_half_depth = 0) const {
    n.require_map(allowed);
    AxisBox b;
    b.min = parse_vector(n.at("min"), -planar_half_depth);
    b.max = parse_vector(n.at("max"), planar_half_depth);
    if (dimension_ == 2 && planar_half_depth == 0) {  // bounds of a planar task: the clip slab
      b.min.y() = -kPlanarClipHalfDepth;
      b.max.y() = kPlanarClipHalfDepth;
    }
    static const char* axis[] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i)
      if (!(b.min[i] < b.max[i]))
        n.fail(std::string("degenerate box: min ") + axis[i] + " = " + format(b.min[i]) + " must be < max " +
               axis[i] + " = " + format(b.max[i]));
    return b;
  }

  std::vector<ConvexPart> parse_parts(const Node& list_node, double default_friction, bool robot) const {
    const Node list = list_node.sequence();
    check_size(list, list.size(), kMaxParts, "parts");
    std::vector<ConvexPart> parts;
    const double half_depth = robot ? kPlanarRobotHalfDepth : kPlanarPartHalfDepth;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Node item = list.item(i);
      item.require_map({"box", "convex"});
      if (item.size() != 1) item.fail("a part is exactly one of box or convex");
      ConvexPart part;
      part.friction = default_friction;
      const bool is_box = item.has("box");
      const Node body = item.at(is_box ? "box" : "convex");
      part.key = body.path();
      std::set<std::string> allowed =
          is_box ? std::set<std::string>{"min", "max"} : std::set<std::string>{"vertices"};
      if (!robot) allowed.insert("friction");
      if (is_box) {
        part.shape = ConvexPart::Shape::kBox;
        part.box = parse_box(body, allowed, half_depth);
        for (int c = 0; c < 8; ++c)
          part.vertices.emplace_back((c & 1) ? part.box.max.x() : part.box.min.x(),
                                     (c & 2) ? part.box.max.y() : part.box.min.y(),
                                     (c & 4) ? part.box.max.z() : part.box.min.z());
      } else {
        body.require_map(allowed);
        part.shape = ConvexPart::Shape::kConvex;
        const Node verts = body.at("vertices").sequence();
        check_size(verts, verts.size(), kMaxConvexVertices, "points");
        for (std::size_t k = 0; k < verts.size(); ++k) {
          if (dimension_ == 2) {
            part.vertices.push_back(parse_vector(verts.item(k), -half_depth));
            part.vertices.push_back(parse_vector(verts.item(k), half_depth));
          } else {
            part.vertices.push_back(parse_vector(verts.item(k)));
          }
        }
        check_solid(body.at("vertices"), part.vertices);
      }
      if (!robot && body.has("friction")) part.friction = friction(body.at("friction"));
      parts.push_back(std::move(part));
    }
    return parts;
  }

  // A convex part needs 4 points that are not coplanar (a solid hull). The test is relative to the part size.
  void check_solid(const Node& n, const std::vector<Vec3>& pts) const {
    if (pts.size() < 4)
      n.fail("a convex part needs at least 4 non-coplanar points, got " + std::to_string(pts.size()));
    double diameter = 0;
    for (const Vec3& p : pts)
      for (const Vec3& q : pts) diameter = std::max(diameter, (p - q).norm());
    if (diameter <= 0) n.fail("all points coincide");
    // Largest tetrahedron volume against diameter^3: zero for coplanar sets.
    const Vec3& a = pts[0];
    double best = 0;
    for (std::size_t i = 1; i < pts.size(); ++i)
      for (std::size_t j = i + 1; j < pts.size(); ++j)
        for (std::size_t k = j + 1; k < pts.size(); ++k)
          best = std::max(best, std::abs((pts[i] - a).cross(pts[j] - a).dot(pts[k] - a)));
    if (best <= 1e-12 * diameter * diameter * diameter)
      n.fail(
          "a convex part needs at least 4 non-coplanar points; these are coplanar (a flat hull has no "
          "volume)");
  }

  Region parse_region(const Node& n) const {
    n.require_map({"point", "segment", "polygon"});
    if (n.size() != 1) n.fail("a region is exactly one of point, segment, polygon");
    Region r;
    r.key = n.path();
    if (n.has("point")) {
      r.kind = Region::Kind::kPoint;
      r.points.push_back(parse_vector(n.at("point")));
      return r;
    }
    const bool segment = n.has("segment");
    const Node pts = n.at(segment ? "segment" : "polygon").sequence();
    check_size(pts, pts.size(), kMaxRegionPoints, "points");
    for (std::size_t i = 0; i < pts.size(); ++i) r.points.push_back(parse_vector(pts.item(i)));
    if (segment) {
      r.kind = Region::Kind::kSegment;
      if (r.points.size() != 2)
        pts.fail("a segment has exactly 2 points, got " + std::to_string(r.points.size()));
      if ((r.points[0] - r.points[1]).norm() == 0) pts.fail("degenerate segment: both ends coincide");
      return r;
    }
    r.kind = Region::Kind::kPolygon;
    if (r.points.size() < 3)
      pts.fail("a polygon needs at least 3 points, got " + std::to_string(r.points.size()));
    check_convex_planar(pts, r.points);
    return r;
  }

  void check_convex_planar(const Node& n, const std::vector<Vec3>& p) const {
    // Newell normal; planarity and convexity relative to the polygon's size.
    Vec3 normal = Vec3::Zero();
    const std::size_t k = p.size();
    for (std::size_t i = 0; i < k; ++i) normal += p[i].cross(p[(i + 1) % k]);
    double diameter = 0;
    for (const Vec3& a : p)
      for (const Vec3& b : p) diameter = std::max(diameter, (a - b).norm());
    if (normal.norm() <= 1e-12 * diameter * diameter) n.fail("degenerate polygon: zero area");
    normal.normalize();
    for (const Vec3& q : p)
      if (std::abs(normal.dot(q - p[0])) > kPolygonPlanarityTolerance * diameter)
        n.fail("the polygon's points do not lie in one plane");
    for (std::size_t i = 0; i < k; ++i) {
      const Vec3 turn = (p[(i + 1) % k] - p[i]).cross(p[(i + 2) % k] - p[(i + 1) % k]);
      if (normal.dot(turn) < -1e-12 * diameter * diameter)
        n.fail("the polygon is not convex (or its points are not in boundary order)");
    }
  }

  // Buckley §3.1.2 termination parameters: `position` (P_s) and `force` (F_s), each one item or a non-empty
  // list of items (their union).
  MotionTermination parse_termination(const Node& n) const {
    n.require_map({"position", "force"});
    // Present keys, null values included (a null is then reported as a bad value, not silently dropped).
    const auto child = [&](const char* key) { return Node(n.raw()[key], n.child_path(key), &file_); };
    const bool position = n.raw()["position"].IsDefined(), force = n.raw()["force"].IsDefined();
    if (!position && !force)
      n.fail("give position (a box of sensed positions), force (a cone of sensed force directions) or both");
    MotionTermination t;
    if (position)
      for_each_item(child("position"), [&](const Node& item) {
        item.require_map({"box"});
        t.position.push_back(parse_box(item.at("box"), {"min", "max"}));
      });
    if (force)
      for_each_item(child("force"), [&](const Node& item) {
        item.require_map({"direction", "angle"});
        ForceCone c;
        c.direction = parse_direction(item.at("direction"), "the force direction");
        c.angle = item.at("angle").number();
        // A circular cone wider than a half-space is not convex (models/friction_cone.h CircularCone); a zero
        // angle is a single direction, which no sensed force matches in practice.
        if (!(c.angle > 0) || c.angle > std::numbers::pi / 2)
          item.at("angle").fail("must be in (0, pi/2] (1.5708) radians, got " + format(c.angle));
        t.force.push_back(c);
      });
    return t;
  }
  // A mapping is one item; a list must be non-empty and holds items.
  template <typename F>
  static void for_each_item(const Node& n, F&& f) {
    if (!n.is_sequence()) return f(n);
    if (n.size() == 0) n.fail("the list is empty");
    for (std::size_t i = 0; i < n.size(); ++i) f(n.item(i));
  }

  void parse_motions(const Node& n, Task& task) const {
    if (!n.is_map()) n.fail("expected a mapping of motion names");
    check_size(n, n.size(), kMaxMotions, "motions");
    std::set<std::string> names;
    for (const auto& kv : n.raw()) {
      const std::string name = kv.first.as<std::string>();
      const Node m(kv.second, n.child_path(name), &file_);
      if (!names.insert(name).second) m.fail("duplicated motion name");
      m.require_map({"spring", "damper", "terminate", "edr"});
      const auto defined = [&](const char* key) { return m.is_map() && m.raw()[key].IsDefined(); };
      if (defined("spring") == defined("damper")) m.fail("a motion is exactly one of spring, damper");
      Motion motion;
      motion.name = name;
      if (m.has("spring")) {
        motion.kind = Motion::Kind::kSpring;
        motion.target = parse_vector(m.at("spring"));
      } else {
        motion.kind = Motion::Kind::kDamper;
        motion.target = parse_direction(m.at("damper"), "the commanded velocity direction");
      }
      if (defined("terminate"))
        motion.terminate = parse_termination(Node(m.raw()["terminate"], m.child_path("terminate"), &file_));
      if (defined("edr")) motion.edr_signal = parse_edr_signal(m.at("edr"));
      task.motions.push_back(motion);
    }
  }

  void parse_strategies(const Node& n, Task& task) const {
    if (!n.is_map()) n.fail("expected a mapping of strategy names");
    std::set<std::string> names;
    for (const auto& kv : n.raw()) {
      const std::string name = kv.first.as<std::string>();
      const Node s(kv.second, n.child_path(name), &file_);
      if (!names.insert(name).second) s.fail("duplicated strategy name");
      const Node list = s.sequence();
      if (list.size() == 0) s.fail("a strategy needs at least one motion");
      Strategy strategy;
      strategy.name = name;
      parse_strategy_list(list, task, strategy, -1, -1);
      for (const StrategyNode& node : strategy.nodes) strategy.motions.push_back(node.motion);
      task.strategies.push_back(strategy);
    }
  }

  // One list of a strategy (docs/task-format.md "strategies"): motion names, optionally ending in one
  // `branch:` item (Buckley §4.2 conditional test). Appends its nodes to strategy.nodes in file order (so
  // node ids are pre-order) and returns the first one's id, -1 for an empty list (a branch that stops).
  int parse_strategy_list(const Node& list, const Task& task, Strategy& strategy, int parent,
                          int parent_branch) const {
    int first = -1, previous = parent;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Node item = list.item(i);
      if (item.is_map()) {
        item.require_map({"branch"});
        if (previous < 0 || (i == 0 && parent_branch >= 0))
          item.fail("a branch tests the sensors after a motion: put a motion before it");
        if (i + 1 != list.size())
          list.item(i + 1).fail(
              "nothing may follow a branch in the same list (continue inside its branches)");
        parse_branch(item.at("branch"), task, strategy, previous);
        break;
      }
      const std::string motion = item.string();
      if (!task.find_motion(motion)) item.fail("unknown motion '" + motion + "'");
      StrategyNode node;
      node.motion = motion;
      node.parent = previous;
      node.branch = i == 0 ? parent_branch : -1;
      const int id = static_cast<int>(strategy.nodes.size());
      check_size(list.item(i), strategy.nodes.size() + 1, kMaxStrategyNodes, "motions in one strategy");
      strategy.nodes.push_back(node);
      if (i > 0) strategy.nodes[static_cast<std::size_t>(previous)].next = id;
      if (first < 0) first = id;
      previous = id;
    }
    return first;
  }

  void parse_branch(const Node& n, const Task& task, Strategy& strategy, int after) const {
    const Node list = n.list();
    bool has_test = false;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Node b = list.item(i);
      b.require_map({"when", "then", "else"});
      const bool otherwise = b.raw()["else"].IsDefined();
      StrategyBranch branch;
      branch.key = b.path();
      branch.otherwise = otherwise;
      if (otherwise) {
        if (b.raw()["when"].IsDefined() || b.raw()["then"].IsDefined())
          b.fail("an 'else' branch has no 'when' or 'then' (its list is the value of 'else')");
        if (i + 1 != list.size()) list.item(i + 1).fail("the 'else' branch must be the last one");
        if (!has_test) b.fail("a branch needs at least one 'when' test before 'else'");
      } else {
        if (!b.raw()["when"].IsDefined())
          b.fail("a branch is either {when: TEST, then: [...]} or {else: [...]}");
        if (!b.raw()["then"].IsDefined()) b.at("then");  // "missing required key"
        branch.when = parse_termination(Node(b.raw()["when"], b.child_path("when"), &file_));
        has_test = true;
      }
      const int index = static_cast<int>(strategy.nodes[static_cast<std::size_t>(after)].branches.size());
      strategy.nodes[static_cast<std::size_t>(after)].branches.push_back(branch);
      const Node body(b.raw()[otherwise ? "else" : "then"], b.child_path(otherwise ? "else" : "then"),
                      &file_);
      const int first = parse_strategy_list(body.sequence(), task, strategy, after, index);
      strategy.nodes[static_cast<std::size_t>(after)].branches[static_cast<std::size_t>(index)].first = first;
    }
  }

  std::string file_;
  int dimension_ = 3;
  const std::vector<double>* requested_values_ = nullptr;  // a slice's model values (nullptr: nominal)
  Task* model_ = nullptr;                                  // the task being read, once model_error is known
  bool affine_ = false;                                    // reading parts, bounds or goal
  ModelCoordinate::Role role_ = ModelCoordinate::Role::kNone;  // what the coordinates being read are
};

}  // namespace

Task parse_task_string(const std::string& yaml_text, const std::string& file_label,
                       const std::vector<double>* model_values) {
  const YAML::Node root = load_yaml_document(yaml_text, file_label);
  try {
    Task task = Parser(file_label, model_values).parse(root);
    if (!task.model_error.empty()) task.model_source = yaml_text;
    return task;
  } catch (const YAML::Exception& e) {
    throw TaskError(file_label, "", std::string("malformed YAML: ") + e.what());
  }
}

Task parse_task_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw TaskError(path.string(), "", "cannot open the file");
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  if (!ec && bytes > kMaxTaskFileBytes)
    throw TaskError(path.string(), "",
                    "the file has " + std::to_string(bytes) + " bytes, more than the " +
                        std::to_string(kMaxTaskFileBytes) + " accepted");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_task_string(buffer.str(), path.string());
}

Task task_at(const Task& task, const std::vector<double>& model_values) {
  if (task.model_error.empty()) {
    if (!model_values.empty())
      throw TaskError(task.source_file, "model_error", "the task has no model parameters");
    return task;
  }
  return parse_task_string(task.model_source, task.source_file, &model_values);
}

}  // namespace cmt
