// Soundness of a prediction (experiments/validation/validation.h, docs/validation.md "Soundness"): every
// motion end of every stable rollout against the termination set the verifier predicted for that motion.
#include <algorithm>
#include <cmath>

#include "experiments/validation/validation.h"

namespace cmt {

double distance_to_prediction(const VerifyStep& step, const Vec3& p) {
  double d = step.termination.distance(p);
  if (step.free_termination) d = std::min(d, std::max(0.0, (p - step.free_center).norm() - step.free_radius));
  return d;
}

int prediction_step(const std::vector<VerifyStep>& steps, const MotionOutcome& motion, int position) {
  const int node = motion.node >= 0 ? motion.node : position;
  for (std::size_t k = 0; k < steps.size(); ++k)
    if ((steps[k].node >= 0 ? steps[k].node : static_cast<int>(k)) == node) return static_cast<int>(k);
  return -1;
}

int motion_key(const std::vector<VerifyStep>& steps, const MotionOutcome& motion, int position) {
  const int step = prediction_step(steps, motion, position);
  return step >= 0 ? step : static_cast<int>(steps.size()) + position;
}

void observe_rollout(const std::vector<VerifyStep>& steps, const RolloutOutcome& ro, std::uint64_t seed,
                     SampleMode mode, double tolerance, std::vector<ObservedEnd>* ends,
                     std::vector<ObservedEnd>* timeouts, std::vector<ObservedEnd>* unexpected_timeouts,
                     int* unpredicted) {
  for (std::size_t mi = 0; mi < ro.motions.size(); ++mi) {
    const MotionOutcome& m = ro.motions[mi];
    ObservedEnd e;
    e.rollout = ro.index;
    e.motion = motion_key(steps, m, static_cast<int>(mi));
    const int step_index = e.motion < static_cast<int>(steps.size()) ? e.motion : -1;
    e.motion_name = m.motion;
    e.end = m.end;
    e.atom = m.atom;
    e.termination = m.termination;
    e.seed = seed;
    e.mode = mode;
    const bool predicted = step_index >= 0;
    if (predicted) e.distance = distance_to_prediction(steps[static_cast<std::size_t>(step_index)], m.end);
    e.inside = predicted && e.distance <= tolerance;
    if (m.termination == Termination::kNone) {
      // Not a termination point. may_not_terminate = false says some reached atom can stick, not that every
      // motion stops; a time-out under it is still worth seeing.
      timeouts->push_back(e);
      if (predicted && !steps[static_cast<std::size_t>(step_index)].may_not_terminate)
        unexpected_timeouts->push_back(e);
      continue;
    }
    if (!predicted) {
      ++*unpredicted;  // the verifier stopped at an earlier failed step and predicted nothing for this one
      continue;
    }
    ends->push_back(e);
  }
}

void score_soundness(const LoadedTask& task, ValidationResult* r) {
  r->contact_tolerance = kContactRelativeTolerance * task.cspace.scale();
  r->ends.clear();
  r->timeouts.clear();
  r->unexpected_timeouts.clear();
  r->successes = r->unstable = r->unpredicted = r->outside = 0;
  for (const RolloutOutcome& ro : r->rollouts) {
    r->successes += ro.success;
    // A broken simulation says nothing about the physics the verifier models.
    if (ro.unstable) {
      ++r->unstable;
      continue;
    }
    observe_rollout(r->prediction.steps, ro, r->options.seed, r->options.mode, r->contact_tolerance, &r->ends,
                    &r->timeouts, &r->unexpected_timeouts, &r->unpredicted);
  }
  r->worst.clear();
  for (const ObservedEnd& e : r->ends)
    if (!e.inside) r->worst.push_back(e);
  r->outside = static_cast<int>(r->worst.size());
  r->soundness = r->ends.empty() ? 1.0 : static_cast<double>(r->ends.size() - r->outside) / r->ends.size();
  // Farthest first; ties keep rollout-major order, so the list depends on nothing but the results.
  std::stable_sort(r->worst.begin(), r->worst.end(),
                   [](const ObservedEnd& a, const ObservedEnd& b) { return a.distance > b.distance; });
  if (r->worst.size() > static_cast<std::size_t>(kMaxWorstEnds)) r->worst.resize(kMaxWorstEnds);
}

bool contradicts_verifier(const ValidationResult& r) {
  return r.outside > 0 || r.search.outside > 0 || r.soundness_bug ||
         (r.sticking && r.sticking->disagreements > 0);
}

}  // namespace cmt
