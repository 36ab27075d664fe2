#include "experiments/validation/verify_json.h"

#include "experiments/common/point_json.h"

namespace cmt {

nlohmann::json pieces_json(const LoadedTask& task, const std::vector<ReachedPiece>& pieces) {
  const int dim = task.task.dimension;
  nlohmann::json out = nlohmann::json::array();
  for (const ReachedPiece& p : pieces) {
    nlohmann::json poly = nlohmann::json::array();
    for (const Vec3& q : p.polygon) poly.push_back(point_json(q, dim));
    nlohmann::json entry = {{"atom", p.atom},
                            {"name", task.cspace.atom_name(p.atom)},
                            {"kind", atom_kind_name(p.kind)},
                            {"polygon", poly}};
    if (!p.holes.empty()) {
      nlohmann::json holes = nlohmann::json::array();
      for (const auto& h : p.holes) {
        nlohmann::json hole = nlohmann::json::array();
        for (const Vec3& q : h) hole.push_back(point_json(q, dim));
        holes.push_back(hole);
      }
      entry["holes"] = holes;
    }
    if (p.kind == AtomKind::kFace && p.polygon.size() >= 3) entry["area"] = p.area;
    out.push_back(entry);
  }
  return out;
}

namespace {

// A spring motion's free-space rest ball (not an atom).
nlohmann::json free_piece_json(const LoadedTask& task, const VerifyStep& s) {
  return {{"atom", -1},
          {"name", "free"},
          {"kind", "free"},
          {"center", point_json(s.free_center, task.task.dimension)},
          {"radius", s.free_radius}};
}

}  // namespace

nlohmann::json verify_json(const LoadedTask& task, const VerifyResult& r, double seconds, bool with_reached) {
  nlohmann::json steps = nlohmann::json::array();
  for (const VerifyStep& s : r.steps) {
    nlohmann::json termination = pieces_json(task, s.termination.pieces());
    if (s.free_termination) termination.push_back(free_piece_json(task, s));
    steps.push_back({{"motion", s.motion},
                     {"termination", termination},
                     {"may_not_terminate", s.may_not_terminate},
                     {"fallback", s.fallback},
                     {"fixpoint_steps", s.fixpoint_steps},
                     {"widened_atoms", s.widened_atoms},
                     {"reached_area", s.reached_area}});
    if (with_reached && s.reached) steps.back()["reached"] = pieces_json(task, s.reached->pieces());
    // The part of `termination` due to the motion's termination sets (Buckley §4.5), when it has any.
    if (s.sensing) steps.back()["sensing_termination"] = pieces_json(task, s.sensing->pieces());
    // Conditional strategies (Buckley §4.2): where the step sits in the strategy tree and the test after it.
    nlohmann::json& j = steps.back();
    j["node"] = s.node;
    j["parent"] = s.parent;
    if (s.branch >= 0) j["branch"] = s.branch;
    if (!s.branches.empty()) {
      nlohmann::json branches = nlohmann::json::array();
      for (std::size_t i = 0; i < s.branches.size(); ++i)
        branches.push_back({{"branch", i},
                            {"reachable", !s.branches[i].start->empty()},
                            {"step", s.branches[i].step},
                            {"start", pieces_json(task, s.branches[i].start->pieces())}});
      j["branches"] = branches;
    }
    if (s.unmatched) j["unmatched"] = pieces_json(task, s.unmatched->pieces());
  }
  nlohmann::json out = {{"task", task.task.name},
                        {"reliable", r.reliable},
                        {"steps", steps},
                        {"seconds", seconds},
                        {"spring_model", spring_model_name(r.spring_model)},
                        {"stop_relative_speed", r.stop_relative_speed},
                        {"contact_lift", r.contact_lift},
                        {"servo_coast", r.servo_coast}};
  if (!r.reliable) {
    out["failed_step"] = r.failed_step;
    out["failure"] = r.failure;
    out["outside_goal"] = pieces_json(task, r.outside_goal);
    if (r.failed_step >= 0 && r.steps[r.failed_step].free_termination)
      out["outside_goal"].push_back(free_piece_json(task, r.steps[r.failed_step]));
  }
  return out;
}

}  // namespace cmt
