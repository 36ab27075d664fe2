// Adversarial rollouts (experiments/falsify/falsify.h): the random baseline, the falsification search, the
// coverage search and the gap search.
#include "experiments/falsify/falsify.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <sstream>

#include "experiments/falsify/robustness.h"
#include "experiments/validation/piece_geometry.h"
#include "sim/parallel_runs.h"

namespace cmt {
namespace {

constexpr double kNoScore = -std::numeric_limits<double>::infinity();

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// What every phase shares: the scene, the layout and the prediction prepared for scoring.
struct Context {
  const LoadedTask& task;
  const Strategy& strategy;
  const VerifyResult& prediction;
  const FalsifyOptions& options;
  std::shared_ptr<const RolloutScene> scene;
  ErrorVectorLayout layout;
  std::vector<PredictedStep> steps;
  double tolerance = 0;
};

struct Observed {
  std::vector<ObservedEnd> ends;
  bool unstable = false;
  bool failed = false;            // terminated everything, stable, and not at the goal
  Vec3 final_end = Vec3::Zero();  // where the rollout ended
};

Observed observe(const Context& c, const RolloutOutcome& ro) {
  Observed o;
  o.unstable = ro.unstable;
  o.failed = !ro.success && !ro.unstable;
  o.final_end = ro.end;
  if (ro.unstable) return o;
  std::vector<ObservedEnd> timeouts, unexpected;
  int unpredicted = 0;
  observe_rollout(c.prediction.steps, ro, c.options.seed, c.options.mode, c.tolerance, &o.ends, &timeouts,
                  &unexpected, &unpredicted);
  return o;
}

std::vector<RolloutOutcome> run_vectors(const Context& c, const std::vector<std::vector<double>>& xs,
                                        int first_index) {
  std::vector<RolloutOutcome> out(xs.size());
  parallel_runs(
      static_cast<int>(xs.size()), c.options.threads,
      [&] { return std::make_unique<RolloutRunner>(c.scene); },
      [&](RolloutRunner& runner, int i) {
        ScriptedErrors errors(c.task.task, c.layout, xs[static_cast<std::size_t>(i)]);
        out[static_cast<std::size_t>(i)] = runner.run(c.strategy, errors, first_index + i);
      });
  return out;
}

// A first-generation point (cross_entropy.h FirstDraw): with probability 1/2 uniform, else at the bounds'
// extremes as the extreme sampling mode draws them (controllers/error_model.h) and as Buckley's extreme
// trajectories need them (App. B: the velocity error constant, on the cone's rim, to one side): every angle
// number at its bound (planar: either sign), every offset on its sphere, no switch, the start on its
// region's boundary.
std::vector<double> extreme_or_uniform(const ErrorVectorLayout& layout, const Task& task, Rng& rng) {
  std::vector<double> x(static_cast<std::size_t>(layout.size()));
  for (double& v : x) v = uniform01(rng);
  if (uniform01(rng) < 0.5) return x;
  const bool planar = task.dimension == 2;
  const auto at = [&](int offset) { return x.begin() + offset; };
  const auto rim_angle = [&](int offset) {
    *at(offset + 2) = planar ? (uniform01(rng) < 0.5 ? 0.0 : 1.0) : 1.0;
  };
  const auto on_sphere = [&](int offset) {
    const Vec3 d = uniform_on_sphere(rng, planar);
    for (int i = 0; i < 3; ++i) *at(offset + i) = 0.5 * (d[i] + 1);
  };
  if (layout.start_size() == 2) {
    if (task.start.kind == Region::Kind::kSegment)
      x[0] = uniform01(rng) < 0.5 ? 0.0 : 1.0;
    else
      x[1] = 1;
  }
  const ErrorVectorShape& shape = layout.shape();
  for (int node = 0; node < layout.nodes(); ++node) {
    const int block = layout.motion_offset(node);
    rim_angle(block + ErrorVectorLayout::kForce);
    on_sphere(block + ErrorVectorLayout::kSensing);
    for (int k = 0; k <= shape.switches; ++k) {
      const int segment = block + ErrorVectorLayout::kVelocity + 3 * k;
      if (k > 0)
        std::copy(at(segment - 3), at(segment), at(segment));  // the same error throughout
      else
        rim_angle(segment);
    }
    std::fill(at(block + layout.switch_times_offset()), at(block + layout.via_offset()), 1.0);
    for (int k = 0; k < shape.via_points; ++k) on_sphere(block + layout.via_offset() + 3 * k);
    if (layout.reading_offset(node) >= 0) {
      on_sphere(layout.reading_offset(node));
      rim_angle(layout.reading_offset(node) + 3);
    }
  }
  return x;
}

FirstDraw first_draw(const Context& c) {
  return [&c](Rng& rng) { return extreme_or_uniform(c.layout, c.task.task, rng); };
}

// The command that replays a rollout: by its error vector, or by seed and index for a random one.
std::string replay_of(const Context& c, const RolloutOutcome& ro, const std::vector<double>& errors) {
  return errors.empty() ? replay_command(c.task, c.strategy.name, c.options.seed, ro.index, c.options.mode,
                                         c.options.form)
                        : error_replay_command(c.task, c.strategy.name, errors, c.options.form);
}

// Records the ends outside (and, under a reliable verdict, a failed rollout) as findings.
void collect_findings(const Context& c, const RolloutOutcome& ro, const Observed& o, const std::string& how,
                      const std::vector<double>& errors, FalsifyResult* r) {
  for (const ObservedEnd& e : o.ends)
    if (!e.inside) {
      ++r->outside;
      r->findings.push_back(
          {how, e.motion_name, e.motion, e.end, e.distance, errors, replay_of(c, ro, errors)});
    }
  if (c.prediction.reliable && o.failed &&
      std::all_of(o.ends.begin(), o.ends.end(), [](const ObservedEnd& e) { return e.inside; }))
    r->findings.push_back(
        {how, "", -1, ro.end, c.scene->goal_distance(ro.end), errors, replay_of(c, ro, errors)});
}

// Counts a stable failed rollout and keeps the first as the failure found.
void count_failure(const Context& c, const RolloutOutcome& ro, const Observed& o, const std::string& how,
                   const std::vector<double>& errors, FalsifyResult* r) {
  if (!o.failed) return;
  ++r->failures;
  if (!r->first_failure)
    r->first_failure =
        FalsifyFinding{how, "", -1, ro.end, c.scene->goal_distance(ro.end), errors, replay_of(c, ro, errors)};
}

// The falsification score of a rollout: its ends' largest signed distance.
double falsify_score(const Context& c, const Observed& o, std::vector<double>* best_per_step) {
  if (o.unstable) return kNoScore;
  double score = kNoScore;
  for (const ObservedEnd& e : o.ends) {
    const double s =
        signed_distance(c.task.cspace, c.steps[static_cast<std::size_t>(e.motion)], e.end, c.tolerance);
    double& best = (*best_per_step)[static_cast<std::size_t>(e.motion)];
    best = std::max(best, s);
    score = std::max(score, s);
  }
  return score;
}

// A search's batch score: runs the vectors, records unstable rollouts and findings (as `how`), scores each
// rollout with `score_one` and appends the rollouts to `all`.
BatchScore batch_score(const Context& c, const std::string& how, std::vector<RolloutOutcome>* all,
                       FalsifyResult* r, const std::function<double(const Observed&)>& score_one) {
  return [&c, how, all, r, score_one](const std::vector<std::vector<double>>& xs) {
    std::vector<RolloutOutcome> outs = run_vectors(c, xs, static_cast<int>(all->size()));
    std::vector<double> scores;
    for (std::size_t i = 0; i < outs.size(); ++i) {
      const Observed o = observe(c, outs[i]);
      r->unstable += o.unstable;
      collect_findings(c, outs[i], o, how, xs[i], r);
      count_failure(c, outs[i], o, how, xs[i], r);
      for (const ObservedEnd& e : o.ends)
        if (e.motion < static_cast<int>(c.steps.size()))
          r->search_ends.push_back({how, e.motion, e.end, e.inside});
      scores.push_back(score_one(o));
      all->push_back(std::move(outs[i]));
    }
    return scores;
  };
}

void falsification_search(const Context& c, std::vector<RolloutOutcome>* all, FalsifyResult* r) {
  const BatchScore score = batch_score(
      c, "falsify", all, r, [&](const Observed& o) { return falsify_score(c, o, &r->best_signed_distance); });
  const CrossEntropyResult cem = cross_entropy_maximize(c.layout.size(), c.options.budget,
                                                        splitmix64(c.options.seed ^ 0x46616c7369667900ULL),
                                                        c.options.search, score, {}, first_draw(c));
  r->searches += cem.searches;
  r->rollouts += cem.evaluations;
  r->best_errors = cem.best.x;
}

// The pieces of a step's termination set that carry its measure (as validation_coverage.cc's cover_step).
std::vector<PieceCoverage> measured_pieces(const Context& c) {
  std::vector<PieceCoverage> out;
  for (std::size_t k = 0; k < c.steps.size(); ++k) {
    const std::vector<ReachedPiece>& pieces = c.steps[k].pieces;
    const auto has = [&](auto pred) { return std::any_of(pieces.begin(), pieces.end(), pred); };
    const bool area =
        has([](const ReachedPiece& p) { return p.kind == AtomKind::kFace && p.polygon.size() >= 3; });
    const bool length = has([](const ReachedPiece& p) { return p.polygon.size() == 2; });
    for (const ReachedPiece& p : pieces) {
      const bool is_area = p.kind == AtomKind::kFace && p.polygon.size() >= 3;
      const bool is_length = !is_area && p.polygon.size() == 2;
      if (area ? !is_area : length ? !is_length : p.polygon.size() != 1) continue;
      PieceCoverage pc;
      pc.step = static_cast<int>(k);
      pc.motion = c.steps[k].step->motion;
      pc.piece = p;
      pc.measure = is_area ? p.area : is_length ? (p.polygon[1] - p.polygon[0]).norm() : 0;
      pc.closest = std::numeric_limits<double>::infinity();
      out.push_back(std::move(pc));
    }
  }
  return out;
}

// Marks the pieces an end of `rollouts` lies in, as reached by `how`; keeps each piece's closest end.
void mark_reached(const Context& c, std::span<const RolloutOutcome> rollouts, const std::string& how,
                  std::vector<PieceCoverage>* pieces) {
  for (const RolloutOutcome& ro : rollouts) {
    const Observed o = observe(c, ro);
    for (const ObservedEnd& e : o.ends)
      for (PieceCoverage& pc : *pieces) {
        if (pc.step != e.motion) continue;
        const double d = distance_to_piece(c.task.cspace, pc.piece, e.end);
        pc.closest = std::min(pc.closest, d);
        if (pc.reached_by.empty() && d <= c.tolerance) pc.reached_by = how;
      }
  }
}

void coverage_search(const Context& c, std::vector<RolloutOutcome>* all, FalsifyResult* r) {
  std::vector<PieceCoverage*> targets;
  for (PieceCoverage& pc : r->pieces)
    if (pc.reached_by.empty()) targets.push_back(&pc);
  std::stable_sort(targets.begin(), targets.end(),
                   [](const PieceCoverage* a, const PieceCoverage* b) { return a->measure > b->measure; });
  if (targets.size() > static_cast<std::size_t>(kMaxCoverageTargets)) targets.resize(kMaxCoverageTargets);
  if (targets.empty() || c.options.coverage_budget <= 0) return;
  const int per_target =
      std::max(c.options.search.population, c.options.coverage_budget / static_cast<int>(targets.size()));
  int spent = 0;
  for (std::size_t t = 0; t < targets.size() && spent < c.options.coverage_budget; ++t) {
    PieceCoverage& pc = *targets[t];
    if (!pc.reached_by.empty()) continue;  // reached meanwhile, by an earlier target's search
    pc.searched = true;
    const int budget = std::min(per_target, c.options.coverage_budget - spent);
    const std::size_t first = all->size();
    const BatchScore score = batch_score(c, "coverage", all, r, [&](const Observed& o) {
      double s = kNoScore;
      for (const ObservedEnd& e : o.ends)
        if (e.motion == pc.step) s = std::max(s, -distance_to_piece(c.task.cspace, pc.piece, e.end));
      return s;
    });
    const GenerationDone reached = [&](const std::vector<CrossEntropyCandidate>& gen) {
      return std::any_of(gen.begin(), gen.end(),
                         [&](const CrossEntropyCandidate& x) { return -x.score <= c.tolerance; });
    };
    const CrossEntropyResult cem = cross_entropy_maximize(
        c.layout.size(), budget, splitmix64(c.options.seed ^ (0x436f766572000000ULL + t)), c.options.search,
        score, reached, first_draw(c));
    r->searches += cem.searches;
    r->rollouts += cem.evaluations;
    pc.rollouts = cem.evaluations;
    spent += cem.evaluations;
    mark_reached(c, std::span<const RolloutOutcome>(*all).subspan(first), "coverage", &r->pieces);
  }
}

// The failure search (an unreliable verdict, docs/falsify.md "False alarms"): one cross-entropy search
// (with restarts) maximizing minus the final end's miss distance, a failed rollout scoring above every
// distance and ending the search. Where the verifier named no place of failure every stable rollout scores
// alike, and the search is a random one of extreme and uniform draws.
void failure_search(const Context& c, std::vector<RolloutOutcome>* all, FalsifyResult* r) {
  if (c.prediction.reliable || c.options.failure_budget <= 0) return;
  constexpr double kFailed = 1;  // above every -distance
  const BatchScore score = batch_score(c, "failure", all, r, [&](const Observed& o) {
    if (o.failed) return kFailed;
    if (o.unstable) return kNoScore;
    const double d = distance_to_failure(c.task.cspace, c.prediction, o.final_end);
    r->failure_closest = std::min(r->failure_closest, d);
    return std::isfinite(d) ? -d : std::numeric_limits<double>::lowest();
  });
  const GenerationDone failed = [](const std::vector<CrossEntropyCandidate>& gen) {
    return std::any_of(gen.begin(), gen.end(),
                       [](const CrossEntropyCandidate& x) { return x.score >= kFailed; });
  };
  const CrossEntropyResult cem = cross_entropy_maximize(c.layout.size(), c.options.failure_budget,
                                                        splitmix64(c.options.seed ^ 0x4661696c00000000ULL),
                                                        c.options.search, score, failed, first_draw(c));
  r->searches += cem.searches;
  r->rollouts += cem.evaluations;
  r->failure_rollouts = cem.evaluations;
  r->failure_searched = true;
}

// The gap search's view of one motion's coverage: its lattice at the baseline's radius and each lattice
// point's distance from the nearest end so far (kept as ends arrive: one pass over the lattice per end).
struct LatticeGaps {
  CoverageLattice lattice;
  double radius = 0;
  std::vector<double> nearest;

