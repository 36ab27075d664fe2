// A loaded task: geometry, error bounds, start/goal regions, motions and strategies (docs/contracts.md "Task
// files"). Immutable once loaded; every length is in the task's own units.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "models/model_error.h"

namespace cmt {

using Vec3 = Eigen::Vector3d;

enum class LengthUnit { kInch, kMillimeter, kMeter };

// Metres per task length unit (MJCF scenes are written in metres).
double meters_per_unit(LengthUnit unit);
const char* unit_name(LengthUnit unit);

// Buckley §2.1 error bounds (L640-652). Lengths in task units, angles in radians.
struct Uncertainty {
  double eps_s = 0;    // position-sensing error: radius of the sensing ball
  double eps_p = 0;    // positioning error in free space
  double theta_v = 0;  // half-angle between commanded and actual velocity, [0, pi/2) (task_ranges.h)
  double theta_f = 0;  // force-direction sensing error
  double step = 0;     // spring interpolation step (defaults to eps_p)
};

struct AxisBox {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
};

// A convex part: a box or the convex hull of points. `vertices` always holds the points whose hull is the
// part (the 8 corners for a box). `key` is the YAML key path it was read from, for messages.
struct ConvexPart {
  enum class Shape { kBox, kConvex };
  Shape shape = Shape::kBox;
  AxisBox box;                 // valid for kBox
  std::vector<Vec3> vertices;  // hull points (box corners for kBox)
  double friction = 0;         // Coulomb coefficient (per-part override or the task default)
  std::string key;
};

// A start or goal region in configuration space (docs/contracts.md): a point, a segment, or a convex planar
// polygon.
struct Region {
  enum class Kind { kPoint, kSegment, kPolygon };
  Kind kind = Kind::kPoint;
  std::vector<Vec3> points;
  std::string key;
};

// A circular cone of sensed reaction-force directions: the force the environment applies to the robot (it
// points into free space, e.g. +z on a floor). `direction` is unit length after loading; 0 < angle <= pi/2.
struct ForceCone {
  Vec3 direction = Vec3::UnitZ();
  double angle = 0;
};

// Buckley §3.1.2 termination parameters of a motion (docs/task-format.md "terminate"): P_s, a union of axis
// boxes of sensed positions, and F_s, a union of cones of sensed force directions. Sticking (type 1) always
// applies; with P_s alone the motion also stops when in contact with the sensed position in P_s (type 2);
// with F_s when the sensed force direction is in F_s and, if P_s is given too, the sensed position in P_s
// (type 3). Empty lists: the condition is not given.
struct MotionTermination {
  std::vector<AxisBox> position;  // P_s, in configuration space (task units)
  std::vector<ForceCone> force;   // F_s
  bool any() const { return !position.empty() || !force.empty(); }
};

// Buckley §3.2-3.3: the generalized damper (commanded velocity direction, unit length after loading) and the
// generalized spring (commanded position in configuration space).
struct Motion {
  enum class Kind { kDamper, kSpring };
  std::string name;
  Kind kind = Kind::kDamper;
  Vec3 target = Vec3::Zero();   // damper: unit velocity direction; spring: commanded position
  MotionTermination terminate;  // optional sensing termination (types 2 and 3)
  // The EDR termination predicate (Donald 1987 §1.5, 1EDR l.1858-1881): once the motion stops, the robot
  // reports `success` when its sensed position and force are consistent with a termination in the goal of
  // some model-error slice, `failure` otherwise (docs/edr.md). `cmt verify --edr` and `cmt validate --edr`
  // read it from the strategy's last motion.
  bool edr_signal = false;
};

// One branch of a conditional test (Buckley §4.2, Fig 4.2): after a motion the robot checks whether its
// sensed position and sensed force are consistent with a node I_i and runs the first branch whose test
// passes. The test has the form of a motion's termination sets: the sensed position in one of `when.position`
// (if given) and the sensed force direction in one of `when.force` (if given). `otherwise` is the `else`
// branch, taken when no earlier test passed. `first` is the strategy node run next; -1 ends the strategy
// there.
struct StrategyBranch {
  MotionTermination when;
  bool otherwise = false;
  int first = -1;
  std::string key;  // YAML key path, for messages
};

// One commanded motion in a strategy's tree. Nodes are numbered in file order (pre-order), node 0 runs
// first; every node is reached along exactly one path (Buckley's strategy graphs are acyclic; a tree keeps
// each node's start set single).
struct StrategyNode {
  std::string motion;
  int parent = -1;  // the node run before this one, -1 for node 0
  int branch = -1;  // index of the parent's branch that leads here, -1 when it follows unconditionally
  int next = -1;    // the node that follows unconditionally, -1 for none
  std::vector<StrategyBranch> branches;  // the conditional test after this motion (then next == -1)
};

// A strategy (docs/contracts.md, docs/task-format.md "strategies"): a decision-free sequence of motions, or a
// tree with conditional branches (Buckley §4.2).
struct Strategy {
  std::string name;
  // Decision-free: the sequence. Conditional: every node's motion in node order (not an execution order).
  std::vector<std::string> motions;
  std::vector<StrategyNode> nodes;  // always set; a sequence is a chain of nodes linked by `next`
  bool conditional() const;
  // A decision-free strategy of `motions` (the nodes are the chain).
  static Strategy sequence(std::string name, std::vector<std::string> motions);
};

struct Task {
  std::string name;
  std::string description;
  std::string source_file;  // path the task was loaded from, for messages
  int dimension = 3;        // 2: planar task, [x, z] in the file, extruded along y
  LengthUnit units = LengthUnit::kMeter;
  double friction = 0;
  Uncertainty uncertainty;

  // Geometry form (a): physical parts; the robot translates and its frame origin is the reference point.
  std::vector<ConvexPart> robot;
  std::vector<ConvexPart> environment;
  // Geometry form (b): configuration-space obstacles directly (the robot is a point).
  std::vector<ConvexPart> cspace;
  bool physical() const { return !robot.empty(); }

  std::optional<AxisBox> bounds;
  // The task's own x, y and z axes in world coordinates (the columns; a signed permutation with det +1, the
  // world axes by default). The C-space is built in these axes (CSpace::build): the convex decomposition of
  // a non-convex face and the order of the atoms follow them, so a task turned together with its axes
  // (task_transform.h) has the turned C-space, atom for atom (docs/task-format.md "axes").
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Region start;
  std::vector<Region> goal;
  std::vector<Motion> motions;
  std::vector<Strategy> strategies;

  // Model error (models/model_error.h; empty without it): the geometry above is read at model_values (the
  // nominal values, or a slice's); model_coordinates holds every affine coordinate of the parts, the bounds
  // and the goal as read, and model_source the file's text, to read other slices (task_at).
  std::vector<ModelParameter> model_error;
  std::vector<double> model_values;
  std::vector<ModelCoordinate> model_coordinates;
  std::string model_source;

  const Motion* find_motion(const std::string& name) const;
  const Strategy* find_strategy(const std::string& name) const;
  // The strategy called `name`; throws TaskError(source_file, "strategies", ...) naming the known ones.
  const Strategy& strategy_named(const std::string& name) const;
  // The strategies' names, comma-separated, for messages.
  std::string strategy_names() const;
};

}  // namespace cmt
