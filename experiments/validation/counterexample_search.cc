// The counterexample search (experiments/validation/counterexample_search.h, docs/validation.md
// "Counterexamples").
//
// A rollout's errors are drawn from its own stream after its start, so the only part of a rollout that can
// be chosen without changing the rollout API is its (seed, index, mode): the search runs rollout 0 of
// derived seeds, in three phases sharing the budget:
//   1. extreme: error mode kExtreme (most draws on the bounds' boundaries, where termination regions are
//      shaped);
//   2. start vertices: extreme-mode candidates whose start (the stream's first draw, predicted with
//      sample_region before running) is a vertex of the start region, cycling through the vertices;
//   3. local search: candidates whose predicted start lies within kLocalStartFraction of the region's
//      diameter of the start of the stable rollout whose final end came closest to the offending termination
//      pieces (VerifyResult::outside_goal, and a spring's free rest ball), in that rollout's mode, moving the
//      centre whenever a search rollout comes closer. The errors of these rollouts are fresh draws: the
//      search is local in the start only.
#include "experiments/validation/counterexample_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "controllers/random.h"
#include "experiments/validation/piece_geometry.h"
#include "sim/parallel_runs.h"

namespace cmt {

std::uint64_t search_seed(std::uint64_t seed, int phase, std::uint64_t k) {
  // Unrelated to the validation's own streams (rollout_stream(seed, i)) and between phases.
  return splitmix64(splitmix64(seed) ^ (0xC3A5C85C97CB3127ULL * static_cast<std::uint64_t>(phase))) + k;
}

namespace {

struct Candidate {
  std::uint64_t seed = 0;
  SampleMode mode = SampleMode::kUniform;
};

std::string point_text(const Vec3& p) {
  std::ostringstream os;
  os << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return os.str();
}

// The start rollout 0 of `seed` will have: RolloutRunner::run draws it first from rollout_stream(seed, 0).
Vec3 predicted_start(const LoadedTask& task, const Candidate& c) {
  Rng rng = rollout_stream(c.seed, 0);
  return sample_region(task.task.start, c.mode, rng);
}

class Search {
 public:
  Search(std::shared_ptr<const LoadedTask> task, const Strategy& strategy, const ValidateOptions& options,
         const VerifyResult& prediction, double tolerance)
      : task_(std::move(task)),
        strategy_(strategy),
        options_(options),
        prediction_(prediction),
        tolerance_(tolerance) {}

  double miss_distance(const RolloutOutcome& r) const {
    return distance_to_failure(task_->cspace, prediction_, r.end);
  }

  // Runs the candidates (at most kSearchBatch) in parallel and scores them; true when one failed.
  bool run_batch(const std::vector<Candidate>& batch, const char* how) {
    for (const Candidate& c : batch) scene(c.mode);  // built here, not in the workers
    std::vector<RolloutOutcome> out(batch.size());
    using Runners = std::map<SampleMode, std::unique_ptr<RolloutRunner>>;  // one per scene, per thread
    parallel_runs(
        static_cast<int>(batch.size()), options_.threads, [] { return std::make_unique<Runners>(); },
        [&](Runners& runners, int i) {
          auto& runner = runners[batch[i].mode];
          if (!runner) runner = std::make_unique<RolloutRunner>(scenes_.at(batch[i].mode));
          out[i] = runner->run(strategy_, batch[i].seed, 0);
        });

    bool found = false;
    for (std::size_t i = 0; i < batch.size(); ++i) {
      const RolloutOutcome& r = out[i];
      ++result_.report.rollouts;
      if (r.unstable) continue;
      std::vector<ObservedEnd> ends, timeouts, unexpected;
      int unpredicted = 0;
      observe_rollout(prediction_.steps, r, batch[i].seed, batch[i].mode, tolerance_, &ends, &timeouts,
                      &unexpected, &unpredicted);
      for (const ObservedEnd& e : ends)
        if (!e.inside) {
          ++result_.report.outside;
          result_.report.worst.push_back(e);
        }
      seen_.push_back({batch[i], r.start, miss_distance(r)});
      if (!r.success && !found && !result_.counterexample) {
        found = true;
        Counterexample cx;
        cx.seed = batch[i].seed;
        cx.index = 0;
        cx.mode = batch[i].mode;
        cx.how = how;
        cx.replay = replay_command(*task_, strategy_.name, cx.seed, 0, cx.mode, options_.form);
        cx.outcome = r;
        result_.counterexample = cx;
      }
    }
    return found;
  }

  // Phase 1.
  bool extreme(int budget) {
    std::uint64_t k = 0;
    for (int done = 0; done < budget;) {
      std::vector<Candidate> batch;
      for (; done < budget && static_cast<int>(batch.size()) < kSearchBatch; ++done)
        batch.push_back({search_seed(options_.seed, 1, k++), SampleMode::kExtreme});
      if (run_batch(batch, "extreme")) return true;
    }
    return false;
  }

