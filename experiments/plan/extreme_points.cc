// Buckley §6.3.4's extreme-point experiment (extreme_points.h).
#include "experiments/plan/extreme_points.h"

#include <algorithm>
#include <stdexcept>

#include "controllers/random.h"
#include "experiments/common/point_json.h"
#include "experiments/validation/validation.h"

namespace cmt {
namespace {

// Two vertices closer than this fraction of the planner's domain diagonal are one (pieces share corners).
constexpr double kSameVertexRelative = 1e-9;

void add_unique(std::vector<Vec3>& points, const Vec3& p, double tolerance) {
  if (std::none_of(points.begin(), points.end(), [&](const Vec3& q) { return (q - p).norm() <= tolerance; }))
    points.push_back(p);
}

AxisBox vertex_box(const std::vector<Vec3>& vertices) {
  AxisBox box{vertices.front(), vertices.front()};
  for (const Vec3& v : vertices) {
    box.min = box.min.cwiseMin(v);
    box.max = box.max.cwiseMax(v);
  }
  return box;
}

AxisBox grown_box(const AxisBox& box, double distance) {
  const Vec3 d = Vec3::Constant(distance);
  return {box.min - d, box.max + d};
}

std::vector<HalfSpace> moved_out(std::vector<HalfSpace> halfspaces, double distance) {
  for (HalfSpace& h : halfspaces) h.offset += distance * h.normal.norm();
  return halfspaces;
}

// The half-spaces of the polyhedra the grown points are taken from: each piece's, or the degenerate box at
// the commanded point.
std::vector<std::vector<HalfSpace>> claimed_polyhedra(const PlannedMotionCell& cell) {
  std::vector<std::vector<HalfSpace>> out;
  if (cell.cells.empty()) {
    out.push_back(planner::box_halfspaces({cell.commanded, cell.commanded}));
    return out;
  }
  for (const planner::ConvexPiece& piece : cell.cells.pieces()) out.push_back(piece.halfspaces);
  return out;
}

bool strictly_inside(const std::vector<HalfSpace>& halfspaces, const Vec3& p, double tolerance) {
  return std::all_of(halfspaces.begin(), halfspaces.end(),
                     [&](const HalfSpace& h) { return h.normal.dot(p) - h.offset < -tolerance; });
}

// The planned task with `motion` commanded at `p`.
std::shared_ptr<const LoadedTask> commanded_at(const LoadedTask& planned, const std::string& motion,
                                               const Vec3& p) {
  auto copy = std::make_shared<LoadedTask>(planned);
  const auto it = std::find_if(copy->task.motions.begin(), copy->task.motions.end(),
                               [&](const Motion& m) { return m.name == motion; });
  if (it == copy->task.motions.end() || it->kind != Motion::Kind::kSpring)
    throw std::invalid_argument("extreme points: no spring motion " + motion + " in the planned task");
  it->target = p;
  return copy;
}

PointTrial run_point(const LoadedTask& planned, const std::string& strategy, const std::string& motion,
                     const Vec3& p, std::uint64_t seed, const ExtremePointOptions& options) {
  ValidateOptions v;
  v.n = options.rollouts;
  v.seed = seed;
  v.threads = options.threads;
  v.counterexample_budget = 0;  // the experiment counts outcomes at its points; no search around them
  const ValidationResult r = run_validation(commanded_at(planned, motion, p), strategy, v);
  PointTrial t;
  t.commanded = p;
  t.reliable = r.prediction.reliable;
  t.failure = r.prediction.failure;
  t.rollouts = static_cast<int>(r.rollouts.size());
  t.successes = r.successes;
  t.outside = r.outside;
  t.unstable = r.unstable;
  return t;
}

}  // namespace

std::vector<Vec3> cell_vertices(const PlannedMotionCell& cell) {
  if (cell.cells.empty()) return {cell.commanded};
  const double tolerance = kSameVertexRelative * cell.cells.diagonal();
  std::vector<Vec3> out;
  for (const planner::ConvexPiece& piece : cell.cells.pieces())
    for (const Vec3& v : piece.vertices) add_unique(out, v, tolerance);
  return out;
}

std::vector<Vec3> grown_vertices(const PlannedMotionCell& cell, double distance) {
  const std::vector<std::vector<HalfSpace>> polyhedra = claimed_polyhedra(cell);
  std::vector<std::vector<HalfSpace>> grown;
  for (const auto& halfspaces : polyhedra) grown.push_back(moved_out(halfspaces, distance));
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < grown.size(); ++i) {
    // Clipped to the piece's own box grown wide enough for the grown corners of all but very acute pieces
    // (a corner of angle theta moves out by distance / sin(theta / 2)); a small box keeps the clipping's
    // relative slack small.
    const AxisBox box = cell.cells.empty() ? AxisBox{cell.commanded, cell.commanded}
                                           : vertex_box(cell.cells.pieces()[i].vertices);
    const AxisBox wide = grown_box(box, 2 * distance + (box.max - box.min).norm());
    const double tolerance = kSameVertexRelative * (wide.max - wide.min).norm();
    const planner::CPositionSet piece = planner::CPositionSet::convex(grown[i], wide);
    for (const planner::ConvexPiece& p : piece.pieces())
      for (const Vec3& v : p.vertices) {
        bool covered = false;
        for (std::size_t j = 0; j < grown.size() && !covered; ++j)
          covered = j != i && strictly_inside(grown[j], v, tolerance);
        if (!covered) add_unique(out, v, tolerance);
      }
  }
  return out;
}

