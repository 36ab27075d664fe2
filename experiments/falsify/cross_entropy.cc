// The cross-entropy method (experiments/falsify/cross_entropy.h).
#include "experiments/falsify/cross_entropy.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace cmt {
namespace {

struct Distribution {
  std::vector<double> mean, sigma;
};

// The raw samples of a generation: uniform in the box for a search's first generation, else from the
// Gaussian, kept within the widened box [-kReach, 1 + kReach]^n. A point is scored at its raw sample clamped
// to the box, and the distribution is refitted on the raw samples, so its mean can pass a face of the box:
// most samples then lie exactly on that face (the bounds' extremes, where termination regions are shaped).
constexpr double kReach = 0.5;

std::vector<std::vector<double>> draw_generation(const Distribution* d, const FirstDraw& first, int dimension,
                                                 int count, std::uint64_t seed, int search, int generation) {
  // Generation g of search s draws from its own stream, so a restart's draws do not depend on how many
  // evaluations came before it.
  Rng rng = rollout_stream(splitmix64(seed) ^ static_cast<std::uint64_t>(search),
                           static_cast<std::uint64_t>(generation));
  std::vector<std::vector<double>> out(static_cast<std::size_t>(count));
  for (std::vector<double>& x : out) {
    if (d == nullptr && first) {
      x = first(rng);
      if (x.size() != static_cast<std::size_t>(dimension))
        throw std::logic_error("cross_entropy_maximize: a first draw of the wrong dimension");
      continue;
    }
    x.resize(static_cast<std::size_t>(dimension));
    for (int i = 0; i < dimension; ++i) {
      const auto k = static_cast<std::size_t>(i);
      x[k] = d == nullptr ? uniform01(rng)
                          : std::clamp(d->mean[k] + d->sigma[k] * standard_normal(rng), -kReach, 1 + kReach);
    }
  }
  return out;
}

std::vector<double> clamped(std::vector<double> x) {
  for (double& v : x) v = std::clamp(v, 0.0, 1.0);
  return x;
}

// The elites' (raw samples') mean and standard deviation, blended into d.
void refit(Distribution& d, const std::vector<const std::vector<double>*>& elites, double smoothing) {
  const std::size_t n = d.mean.size();
  for (std::size_t k = 0; k < n; ++k) {
    double mean = 0;
    for (const std::vector<double>* x : elites) mean += (*x)[k];
    mean /= static_cast<double>(elites.size());
    double var = 0;
    for (const std::vector<double>* x : elites) var += ((*x)[k] - mean) * ((*x)[k] - mean);
    var /= static_cast<double>(elites.size());
    d.mean[k] = smoothing * mean + (1 - smoothing) * d.mean[k];
    d.sigma[k] = smoothing * std::sqrt(var) + (1 - smoothing) * d.sigma[k];
  }
}

}  // namespace

CrossEntropyResult cross_entropy_maximize(int dimension, int budget, std::uint64_t seed,
                                          const CrossEntropyOptions& options, const BatchScore& score,
                                          const GenerationDone& done, const FirstDraw& first) {
  if (dimension < 1 || budget < 1 || options.population < 2)
    throw std::invalid_argument("cross_entropy_maximize: dimension, budget >= 1 and population >= 2 needed");
  const int elite_count = std::clamp(static_cast<int>(std::ceil(options.elite_fraction * options.population)),
                                     2, options.population);
  CrossEntropyResult result;
  result.best.score = -std::numeric_limits<double>::infinity();
  Distribution d;
  bool fresh = true;  // the next generation starts a search (uniform draws)
  int generation = 0, stalled = 0;
  double search_best = -std::numeric_limits<double>::infinity();
  while (result.evaluations < budget) {
    if (fresh) {
      ++result.searches;
      generation = 0;
      stalled = 0;
      search_best = -std::numeric_limits<double>::infinity();
    }
    const int search = result.searches - 1;
    const int count = std::min(options.population, budget - result.evaluations);
    std::vector<std::vector<double>> raw =
        draw_generation(fresh ? nullptr : &d, first, dimension, count, seed, search, generation);
    std::vector<std::vector<double>> xs;
    for (const std::vector<double>& z : raw) xs.push_back(clamped(z));
    const std::vector<double> scores = score(xs);
    if (scores.size() != xs.size())
      throw std::logic_error("cross_entropy_maximize: one score per point needed");
    std::vector<CrossEntropyCandidate> gen;
    for (std::size_t i = 0; i < xs.size(); ++i) {
      const double s = std::isnan(scores[i]) ? -std::numeric_limits<double>::infinity() : scores[i];
      gen.push_back({std::move(xs[i]), s, search, generation, result.evaluations++});
      if (s > result.best.score) result.best = gen.back();
    }
    if (done && done(gen)) break;
    // Refit on the generation's elites (stable: equal scores keep index order).
    std::vector<std::size_t> order(gen.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return gen[a].score > gen[b].score; });
    std::vector<const std::vector<double>*> elites;
    for (std::size_t i = 0; i < order.size() && i < static_cast<std::size_t>(elite_count); ++i)
      elites.push_back(&raw[order[i]]);
    if (fresh) {
      d.mean.assign(static_cast<std::size_t>(dimension), 0.5);
      d.sigma.assign(static_cast<std::size_t>(dimension), options.initial_sigma);
      fresh = false;
    }
    if (elites.size() >= 2) refit(d, elites, options.smoothing);
    const double generation_best = gen[order.front()].score;
    stalled = generation_best > search_best ? 0 : stalled + 1;
    search_best = std::max(search_best, generation_best);
    ++generation;
    const double widest = *std::max_element(d.sigma.begin(), d.sigma.end());
    if (widest < options.restart_sigma || stalled >= options.stall_generations) fresh = true;
  }
  return result;
}

}  // namespace cmt