  void add_end(const Vec3& end) {
    for (std::size_t i = 0; i < lattice.points.size(); ++i)
      nearest[i] = std::min(nearest[i], (lattice.points[i] - end).norm());
  }
};

void add_ends(const Context& c, std::span<const RolloutOutcome> rollouts, std::vector<LatticeGaps>* steps) {
  for (const RolloutOutcome& ro : rollouts)
    for (const ObservedEnd& e : observe(c, ro).ends)
      if (e.motion >= 0 && static_cast<std::size_t>(e.motion) < steps->size())
        (*steps)[static_cast<std::size_t>(e.motion)].add_end(coverage_position(c.task, e.end));
}

// Around a target its search did not reach, the points its search came no closer to than the target itself
// are taken as out of reach: within the closest end's distance less the radius (at least the radius). A
// search-order heuristic only: coverage is scored on every point all the same.
double skip_radius(const CoverageGap& unreached, double radius) {
  // A search with no end of its motion (every rollout unstable, say) tells nothing about the points nearby.
  if (!std::isfinite(unreached.closest)) return radius;
  return std::max(radius, unreached.closest - radius);
}

// The uncovered lattice point farthest from every end of its motion, in units of its motion's radius,
// skipping points near a target no search reached (skip_radius); nullopt when every point is covered (or
// skipped).
std::optional<CoverageGap> farthest_gap(const Context& c, const std::vector<LatticeGaps>& steps,
                                        const std::vector<CoverageGap>& unreached) {
  std::optional<CoverageGap> best;
  double best_in_radii = 0;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const LatticeGaps& s = steps[k];
    for (std::size_t i = 0; i < s.lattice.points.size(); ++i) {
      const Vec3& q = s.lattice.points[i];
      const double in_radii = s.nearest[i] / s.radius;
      if (in_radii <= 1 || (best && in_radii <= best_in_radii)) continue;
      if (std::any_of(unreached.begin(), unreached.end(), [&](const CoverageGap& g) {
            return g.step == static_cast<int>(k) && (g.point - q).norm() <= skip_radius(g, s.radius);
          }))
        continue;
      best = CoverageGap{static_cast<int>(k), c.prediction.steps[k].motion, q, s.nearest[i], s.nearest[i]};
      best_in_radii = in_radii;
    }
  }
  return best;
}

void gap_search(const Context& c, const std::vector<StepValidation>& radii,
                std::span<const RolloutOutcome> random, std::vector<RolloutOutcome>* all, FalsifyResult* r) {
  if (c.options.gap_budget <= 0) return;
  // Coverage pools the motions with the strategy's highest-dimensional measure (score_coverage): only their
  // gaps count.
  std::string pooled = "none";
  for (const char* m : {"points", "length", "area"})
    for (const StepValidation& v : radii)
      if (v.measure == m) pooled = m;
  std::vector<LatticeGaps> steps(c.prediction.steps.size());
  for (std::size_t k = 0; k < steps.size(); ++k) {
    LatticeGaps& s = steps[k];
    s.lattice = coverage_lattice(c.task, c.prediction.steps[k]);
    // Points carry no radius of their own (the piece search covers them); a motion no baseline end measured
    // has no radius either.
    if (s.lattice.measure != pooled || pooled == "points" || k >= radii.size() || !(radii[k].radius > 0))
      s.lattice.points.clear();
    s.radius = k < radii.size() ? radii[k].radius : 0;
    s.nearest.assign(s.lattice.points.size(), std::numeric_limits<double>::infinity());
  }
  add_ends(c, random, &steps);
  add_ends(c, *all, &steps);
  std::vector<CoverageGap> unreached;
  int spent = 0;
  for (std::uint64_t t = 0; spent < c.options.gap_budget; ++t) {
    std::optional<CoverageGap> gap = farthest_gap(c, steps, unreached);
    if (!gap) break;
    const double radius = steps[static_cast<std::size_t>(gap->step)].radius;
    const std::size_t first = all->size();
    const BatchScore score = batch_score(c, "gap", all, r, [&](const Observed& o) {
      double s = kNoScore;
      for (const ObservedEnd& e : o.ends)
        if (e.motion == gap->step) s = std::max(s, -(coverage_position(c.task, e.end) - gap->point).norm());
      return s;
    });
    const GenerationDone covered = [&](const std::vector<CrossEntropyCandidate>& gen) {
      return std::any_of(gen.begin(), gen.end(),
                         [&](const CrossEntropyCandidate& x) { return -x.score <= radius; });
    };
    const int budget = std::min(c.options.gap_rollouts, c.options.gap_budget - spent);
    const CrossEntropyResult cem = cross_entropy_maximize(
        c.layout.size(), budget, splitmix64(c.options.seed ^ (0x4761700000000000ULL + t)), c.options.search,
        score, covered, first_draw(c));
    r->searches += cem.searches;
    r->rollouts += cem.evaluations;
    spent += cem.evaluations;
    gap->rollouts = cem.evaluations;
    gap->closest = std::isfinite(cem.best.score) ? -cem.best.score : std::numeric_limits<double>::infinity();
    gap->reached = gap->closest <= radius;
    gap->radius = radius;
    const std::span<const RolloutOutcome> added = std::span<const RolloutOutcome>(*all).subspan(first);
    add_ends(c, added, &steps);
    mark_reached(c, added, "gap", &r->pieces);
    if (!gap->reached) unreached.push_back(*gap);
    r->gaps.push_back(std::move(*gap));
  }
}

// Coverage as `cmt validate` scores it, over `rollouts`; with `radii`, at those radii per step.
ValidationResult validation_coverage(const LoadedTask& task, const VerifyResult& prediction,
                                     const FalsifyOptions& options,
                                     const std::vector<RolloutOutcome>& rollouts,
                                     const std::vector<StepValidation>& radii = {}) {
  ValidationResult v;
  v.prediction = prediction;
  v.options.seed = options.seed;
  v.options.mode = options.mode;
  v.rollouts = rollouts;
  score_soundness(task, &v);
  score_coverage(task, &v, radii);
  return v;
}

}  // namespace