  // Phase 2. Returns the number of rollouts it ran through *ran.
  bool start_vertices(int budget, int* ran) {
    const std::vector<Vec3>& corners = task_->task.start.points;
    std::uint64_t k = 0;
    const std::uint64_t cap = static_cast<std::uint64_t>(budget) * kMaxScanPerRollout;
    *ran = 0;
    while (*ran < budget && k < cap) {
      std::vector<Candidate> batch;
      while (*ran + static_cast<int>(batch.size()) < budget &&
             static_cast<int>(batch.size()) < kSearchBatch && k < cap) {
        const Candidate c{search_seed(options_.seed, 2, k++), SampleMode::kExtreme};
        // Cycle through the corners so each gets its share.
        const Vec3& want = corners[(*ran + batch.size()) % corners.size()];
        if (predicted_start(*task_, c) == want) batch.push_back(c);
      }
      if (batch.empty()) break;
      *ran += static_cast<int>(batch.size());
      if (run_batch(batch, "start-vertices")) return true;
    }
    return false;
  }

  // Phase 3.
  bool local(int budget, std::string* note) {
    if (seen_.empty()) return false;
    auto closest = [&] {
      return std::min_element(seen_.begin(), seen_.end(),
                              [](const Seen& a, const Seen& b) { return a.miss < b.miss; });
    };
    Seen centre = *closest();
    const std::vector<Vec3>& pts = task_->task.start.points;
    double diameter = 0;
    for (const Vec3& a : pts)
      for (const Vec3& b : pts) diameter = std::max(diameter, (a - b).norm());
    const double radius = kLocalStartFraction * diameter;
    std::ostringstream os;
    os << "local search from the start " << point_text(centre.start) << " (seed " << centre.candidate.seed
       << ", " << sample_mode_name(centre.candidate.mode) << ", final end " << centre.miss
       << " from the offending pieces)";
    std::uint64_t k = 0;
    const std::uint64_t cap = static_cast<std::uint64_t>(budget) * kMaxScanPerRollout;
    int ran = 0;
    while (ran < budget && k < cap) {
      std::vector<Candidate> batch;
      while (ran + static_cast<int>(batch.size()) < budget && static_cast<int>(batch.size()) < kSearchBatch &&
             k < cap) {
        const Candidate c{search_seed(options_.seed, 3, k++), centre.candidate.mode};
        if ((predicted_start(*task_, c) - centre.start).norm() <= radius) batch.push_back(c);
      }
      if (batch.empty()) break;
      ran += static_cast<int>(batch.size());
      if (run_batch(batch, "local-search")) break;
      const Seen best = *closest();
      if (best.miss < centre.miss) {
        centre = best;
        os << "; moved to " << point_text(centre.start) << " (" << centre.miss << ")";
      }
    }
    os << "; " << ran << " rollouts";
    *note = os.str();
    return result_.counterexample.has_value();
  }

  SearchResult run(const std::vector<RolloutOutcome>& rollouts) {
    result_.report.ran = true;
    for (const RolloutOutcome& r : rollouts)
      if (!r.unstable) seen_.push_back({{options_.seed, options_.mode}, r.start, miss_distance(r)});
    const int budget = std::max(0, options_.counterexample_budget);
    const bool corners = task_->task.start.kind != Region::Kind::kPoint;
    const int share1 = corners ? (budget + 2) / 3 : (budget + 1) / 2;
    const int share2 = corners ? (budget - share1 + 1) / 2 : 0;
    std::ostringstream note;
    note << "extreme: ";
    const int before1 = result_.report.rollouts;
    const bool hit1 = extreme(share1);
    note << result_.report.rollouts - before1 << " rollouts";
    if (hit1) return finish(note.str() + ", found");
    int ran2 = 0;
    if (corners) {
      const bool hit = start_vertices(share2, &ran2);
      note << "; start vertices: " << ran2 << " rollouts";
      if (hit) return finish(note.str() + ", found");
    } else {
      note << "; start vertices: none (the start region is a point, every start is it)";
    }
    std::string local_note;
    const bool hit = local(budget - share1 - ran2, &local_note);
    note << "; " << local_note << (hit ? ", found" : ", none failed");
    return finish(note.str());
  }

 private:
  struct Seen {
    Candidate candidate;
    Vec3 start;
    double miss;
  };

  std::shared_ptr<const RolloutScene> scene(SampleMode mode) {
    auto& s = scenes_[mode];
    if (!s) {
      SimOptions sim;
      sim.form = options_.form;
      sim.mode = mode;
      s = RolloutScene::build(task_, sim);
    }
    return s;
  }

  SearchResult finish(const std::string& note) {
    result_.report.note = note;
    std::stable_sort(result_.report.worst.begin(), result_.report.worst.end(),
                     [](const ObservedEnd& a, const ObservedEnd& b) { return a.distance > b.distance; });
    if (result_.report.worst.size() > static_cast<std::size_t>(kMaxWorstEnds))
      result_.report.worst.resize(kMaxWorstEnds);
    return result_;
  }

  std::shared_ptr<const LoadedTask> task_;
  const Strategy& strategy_;
  const ValidateOptions& options_;
  const VerifyResult& prediction_;
  double tolerance_;
  std::map<SampleMode, std::shared_ptr<const RolloutScene>> scenes_;
  std::vector<Seen> seen_;
  SearchResult result_;
};

}  // namespace

SearchResult search_counterexample(std::shared_ptr<const LoadedTask> task, const Strategy& strategy,
                                   const ValidateOptions& options, const VerifyResult& prediction,
                                   const std::vector<RolloutOutcome>& rollouts, double contact_tolerance) {
  Search search(std::move(task), strategy, options, prediction, contact_tolerance);
  return search.run(rollouts);
}

}  // namespace cmt
