#include "verifier/edr/edr_plan.h"

#include <Eigen/Geometry>
#include <cmath>

#include "models/model_error.h"

namespace cmt {
namespace {

Vec3 centroid(const std::vector<Region>& regions) {
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (const Region& r : regions)
    for (const Vec3& p : r.points) sum += p, ++n;
  return n > 0 ? Vec3(sum / n) : Vec3(Vec3::Zero());
}

// The mean of the termination pieces' vertex means over the slices: where the push-forward lies.
Vec3 push_forward_centroid(const EdrResult& r) {
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (const EdrSlice& s : r.slices) {
    if (!s.termination) continue;
    for (const ReachedPiece& p : s.termination->pieces()) {
      Vec3 mean = Vec3::Zero();
      for (const Vec3& q : p.polygon) mean += q;
      if (p.polygon.empty()) continue;
      sum += mean / static_cast<double>(p.polygon.size());
      ++n;
    }
  }
  return n > 0 ? Vec3(sum / n) : Vec3(Vec3::Zero());
}

std::vector<std::string> names(std::size_t count) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < count; ++i) out.push_back(edr_plan_motion_name(static_cast<int>(i)));
  return out;
}

class Search {
 public:
  Search(const Task& task, const TaskWithDampers& with_dampers, const EdrPlanOptions& options)
      : task_(task), with_dampers_(with_dampers), options_(options) {
    coarse_ = model_slices(task, options.coarse_resolution);
    fine_ = model_slices(task, options.fine_resolution);
    quick_ = options.edr;
    quick_.preimages = false;
  }

  bool exhausted() const { return plan_.verdicts >= options_.max_verdicts; }

  // The verdict of `directions` on the coarse slices (counted).
  EdrResult coarse(const std::vector<Vec3>& directions) {
    ++plan_.verdicts;
    return verify_edr(with_dampers_(directions), names(directions.size()), coarse_, quick_);
  }

  bool holds(const EdrResult& verdict) const {
    return verdict.edr_reliable && (!options_.guaranteed || guaranteed_where_goal_exists(verdict));
  }

  // True (and the plan set) when the coarse verdict holds and the fine one too.
  bool accept(const std::vector<Vec3>& directions, const EdrResult& coarse_verdict) {
    if (!holds(coarse_verdict)) return false;
    EdrResult fine = verify_edr(with_dampers_(directions), names(directions.size()), fine_, options_.edr);
    if (!holds(fine)) return false;
    plan_.found = true;
    plan_.directions = directions;
    plan_.verdict = std::move(fine);
    return true;
  }

  bool one_step(const Vec3& toward) {
    for (const Vec3& v : edr_candidate_directions(toward, options_.angle_step, options_.angle_steps)) {
      if (exhausted()) return false;
      if (accept({v}, coarse({v}))) return true;
    }
    return false;
  }

  bool two_steps(const Vec3& toward, const Vec3& goal) {
    for (const Vec3& v1 : edr_candidate_directions(toward, options_.angle_step, options_.angle_steps)) {
      if (exhausted()) return false;
      const EdrResult first = coarse({v1});
      if (!first.terminates) continue;
      const Vec3 next = goal - push_forward_centroid(first);
      if (next.norm() < 1e-12) continue;
      for (const Vec3& v2 :
           edr_candidate_directions(next.normalized(), options_.angle_step, options_.angle_steps)) {
        if (exhausted()) return false;
        if (accept({v1, v2}, coarse({v1, v2}))) return true;
      }
    }
    return false;
  }

  EdrPlan run() {
    const Vec3 goal = centroid(task_.goal), start = centroid({task_.start});
    const Vec3 toward = goal - start;
    if (toward.norm() < 1e-12) {
      plan_.reason = "the start's centroid is the goal's: no direction toward the goal";
      return plan_;
    }
    if (options_.min_motions <= 1 && one_step(toward.normalized())) return plan_;
    if (options_.max_motions >= 2 && two_steps(toward.normalized(), goal)) return plan_;
    plan_.reason =
        exhausted() ? "the search's budget of coarse verdicts ran out"
        : options_.guaranteed
            ? "no candidate is EDR-reliable and guaranteed where the goal exists on the coarse and "
              "the fine slices"
            : "no candidate is EDR-reliable on the coarse and the fine slices";
    return plan_;
  }

 private:
  const Task& task_;
  const TaskWithDampers& with_dampers_;
  EdrPlanOptions options_;
  std::vector<std::vector<double>> coarse_, fine_;
  EdrOptions quick_;
  EdrPlan plan_;
};

}  // namespace

bool guaranteed_where_goal_exists(const EdrResult& verdict) {
  for (const EdrSlice& s : verdict.slices)
    if (!s.goal_empty && !s.reliable) return false;
  return true;
}

std::string edr_plan_motion_name(int index) { return "edr_plan_" + std::to_string(index + 1); }

std::vector<Vec3> edr_candidate_directions(const Vec3& toward, double angle_step, int angle_steps) {
  Vec3 axis = toward.cross(Vec3::UnitZ());
  axis = axis.norm() > 1e-9 ? Vec3(axis.normalized()) : Vec3(Vec3::UnitY());
  std::vector<Vec3> out = {toward};
  for (int k = 1; k <= angle_steps; ++k)
    for (double sign : {1.0, -1.0}) out.push_back(Eigen::AngleAxisd(sign * k * angle_step, axis) * toward);
  return out;
}

EdrPlan plan_edr(const Task& task, const TaskWithDampers& with_dampers, const EdrPlanOptions& options) {
  return Search(task, with_dampers, options).run();
}

}  // namespace cmt
