// The `cmt falsify --json` object (experiments/falsify/falsify.h, docs/falsify.md).
#include <cmath>

#include "experiments/common/point_json.h"
#include "experiments/falsify/falsify.h"
#include "experiments/validation/verify_json.h"

namespace cmt {
namespace {

nlohmann::json finite_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); }

nlohmann::json piece_json(const LoadedTask& task, const PieceCoverage& pc) {
  const int dim = task.task.dimension;
  nlohmann::json points = nlohmann::json::array();
  for (const Vec3& p : pc.piece.polygon) points.push_back(point_json(p, dim));
  return {{"step", pc.step},
          {"motion", pc.motion},
          {"atom", pc.piece.atom},
          {"atom_name", task.cspace.atom_name(pc.piece.atom)},
          {"kind", atom_kind_name(pc.piece.kind)},
          {"measure", pc.measure},
          {"points", points},
          {"reached", !pc.reached_by.empty()},
          {"reached_by", pc.reached_by.empty() ? nlohmann::json() : nlohmann::json(pc.reached_by)},
          {"searched", pc.searched},
          {"search_rollouts", pc.rollouts},
          {"closest_end", finite_or_null(pc.closest)}};
}

}  // namespace

nlohmann::json falsify_json(const LoadedTask& task, const FalsifyResult& r) {
  const int dim = task.task.dimension;
  nlohmann::json best = nlohmann::json::array();
  for (std::size_t k = 0; k < r.best_signed_distance.size(); ++k)
    best.push_back(
        {{"step", k},
         {"motion", r.prediction.steps[k].motion},
         {"best_signed_distance", finite_or_null(r.best_signed_distance[k])},
         {"best_distance_outside",
          std::max(0.0, std::isfinite(r.best_signed_distance[k]) ? r.best_signed_distance[k] : 0.0)}});
  nlohmann::json bugs = nlohmann::json::array();
  for (const FalsifyFinding& f : r.findings)
    bugs.push_back(
        {{"how", f.how},
         {"motion", f.motion.empty() ? nlohmann::json() : nlohmann::json(f.motion)},
         {"step", f.step},
         {"end", point_json(f.end, dim)},
         {"distance", f.distance},
         {"kind", f.motion.empty() ? "failed under a reliable verdict" : "end outside the prediction"},
         {"errors", f.errors.empty() ? nlohmann::json() : nlohmann::json(format_error_vector(f.errors))},
         {"replay", f.replay}});
  nlohmann::json pieces = nlohmann::json::array(), unreached = nlohmann::json::array();
  for (const PieceCoverage& pc : r.pieces) {
    pieces.push_back(piece_json(task, pc));
    if (pc.reached_by.empty()) unreached.push_back(piece_json(task, pc));
  }
  nlohmann::json gaps = nlohmann::json::array();
  int gaps_reached = 0;
  for (const CoverageGap& g : r.gaps) {
    gaps_reached += g.reached;
    gaps.push_back({{"step", g.step},
                    {"motion", g.motion},
                    {"point", point_json(g.point, dim)},
                    {"gap", g.gap},
                    {"closest_end", finite_or_null(g.closest)},
                    {"reached", g.reached},
                    {"radius", g.radius},
                    {"rollouts", g.rollouts}});
  }
  nlohmann::json search_ends = nlohmann::json::array();
  for (const SearchEnd& e : r.search_ends)
    search_ends.push_back(
        {{"how", e.how}, {"step", e.step}, {"end", point_json(e.end, dim)}, {"inside", e.inside}});
  nlohmann::json failure;  // null: none found
  if (r.first_failure)
    failure = {{"how", r.first_failure->how},
               {"end", point_json(r.first_failure->end, dim)},
               {"goal_distance", r.first_failure->distance},
               {"errors", r.first_failure->errors.empty()
                              ? nlohmann::json()
                              : nlohmann::json(format_error_vector(r.first_failure->errors))},
               {"replay", r.first_failure->replay}};
  return {{"task", r.task},
          {"strategy", r.strategy},
          {"reliable", r.prediction.reliable},
          {"controller", controller_form_name(r.options.form)},
          {"seed", r.options.seed},
          {"threads", r.options.threads},
          {"budget", r.options.budget},
          {"coverage_budget", r.options.coverage_budget},
          {"gap_budget", r.options.gap_budget},
          {"gap_rollouts", r.options.gap_rollouts},
          {"random_rollouts", r.options.random},
          {"random_mode", sample_mode_name(r.options.mode)},
          {"error_vector_length", r.dimension},
          {"switches", r.shape.switches},
          {"switch_horizon", r.shape.horizon},
          {"searches", r.searches},
          {"rollouts", r.rollouts},
          {"unstable", r.unstable},
          {"outside", r.outside},
          {"soundness_bugs", bugs},
          {"motions", best},
          {"best_errors", format_error_vector(r.best_errors)},
          {"coverage_before", r.coverage_before},
          {"coverage_after", r.coverage_after},
          {"coverage_radius", r.coverage_radius},
          {"pieces", pieces},
          {"unreached_pieces", unreached},
          {"gaps", gaps},
          {"gaps_reached", gaps_reached},
          {"search_ends", search_ends},
          {"failure_budget", r.options.failure_budget},
          {"failure_searched", r.failure_searched},
          {"failure_rollouts", r.failure_rollouts},
          {"failure_closest", finite_or_null(r.failure_closest)},
          {"failures", r.failures},
          {"first_failure", failure},
          {"false_alarm", r.false_alarm()},
          {"verify_seconds", r.verify_seconds},
          {"random_seconds", r.random_seconds},
          {"search_seconds", r.search_seconds},
          {"coverage_seconds", r.coverage_seconds},
          {"gap_seconds", r.gap_seconds},
          {"failure_seconds", r.failure_seconds}};
}

}  // namespace cmt
