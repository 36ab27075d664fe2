// The `cmt validate --json` object (experiments/validation/validation.h, docs/validation.md "Output").
#include <map>

#include "experiments/common/point_json.h"
#include "experiments/validation/validation.h"
#include "experiments/validation/verify_json.h"

namespace cmt {
namespace {

std::string atom_label(const LoadedTask& task, int atom) {
  return atom < 0 ? "free" : task.cspace.atom_name(atom);
}

nlohmann::json end_json(const LoadedTask& task, const ValidationResult& r, const ObservedEnd& e) {
  const std::string motion = !e.motion_name.empty() ? e.motion_name
                             : e.motion >= 0 && e.motion < static_cast<int>(r.prediction.steps.size())
                                 ? r.prediction.steps[static_cast<std::size_t>(e.motion)].motion
                                 : "";
  return {{"rollout", e.rollout},
          {"seed", e.seed},
          {"mode", sample_mode_name(e.mode)},
          {"motion_index", e.motion},
          {"motion", motion},
          {"end", point_json(e.end, task.task.dimension)},
          {"atom", e.atom},
          {"atom_name", atom_label(task, e.atom)},
          {"termination", termination_name(e.termination)},
          {"inside", e.inside},
          {"distance", e.distance}};  // +infinity (empty prediction) prints as null
}

nlohmann::json ends_json(const LoadedTask& task, const ValidationResult& r,
                         const std::vector<ObservedEnd>& ends) {
  nlohmann::json out = nlohmann::json::array();
  for (const ObservedEnd& e : ends) out.push_back(end_json(task, r, e));
  return out;
}

// Per atom: trials of each verifier class and how many stuck; must that slid and never that stuck disagree.
nlohmann::json sticking_table(const LoadedTask& task, const StickingCheckResult& s) {
  struct Row {
    AtomKind kind = AtomKind::kFace;
    int trials[3] = {0, 0, 0}, stuck[3] = {0, 0, 0};
  };
  std::map<int, Row> rows;
  for (const StickingTrialRecord& t : s.records) {
    Row& row = rows[t.atom];
    row.kind = t.kind;
    const int c = static_cast<int>(t.cls);
    ++row.trials[c];
    row.stuck[c] += t.stuck;
  }
  nlohmann::json out = nlohmann::json::array();
  for (const auto& [atom, row] : rows) {
    nlohmann::json entry = {
        {"atom", atom}, {"name", task.cspace.atom_name(atom)}, {"kind", atom_kind_name(row.kind)}};
    for (StickClass c : {StickClass::kMust, StickClass::kMay, StickClass::kNever}) {
      const int i = static_cast<int>(c);
      entry[stick_class_name(c)] = {{"trials", row.trials[i]}, {"stuck", row.stuck[i]}};
    }
    const int must = static_cast<int>(StickClass::kMust), never = static_cast<int>(StickClass::kNever);
    entry["disagreements"] = (row.trials[must] - row.stuck[must]) + row.stuck[never];
    out.push_back(entry);
  }
  return out;
}

}  // namespace

nlohmann::json counterexample_json(const LoadedTask& task, const Counterexample& cx) {
  const RolloutOutcome& o = cx.outcome;
  nlohmann::json motions = nlohmann::json::array();
  for (const MotionOutcome& m : o.motions)
    motions.push_back({{"motion", m.motion},
                       {"end", point_json(m.end, task.task.dimension)},
                       {"atom", m.atom},
                       {"atom_name", atom_label(task, m.atom)},
                       {"termination", termination_name(m.termination)},
                       {"node", m.node},
                       {"branch", m.branch}});
  return {{"seed", cx.seed},
          {"index", cx.index},
          {"mode", sample_mode_name(cx.mode)},
          {"how", cx.how},
          {"replay", cx.replay},
          {"success", o.success},
          {"unstable", o.unstable},
          {"start", point_json(o.start, task.task.dimension)},
          {"end", point_json(o.end, task.task.dimension)},
          {"atom", o.atom},
          {"atom_name", atom_label(task, o.atom)},
          {"termination", termination_name(o.termination)},
          {"motions", motions}};
}

nlohmann::json validation_json(const LoadedTask& task, const ValidationResult& r, bool with_ends) {
  const int n = static_cast<int>(r.rollouts.size());
  nlohmann::json steps = nlohmann::json::array();
  for (std::size_t i = 0; i < r.steps.size(); ++i) {
    const StepValidation& s = r.steps[i];
    const VerifyStep& v = r.prediction.steps[i];
    steps.push_back({{"motion", s.motion},
                     {"may_not_terminate", v.may_not_terminate},
                     {"free_termination", v.free_termination},
                     {"ends", s.ends},
                     {"outside", s.outside},
                     {"measure", s.measure},
                     {"predicted", s.predicted},
                     {"covered", s.covered},
                     {"coverage", s.coverage},
                     {"coverage_radius", s.radius}});
  }
  nlohmann::json j = {
      {"task", r.task},
      {"strategy", r.strategy},
      {"controller", controller_form_name(r.options.form)},
      {"verifier_model", verifier_model_json(r.verifier)},
      {"mode", sample_mode_name(r.options.mode)},
      {"seed", r.options.seed},
      {"threads", r.options.threads},
      {"reliable", r.prediction.reliable},
      {"verifier_timed_out", r.options.verifier_timed_out_after > 0},
      {"rollouts", n},
      {"successes", r.successes},
      {"failures", n - r.successes - r.unstable},
      {"unstable", r.unstable},
      {"ends_checked", r.ends.size()},
      {"outside", r.outside},
      {"soundness", r.soundness},
      {"coverage", r.coverage},
      {"coverage_radius", r.coverage_radius},
      {"coverage_constant", kCoverageConstant},
      {"contact_tolerance", r.contact_tolerance},
      {"timeouts", r.timeouts.size()},
      {"unexpected_timeouts", ends_json(task, r, r.unexpected_timeouts)},
      {"unpredicted", r.unpredicted},
      {"steps", steps},
      {"worst", ends_json(task, r, r.worst)},
      {"counterexample",
       r.counterexample ? counterexample_json(task, *r.counterexample) : nlohmann::json(nullptr)},
      {"soundness_bug", r.soundness_bug},
      {"contradicts_verifier", contradicts_verifier(r)},
      {"prediction", verify_json(task, r.prediction, r.verify_seconds)},
      {"seconds",
       {{"verify", r.verify_seconds},
        {"rollouts", r.rollout_seconds},
        {"search", r.search_seconds},
        {"sticking", r.sticking_seconds}}},
  };
  if (r.search.ran)
    j["search"] = {{"rollouts", r.search.rollouts},
                   {"outside", r.search.outside},
                   {"worst", ends_json(task, r, r.search.worst)},
                   {"note", r.search.note}};
  if (r.sticking) {
    nlohmann::json s = sticking_check_json(task, *r.sticking);
    s.erase("records");  // summarized per atom below; every trial is `cmt check-sticking`'s business
    s["per_atom"] = sticking_table(task, *r.sticking);
    j["sticking"] = s;
  }
  if (with_ends) j["ends"] = ends_json(task, r, r.ends);
  return j;
}

}  // namespace cmt