std::string error_replay_command(const LoadedTask& task, const std::string& strategy,
                                 const std::vector<double>& errors, ControllerForm form) {
  std::ostringstream os;
  os << "cmt rollout " << task.task.source_file << " --strategy " << strategy << " --errors "
     << format_error_vector(errors);
  if (form != ControllerForm::kAdmittance) os << " --controller " << controller_form_name(form);
  return os.str();
}

namespace {

// run_falsify with the random rollouts run here (`baseline` null) or given.
FalsifyResult falsify_with(std::shared_ptr<const LoadedTask> task, const Strategy& strategy,
                           const VerifyResult& prediction, const FalsifyOptions& options,
                           const std::vector<RolloutOutcome>* baseline) {
  FalsifyResult r;
  r.task = task->task.name;
  r.strategy = strategy.name;
  r.options = options;
  r.options.threads = std::max(1, options.threads);
  r.prediction = prediction;
  SimOptions sim;
  sim.form = options.form;
  sim.mode = options.mode;
  r.shape = default_error_shape(options.form == ControllerForm::kPosition, sim.damper_speed_per_scale);
  r.shape.switches = options.switches;
  Context c{*task,
            strategy,
            r.prediction,
            r.options,
            RolloutScene::build(task, sim),
            ErrorVectorLayout(task->task, strategy, r.shape),
            predicted_steps(r.prediction),
            kContactRelativeTolerance * task->cspace.scale()};
  r.dimension = c.layout.size();

  auto start = std::chrono::steady_clock::now();
  std::vector<RolloutOutcome> own;
  if (baseline == nullptr) {
    if (options.random > 0)
      own = run_rollouts(c.scene, strategy, options.random, options.seed, r.options.threads);
    for (const RolloutOutcome& ro : own) {
      const Observed o = observe(c, ro);
      collect_findings(c, ro, o, "random", {}, &r);
      count_failure(c, ro, o, "random", {}, &r);
    }
  } else {
    for (const RolloutOutcome& ro : *baseline) count_failure(c, ro, observe(c, ro), "random", {}, &r);
    r.options.random = static_cast<int>(baseline->size());  // already scored by the caller: no findings
  }
  const std::vector<RolloutOutcome>& random = baseline == nullptr ? own : *baseline;
  r.random_seconds = baseline == nullptr ? seconds_since(start) : 0;

  start = std::chrono::steady_clock::now();
  std::vector<RolloutOutcome> searched;
  r.best_signed_distance.assign(r.prediction.steps.size(), kNoScore);
  if (options.budget > 0) falsification_search(c, &searched, &r);
  r.search_seconds = seconds_since(start);

  start = std::chrono::steady_clock::now();
  r.pieces = measured_pieces(c);
  mark_reached(c, random, "random", &r.pieces);
  mark_reached(c, searched, "falsify", &r.pieces);
  coverage_search(c, &searched, &r);
  // After: every rollout, at the random baseline's radii (a radius from the larger sample would be smaller
  // and could lower the coverage of a superset of ends).
  const ValidationResult before = validation_coverage(*task, r.prediction, options, random);
  r.coverage_before = before.coverage;
  r.coverage_radius = before.coverage_radius;
  r.coverage_seconds = seconds_since(start);

  start = std::chrono::steady_clock::now();
  failure_search(c, &searched, &r);
  r.failure_seconds = seconds_since(start);

  start = std::chrono::steady_clock::now();
  gap_search(c, before.steps, random, &searched, &r);
  std::vector<RolloutOutcome> all = random;
  all.insert(all.end(), searched.begin(), searched.end());
  r.coverage_after = validation_coverage(*task, r.prediction, options, all, before.steps).coverage;
  r.gap_seconds = seconds_since(start);

  std::stable_sort(r.findings.begin(), r.findings.end(),
                   [](const FalsifyFinding& a, const FalsifyFinding& b) { return a.distance > b.distance; });
  if (r.findings.size() > static_cast<std::size_t>(kMaxWorstEnds)) r.findings.resize(kMaxWorstEnds);
  return r;
}

}  // namespace

FalsifyResult run_falsify(std::shared_ptr<const LoadedTask> task, const Strategy& strategy,
                          const VerifyResult& prediction, const FalsifyOptions& options) {
  return falsify_with(std::move(task), strategy, prediction, options, nullptr);
}

FalsifyResult run_falsify(std::shared_ptr<const LoadedTask> task, const Strategy& strategy,
                          const VerifyResult& prediction, const FalsifyOptions& options,
                          const std::vector<RolloutOutcome>& baseline) {
  return falsify_with(std::move(task), strategy, prediction, options, &baseline);
}

FalsifyResult run_falsify(std::shared_ptr<const LoadedTask> task, const std::string& strategy_name,
                          const FalsifyOptions& options) {
  const Strategy& strategy = task->task.strategy_named(strategy_name);
  const VerifierModel model = make_verifier_model(task, options.form);
  const auto start = std::chrono::steady_clock::now();
  const VerifyResult prediction =
      verify_strategy(*model.task, *model.task->task.find_strategy(strategy_name), model.verify_options());
  const double verify_seconds = seconds_since(start);
  FalsifyResult r = run_falsify(task, strategy, prediction, options);
  r.verify_seconds = verify_seconds;
  return r;
}

}  // namespace cmt