std::vector<MotionExtremes> run_extreme_points(std::shared_ptr<const LoadedTask> planned,
                                               const std::string& strategy,
                                               const std::vector<PlannedMotionCell>& cells,
                                               const ExtremePointOptions& options) {
  const double eps_p = planned->task.uncertainty.eps_p;
  std::uint64_t point = 0;  // the experiment's point counter, for the seeds
  const auto trial = [&](const PlannedMotionCell& cell, const Vec3& p) {
    return run_point(*planned, strategy, cell.motion, p, splitmix64(options.seed + point++), options);
  };
  std::vector<MotionExtremes> out;
  for (const PlannedMotionCell& cell : cells) {
    MotionExtremes m;
    m.motion = cell.motion;
    m.claims_cell = !cell.cells.empty();
    for (const Vec3& v : cell_vertices(cell)) m.vertices.push_back(trial(cell, v));
    for (double factor : options.grow) {
      GrownTrials g;
      g.factor = factor;
      for (const Vec3& v : grown_vertices(cell, factor * eps_p)) g.points.push_back(trial(cell, v));
      m.grown.push_back(std::move(g));
    }
    out.push_back(std::move(m));
  }
  return out;
}

namespace {

nlohmann::json trials_json(const LoadedTask& task, const std::vector<PointTrial>& trials) {
  nlohmann::json points = nlohmann::json::array();
  int rollouts = 0, successes = 0;
  for (const PointTrial& t : trials) {
    points.push_back({{"commanded", point_json(t.commanded, task.task.dimension)},
                      {"reliable", t.reliable},
                      {"failure", t.failure},
                      {"rollouts", t.rollouts},
                      {"successes", t.successes},
                      {"outside", t.outside},
                      {"unstable", t.unstable}});
    rollouts += t.rollouts;
    successes += t.successes;
  }
  return {{"points", points},
          {"rollouts", rollouts},
          {"successes", successes},
          {"rate", rollouts > 0 ? static_cast<double>(successes) / rollouts : 0.0}};
}

}  // namespace

bool vertices_all_succeed(const std::vector<MotionExtremes>& motions) {
  return std::all_of(motions.begin(), motions.end(), [](const MotionExtremes& m) {
    return std::all_of(m.vertices.begin(), m.vertices.end(),
                       [](const PointTrial& t) { return t.successes == t.rollouts && t.outside == 0; });
  });
}

nlohmann::json extreme_points_json(const LoadedTask& task, const std::vector<MotionExtremes>& motions,
                                   const ExtremePointOptions& options) {
  nlohmann::json list = nlohmann::json::array();
  for (const MotionExtremes& m : motions) {
    nlohmann::json grown = nlohmann::json::array();
    for (const GrownTrials& g : m.grown) {
      nlohmann::json entry = trials_json(task, g.points);
      entry["factor"] = g.factor;
      grown.push_back(entry);
    }
    list.push_back({{"motion", m.motion},
                    {"claims_cell", m.claims_cell},
                    {"vertices", trials_json(task, m.vertices)},
                    {"grown", grown}});
  }
  return {{"rollouts_per_point", options.rollouts},
          {"grow", options.grow},
          {"seed", options.seed},
          {"eps_p", task.task.uncertainty.eps_p},
          {"vertices_all_succeed", vertices_all_succeed(motions)},
          {"motions", list}};
}

}  // namespace cmt
