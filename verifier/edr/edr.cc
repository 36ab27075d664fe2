#include "verifier/edr/edr.h"

#include <algorithm>
#include <cmath>

#include "models/task_error.h"
#include "verifier/atom_cone.h"
#include "verifier/backprojection.h"
#include "verifier/edr/distinguish.h"

namespace cmt {
namespace {

// Sweeps between adjacent slices are formed up to this many slices (the pairing is quadratic).
constexpr std::size_t kMaxSweptSlices = 2000;

// Why the motions may fail to terminate in a slice ("" when they terminate): EDR needs every motion to end.
std::string termination_failure(const VerifyResult& result, std::size_t motions) {
  for (const VerifyStep& step : result.steps) {
    if (step.may_not_terminate)
      return "motion '" + step.motion + "' may never terminate: no reached atom can stick";
    if (!step.slide_forever.empty()) return "motion '" + step.motion + "' may slide forever";
    if (step.fallback) return "motion '" + step.motion + "': the forward projection fell back to every atom";
    if (step.free_termination)
      return "motion '" + step.motion + "' may come to rest in free space (no contact to sense)";
  }
  if (result.steps.size() < motions) return result.failure;
  return "";
}

void add_preimages(const LoadedTask& task, const ReachedSet& goal, const Motion& motion,
                   const EdrOptions& options, EdrSlice* s) {
  if (motion.kind != Motion::Kind::kDamper) return;
  const AtomCones cones(task.cspace);
  const DamperBackprojection strong = backproject_damper(
      task, cones, goal, motion.target, s->options.stop_relative_speed, options.backprojection_margin(task));
  const WeakBackprojection weak = weak_backproject_damper(task, cones, goal, motion.target);
  s->strong = strong.strong.intersected(*s->reached);
  s->weak = weak.weak.intersected(*s->reached);
  s->failure_sticking_area =
      ReachedSet::from_pieces(task.cspace, s->failure_pieces).intersected(*s->weak).area();
}

// (d), Donald's linking condition (L0) at every link k of the sequence: the terminations of the first k
// motions that lie in G, G ∩ push_k, must lie in the strong preimage of G under the remaining motions, i.e.
// the rest run from there ends in G only (verify_strategy_from's goal containment).
void check_linking(const LoadedTask& task, const std::vector<std::string>& motions,
                   const VerifyResult& result, const ReachedSet& goal, EdrSlice* s) {
  for (std::size_t k = 1; k < motions.size() && k < result.steps.size(); ++k) {
    const ReachedSet attained = result.steps[k - 1].termination.intersected(goal);
    if (attained.empty()) continue;
    const std::vector<std::string> rest(motions.begin() + static_cast<std::ptrdiff_t>(k), motions.end());
    const VerifyResult from_goal =
        verify_strategy_from(task, Strategy::sequence("rest", rest), attained, s->options);
    if (from_goal.reliable) continue;
    s->linked = false;
    s->linking_problem = "motion '" + motions[k - 1] + "' may stop in the goal, and from there '" +
                         motions[k] + "'" + (rest.size() > 1 ? " and the rest" : "") +
                         " may not end in it (linking condition L0): " + from_goal.failure;
    return;
  }
}

std::string slice_text(const Task& task, const std::vector<double>& values) {
  std::string at;
  for (std::size_t p = 0; p < values.size(); ++p)
    at += (at.empty() ? "" : ", ") + task.model_error[p].name + " = " + std::to_string(values[p]);
  return at;
}

EdrSlice simulate_slice(const Task& task, const std::vector<std::string>& motions,
                        const std::vector<double>& values, const EdrOptions& options) {
  EdrSlice s;
  s.values = values;
  s.task = load_task_slice(task, values);
  const LoadedTask& slice = *s.task;
  const ReachedSet goal = ReachedSet::from_regions(slice, slice.task.goal, /*partial=*/true);
  s.goal_empty = goal.empty();
  s.options = options.verify(slice);
  const VerifyResult result = verify_motions(slice, motions, s.options);
  s.termination_problem = termination_failure(result, motions.size());
  s.terminates = s.termination_problem.empty();
  if (!s.terminates) return s;
  const VerifyStep& last = result.steps.back();
  s.reliable = result.reliable;
  s.reached = last.reached;
  s.termination = std::make_shared<const ReachedSet>(last.termination);
  s.success = std::make_shared<const ReachedSet>(last.termination.intersected(goal));
  s.failure_pieces = pieces_outside_goal(slice, last.termination);
  for (const ReachedPiece& p : s.failure_pieces) s.failure_area += p.area;
  if (options.preimages) add_preimages(slice, goal, *slice.task.find_motion(motions.back()), options, &s);
  check_linking(slice, motions, result, goal, &s);
  return s;
}

// A slice's errors name it (the geometry at those values, its start, its motions).
EdrSlice run_slice(const Task& task, const std::vector<std::string>& motions,
                   const std::vector<double>& values, const EdrOptions& options) {
  try {
    return simulate_slice(task, motions, values, options);
  } catch (const TaskError& e) {
    throw TaskError(e.file(), e.key(), "in the slice " + slice_text(task, values) + ": " + e.reason());
  }
}

// Pairs of slices that differ in exactly one parameter, at consecutive values of it among the slices'. Not
// along a discrete parameter: no world lies between its values.
std::vector<std::pair<int, int>> adjacent_slices(const Task& task, const std::vector<EdrSlice>& slices) {
  std::vector<std::pair<int, int>> out;
  if (slices.empty() || slices.size() > kMaxSweptSlices) return out;
  const std::size_t params = slices.front().values.size();
  for (std::size_t p = 0; p < params; ++p) {
    if (task.model_error.at(p).discrete()) continue;
    std::vector<double> values;
    for (const EdrSlice& s : slices) values.push_back(s.values[p]);
    std::sort(values.begin(), values.end());
    values.erase(std::unique(values.begin(), values.end()), values.end());
    auto rank = [&](double v) { return std::lower_bound(values.begin(), values.end(), v) - values.begin(); };
    for (std::size_t i = 0; i < slices.size(); ++i)
      for (std::size_t j = 0; j < slices.size(); ++j) {
        bool others_equal = true;
        for (std::size_t q = 0; q < params; ++q)
          others_equal = others_equal && (q == p || slices[i].values[q] == slices[j].values[q]);
        if (others_equal && rank(slices[j].values[p]) == rank(slices[i].values[p]) + 1)
          out.emplace_back(static_cast<int>(i), static_cast<int>(j));
      }
  }
  return out;
}

// Do the points lie in one plane (within tol)? Collinear and coincident points do.
bool coplanar(const std::vector<Vec3>& points, double tol) {
  const Vec3 n = plane_normal(points);
  if (n.isZero()) return true;
  for (const Vec3& q : points)
    if (std::abs(n.dot(q - points[0])) > tol) return false;
  return true;
}

// The area of a convex polygon (0 for fewer than 3 points).
double convex_area(const std::vector<Vec3>& polygon) {
  Vec3 sum = Vec3::Zero();
  for (std::size_t k = 0; k + 2 < polygon.size(); ++k)
    sum += (polygon[k + 1] - polygon[0]).cross(polygon[k + 2] - polygon[0]);
  return 0.5 * sum.norm();
}

// The sweep of two slices' pieces: per pair on the same atom and kind whose points are coplanar within tol,
// their convex hull (keeping the first piece's atom and kind; its area the hull's).
std::vector<ReachedPiece> sweep_hulls(const std::vector<ReachedPiece>& first,
                                      const std::vector<ReachedPiece>& second, double tol) {
  std::vector<ReachedPiece> out;
  for (const ReachedPiece& a : first)
    for (const ReachedPiece& b : second) {
      if (a.atom != b.atom || a.kind != b.kind) continue;
      std::vector<Vec3> points = a.polygon;
      points.insert(points.end(), b.polygon.begin(), b.polygon.end());
      if (points.empty() || !coplanar(points, tol)) continue;
      ReachedPiece hull = a;
      hull.polygon = convex_piece(ReachedPiece{a.atom, a.kind, points, {}, 0}).points;
      hull.holes.clear();
      hull.area = convex_area(hull.polygon);
      out.push_back(std::move(hull));
    }
  return out;
}

// The swept pieces between adjacent slices (EdrResult::swept_success): `pieces(i)` gives slice i's.
// A swept piece keeps slice i's index, C-space and the atom (whose friction cone it stands for).
template <class Pieces>
std::vector<SlicePiece> swept(const Task& task, const std::vector<EdrSlice>& slices, const Pieces& pieces) {
  std::vector<SlicePiece> out;
  for (const auto& [i, j] : adjacent_slices(task, slices)) {
    if (!slices[i].termination || !slices[j].termination) continue;
    const double tol = kGoalRelativeTolerance * slices[i].task->cspace.scale();
    for (ReachedPiece& hull : sweep_hulls(pieces(i), pieces(j), tol))
      out.push_back({&slices[i].task->cspace, i, std::move(hull)});
  }
  return out;
}

// Is every vertex of every piece of `pieces` within `tol` of one piece of `a` or `b` or of their sweep
// (sweep_hulls at `coplanar_tol`, as swept() forms it) on the same atom?
bool covered_by_sweep(const std::vector<ReachedPiece>& pieces, const std::vector<ReachedPiece>& a,
                      const std::vector<ReachedPiece>& b, double tol, double coplanar_tol) {
  std::vector<ReachedPiece> hulls = a;
  hulls.insert(hulls.end(), b.begin(), b.end());
  for (ReachedPiece& hull : sweep_hulls(a, b, coplanar_tol)) hulls.push_back(std::move(hull));
  std::vector<ConvexPiece> convex;
  for (const ReachedPiece& h : hulls) convex.push_back(convex_piece(h));
  for (const ReachedPiece& piece : pieces) {
    bool inside_one = false;
    for (std::size_t k = 0; k < hulls.size() && !inside_one; ++k) {
      if (hulls[k].atom != piece.atom || hulls[k].kind != piece.kind) continue;
      inside_one = std::all_of(piece.polygon.begin(), piece.polygon.end(),
                               [&](const Vec3& q) { return point_to_piece(q, convex[k]) <= tol; });
    }
    if (!inside_one) return false;
  }
  return true;
}

std::vector<ReachedPiece> success_pieces_of(const EdrSlice& s) {
  return s.success ? s.success->pieces() : std::vector<ReachedPiece>{};
}

// Does the midpoint slice m need to join the slices between a and b (EdrOptions::refine_depth)?
bool needs_midpoint(const EdrSlice& a, const EdrSlice& b, const EdrSlice& m) {
  if (a.goal_empty != b.goal_empty || !m.terminates) return true;
  if (!a.terminates || !b.terminates) return false;  // the verdict fails at a or b anyway
  // Within the predicate's contact slack of the sweep, which swept() forms at the goal tolerance.
  const double scale = m.task->cspace.scale();
  const double tol = kEdrContactRelativeSlack * scale, coplanar_tol = kGoalRelativeTolerance * scale;
  return !covered_by_sweep(success_pieces_of(m), success_pieces_of(a), success_pieces_of(b), tol,
                           coplanar_tol) ||
         !covered_by_sweep(m.failure_pieces, a.failure_pieces, b.failure_pieces, tol, coplanar_tol);
}

// Slicing-gap refinement (EdrOptions::refine_depth): bisects adjacent slices of the task's one continuous
// parameter where needs_midpoint says so, appending the midpoints to *slices (never past kMaxSweptSlices,
// where sweeps stop). Returns the depth applied: 0 for other tasks.
int refine_slices(const Task& task, const std::vector<std::string>& motions, const EdrOptions& options,
                  std::vector<EdrSlice>* slices) {
  if (options.refine_depth <= 0 || task.model_error.size() != 1 || task.model_error[0].discrete()) return 0;
  struct Gap {
    int a, b, depth;
  };
  std::vector<Gap> work;
  for (const auto& [i, j] : adjacent_slices(task, *slices)) work.push_back({i, j, 0});
  while (!work.empty()) {
    const Gap g = work.back();
    work.pop_back();
    if (g.depth >= options.refine_depth || slices->size() >= kMaxSweptSlices) continue;
    const double mid = 0.5 * ((*slices)[g.a].values[0] + (*slices)[g.b].values[0]);
    EdrSlice m = run_slice(task, motions, {mid}, options);
    if (!needs_midpoint((*slices)[g.a], (*slices)[g.b], m)) continue;
    slices->push_back(std::move(m));
    const int k = static_cast<int>(slices->size()) - 1;
    work.push_back({g.a, k, g.depth + 1});
    work.push_back({k, g.b, g.depth + 1});
  }
  std::stable_sort(slices->begin(), slices->end(),
                   [](const EdrSlice& x, const EdrSlice& y) { return x.values < y.values; });
  return options.refine_depth;
}

// (c): every termination in G against every point of H, over all pairs of slices and the sweeps between
// adjacent ones. Every pair is tested (the per-slice flags need them all); the first confusion_limit
// confusable pairs are listed.
void check_distinguishable(const Task& task, const EdrOptions& options, EdrResult* out) {
  std::vector<SlicePiece> success, failure;
  std::vector<std::vector<ReachedPiece>> success_pieces(out->slices.size());  // each slice's, made once
  double scale = 0;
  for (std::size_t i = 0; i < out->slices.size(); ++i) {
    const EdrSlice& s = out->slices[i];
    scale = std::max(scale, s.task->cspace.scale());
    if (!s.success) continue;
    success_pieces[i] = s.success->pieces();
    for (const ReachedPiece& p : success_pieces[i])
      success.push_back({&s.task->cspace, static_cast<int>(i), p});
    for (const ReachedPiece& p : s.failure_pieces)
      failure.push_back({&s.task->cspace, static_cast<int>(i), p});
  }
  out->swept_success =
      swept(task, out->slices, [&](int i) -> const std::vector<ReachedPiece>& { return success_pieces[i]; });
  out->swept_failure = swept(task, out->slices, [&](int i) -> const std::vector<ReachedPiece>& {
    return out->slices[i].failure_pieces;
  });
  success.insert(success.end(), out->swept_success.begin(), out->swept_success.end());
  failure.insert(failure.end(), out->swept_failure.begin(), out->swept_failure.end());
  const std::vector<Confusion> pairs = confusable_pairs(
      success, failure, task.uncertainty.eps_s, task.uncertainty.theta_f, kEdrPositionRelativeMargin * scale);
  out->distinguishable = pairs.empty();
  out->confusion_count = static_cast<int>(pairs.size());
  for (const Confusion& c : pairs) {
    out->slices[success[c.a].slice].distinguishable = false;
    out->slices[failure[c.b].slice].distinguishable = false;
    if (out->confusions.size() < options.confusion_limit)
      out->confusions.push_back({success[c.a].slice, failure[c.b].slice, success[c.a].piece,
                                 failure[c.b].piece, c.distance, c.force_angle});
  }
}

}  // namespace

EdrResult verify_edr(const Task& task, const std::vector<std::string>& motions,
                     const std::vector<std::vector<double>>& slices, const EdrOptions& options) {
  EdrResult out;
  for (const std::vector<double>& values : slices)
    out.slices.push_back(run_slice(task, motions, values, options));
  out.refine_depth = refine_slices(task, motions, options, &out.slices);
  for (const EdrSlice& s : out.slices) {
    out.terminates = out.terminates && s.terminates;
    out.reaches_goal = out.reaches_goal || (s.success && !s.success->empty());
  }
  if (!out.terminates) {
    out.reason = "the motions may not terminate in some slice";
    return out;
  }
  if (!out.reaches_goal) out.reason = "no slice's termination set meets the goal";
  check_distinguishable(task, options, &out);
  if (out.reaches_goal && !out.distinguishable)
    out.reason = "a termination in the goal is confusable with a failure termination (H)";
  for (const EdrSlice& s : out.slices)
    if (!s.linked && out.linked) {
      out.linked = false;
      if (out.reason.empty())
        out.reason = "in the slice " + slice_text(task, s.values) + ": " + s.linking_problem;
    }
  out.edr_reliable = out.reaches_goal && out.distinguishable && out.linked;
  return out;
}

}  // namespace cmt
