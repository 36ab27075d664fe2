// The CLI's EDR verdict and its JSON (edr_verdict.h).
#include "experiments/edr/edr_verdict.h"

#include "experiments/validation/verifier_model.h"
#include "experiments/validation/verify_json.h"
#include "models/input_error.h"
#include "models/model_error.h"

namespace cmt {
namespace {

VerifyOptions slice_options(const LoadedTask& slice, const EdrVerdictRequest& r) {
  if (r.first_order) return VerifyOptions{};
  VerifyOptions o = rollout_verify_options(slice);
  if (r.contact_lift >= 0) o.contact_lift = r.contact_lift;
  if (r.servo_coast >= 0) o.servo_coast = r.servo_coast;
  if (r.stop_relative_speed >= 0) o.stop_relative_speed = r.stop_relative_speed;
  return o;
}

// The strategy's motions, checked: decision-free, and with `edr: true` on the last one when required.
const Strategy& checked_strategy(const Task& task, const EdrVerdictRequest& r) {
  const Strategy& strategy = task.strategy_named(r.strategy);
  if (strategy.conditional())
    throw InputError(r.file, "strategies." + r.strategy,
                     "a conditional strategy: the EDR verdict is for decision-free sequences (the EDR test "
                     "follows the last motion)");
  const Motion* last = task.find_motion(strategy.motions.back());
  if (r.require_signal && (last == nullptr || !last->edr_signal))
    throw InputError(r.file, "motions." + strategy.motions.back() + ".edr",
                     "the last motion of strategy '" + r.strategy +
                         "' carries no EDR termination predicate (add `edr: true`)");
  return strategy;
}

nlohmann::json parameters_json(const Task& task, int resolution) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t p = 0; p < task.model_error.size(); ++p) {
    const ModelParameter& m = task.model_error[p];
    out.push_back({{"name", m.name},
                   {"min", m.min},
                   {"max", m.max},
                   {"nominal", m.nominal},
                   {"discrete", m.discrete()},
                   {"critical", critical_values(task, p)},
                   {"values", slice_values(task, p, resolution)}});
  }
  return out;
}

nlohmann::json slice_json(const Task& task, const EdrSlice& s) {
  nlohmann::json params = nlohmann::json::object();
  for (std::size_t p = 0; p < task.model_error.size(); ++p) params[task.model_error[p].name] = s.values[p];
  const LoadedTask& slice = *s.task;
  nlohmann::json out = {{"params", params},
                        {"goal_empty", s.goal_empty},
                        {"terminates", s.terminates},
                        {"reliable", s.reliable},
                        {"distinguishable", s.distinguishable},
                        {"linked", s.linked},
                        {"contact_lift", s.options.contact_lift},
                        {"servo_coast", s.options.servo_coast}};
  if (!s.terminates) {
    out["termination_problem"] = s.termination_problem;
    return out;
  }
  if (!s.linked) out["linking_problem"] = s.linking_problem;
  out["forward"] = pieces_json(slice, s.reached->pieces());
  out["forward_area"] = s.reached->area();
  out["termination_area"] = s.termination->area();
  out["success"] = pieces_json(slice, s.success->pieces());
  out["success_area"] = s.success->area();
  out["failure"] = pieces_json(slice, s.failure_pieces);
  out["failure_area"] = s.failure_area;
  if (s.strong) {
    out["strong_preimage_area"] = s.strong->area();
    out["weak_preimage_area"] = s.weak->area();
    out["failure_sticking_area"] = s.failure_sticking_area;
  }
  return out;
}

nlohmann::json confusion_json(const EdrResult& r, const EdrConfusion& c) {
  return {{"success_slice", c.success_slice},
          {"failure_slice", c.failure_slice},
          {"success_piece", pieces_json(*r.slices[c.success_slice].task, {c.success_piece})[0]},
          {"failure_piece", pieces_json(*r.slices[c.failure_slice].task, {c.failure_piece})[0]},
          {"distance", c.distance},
          {"force_angle", c.force_angle}};
}

}  // namespace

EdrResult edr_verdict(const LoadedTask& task, const EdrVerdictRequest& request) {
  const Strategy& strategy = checked_strategy(task.task, request);
  std::vector<std::vector<double>> slices;
  try {
    slices = model_slices(task.task, request.resolution);
  } catch (const std::invalid_argument& e) {
    throw InputError(request.file, "--resolution", e.what());
  }
  EdrOptions options;
  options.verify = [request](const LoadedTask& slice) { return slice_options(slice, request); };
  options.backprojection_margin = [request](const LoadedTask& slice) {
    return slice_options(slice, request).contact_lift;
  };
  options.refine_depth = request.refine_depth;
  return verify_edr(task.task, strategy.motions, slices, options);
}

nlohmann::json edr_verdict_json(const Task& task, const EdrVerdictRequest& request, const EdrResult& r) {
  nlohmann::json slices = nlohmann::json::array(), confusions = nlohmann::json::array();
  for (const EdrSlice& s : r.slices) slices.push_back(slice_json(task, s));
  for (const EdrConfusion& c : r.confusions) confusions.push_back(confusion_json(r, c));
  auto swept_json = [&](const std::vector<SlicePiece>& pieces) {
    nlohmann::json out = nlohmann::json::array();
    for (const SlicePiece& p : pieces) {
      nlohmann::json piece = pieces_json(*r.slices[p.slice].task, {p.piece})[0];
      piece["slice"] = p.slice;
      out.push_back(piece);
    }
    return out;
  };
  return {{"task", task.name},
          {"strategy", request.strategy},
          {"motions", task.strategy_named(request.strategy).motions},
          {"resolution", request.resolution},
          {"refine_depth", r.refine_depth},
          {"model", request.first_order ? "first-order" : "rollouts"},
          {"parameters", parameters_json(task, request.resolution)},
          {"slices", slices},
          {"terminates", r.terminates},
          {"reaches_goal", r.reaches_goal},
          {"distinguishable", r.distinguishable},
          {"linked", r.linked},
          {"confusions", confusions},
          {"confusion_count", r.confusion_count},
          {"swept_success", swept_json(r.swept_success)},
          {"swept_failure", swept_json(r.swept_failure)},
          {"edr_reliable", r.edr_reliable},
          {"reason", r.reason}};
}

}  // namespace cmt
