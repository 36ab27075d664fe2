// The cross-entropy method (Rubinstein 1999; de Boer et al. 2005) over the unit box [0, 1]^n, maximizing a
// score: a diagonal Gaussian sampling distribution is fitted, generation by generation, to the best fraction
// of its samples (raw samples may pass the box's faces and are scored clamped onto them, so the bounds'
// extremes are reached; cross_entropy.cc); a search restarts from a uniform generation when the distribution
// has collapsed or stalls. Why this and not a packaged optimizer: the score is a MuJoCo rollout (noisy in
// effect, discontinuous where a contact switches), a whole generation is evaluated at once so the rollouts
// run in parallel, and the search must be deterministic for any thread count. NLopt's derivative-free methods
// (Debian libnlopt) evaluate one point at a time, and its stochastic ones draw from a process-wide generator;
// CMA-ES has no Debian package. Every draw here comes from a stream of (seed, search, generation), and the
// scores are consumed in index order, so the result depends on the seed and the budget only.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "controllers/random.h"

namespace cmt {

struct CrossEntropyOptions {
  int population = 16;           // samples per generation (evaluated together)
  double elite_fraction = 0.25;  // the best this fraction of a generation refits the distribution
  double smoothing = 0.7;        // new parameters = smoothing x elite fit + (1 - smoothing) x old
  double initial_sigma = 0.3;    // per coordinate, after the uniform first generation
  // A search restarts when every coordinate's sigma is below this, or after this many generations without
  // improving its best score.
  double restart_sigma = 0.02;
  int stall_generations = 5;
};

struct CrossEntropyCandidate {
  std::vector<double> x;
  double score = 0;
  int search = 0;      // restart number, from 0
  int generation = 0;  // within its search
  int evaluation = 0;  // index among all evaluations, from 0
};

struct CrossEntropyResult {
  CrossEntropyCandidate best;  // the highest score (the earliest among equals)
  int evaluations = 0;
  int searches = 0;
};

// Scores of a batch of points, in order.
using BatchScore = std::function<std::vector<double>(const std::vector<std::vector<double>>&)>;
// Called after each generation with every candidate of it; returning true ends the run.
using GenerationDone = std::function<bool(const std::vector<CrossEntropyCandidate>&)>;

// Draws one point of a search's first generation from the stream it is given (a caller that knows where good
// points tend to lie, e.g. the bounds' extremes, biases the start); without one, uniform in the box.
using FirstDraw = std::function<std::vector<double>(Rng&)>;

// Maximizes over [0, 1]^dimension with at most `budget` evaluations (the last generation may be partial).
// Throws std::invalid_argument for dimension < 1, budget < 1 or a population < 2.
CrossEntropyResult cross_entropy_maximize(int dimension, int budget, std::uint64_t seed,
                                          const CrossEntropyOptions& options, const BatchScore& score,
                                          const GenerationDone& done = {}, const FirstDraw& first = {});

}  // namespace cmt
