// Seeded random streams for Monte Carlo rollouts (docs/rollouts.md). Rollout i draws every random
// number from its own std::mt19937_64, seeded by a SplitMix64 hash of (master seed, i) only, so a rollout's
// result does not depend on which thread runs it or in which order rollouts are run.
#pragma once

#include <cstdint>
#include <random>

#include "models/task.h"

namespace cmt {

// SplitMix64 finalizer (Steele, Lea and Flood 2014): a bijective 64-bit mix with full avalanche.
std::uint64_t splitmix64(std::uint64_t x);

// The stream of rollout `index` under `master_seed`: seeded with 4 words of a SplitMix64 sequence started at
// splitmix64(master_seed) ^ index, so nearby seeds and indices give unrelated streams.
std::mt19937_64 rollout_stream(std::uint64_t master_seed, std::uint64_t index);

using Rng = std::mt19937_64;

// Uniform double in [0, 1) from the top 53 bits (portable, unlike std::uniform_real_distribution whose
// algorithm the standard leaves open; results must not depend on the standard library).
double uniform01(Rng& rng);
double uniform(Rng& rng, double lo, double hi);
// Uniform integer in [0, n), n > 0 (rejection sampling, unbiased).
int uniform_index(Rng& rng, int n);
// Standard normal (Marsaglia polar method), for directions.
double standard_normal(Rng& rng);

// Uniform on the unit sphere; with `planar` on the unit circle of the x-z plane (planar tasks, Buckley's 2-D
// examples: y is the extrusion axis and never moves).
Vec3 uniform_on_sphere(Rng& rng, bool planar = false);
// Uniform in the closed ball of radius r (disc in the x-z plane when planar).
Vec3 uniform_in_ball(Rng& rng, double r, bool planar = false);

}  // namespace cmt
