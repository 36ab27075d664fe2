#include "controllers/random.h"

#include <cmath>

namespace cmt {

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::mt19937_64 rollout_stream(std::uint64_t master_seed, std::uint64_t index) {
  std::uint64_t state = splitmix64(master_seed) ^ index;
  std::uint32_t words[8];
  for (int i = 0; i < 4; ++i) {
    state = splitmix64(state);
    words[2 * i] = static_cast<std::uint32_t>(state);
    words[2 * i + 1] = static_cast<std::uint32_t>(state >> 32);
  }
  std::seed_seq seq(words, words + 8);
  return std::mt19937_64(seq);
}

double uniform01(Rng& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

double uniform(Rng& rng, double lo, double hi) { return lo + (hi - lo) * uniform01(rng); }

int uniform_index(Rng& rng, int n) {
  const std::uint64_t range = static_cast<std::uint64_t>(n);
  const std::uint64_t limit = rng.max() - (rng.max() % range);  // largest multiple of range: no modulo bias
  std::uint64_t x;
  do x = rng();
  while (x >= limit);
  return static_cast<int>(x % range);
}

double standard_normal(Rng& rng) {
  double u, v, s;
  do {
    u = 2 * uniform01(rng) - 1;
    v = 2 * uniform01(rng) - 1;
    s = u * u + v * v;
  } while (s >= 1 || s == 0);
  return u * std::sqrt(-2 * std::log(s) / s);
}

Vec3 uniform_on_sphere(Rng& rng, bool planar) {
  if (planar) {
    const double a = uniform(rng, 0, 2 * M_PI);
    return Vec3(std::cos(a), 0, std::sin(a));
  }
  Vec3 v;
  do v = Vec3(standard_normal(rng), standard_normal(rng), standard_normal(rng));
  while (v.squaredNorm() < 1e-20);
  return v.normalized();
}

Vec3 uniform_in_ball(Rng& rng, double r, bool planar) {
  // Radius by inverse CDF: P(|x| <= t) = (t/r)^d.
  const double radius = r * std::pow(uniform01(rng), planar ? 0.5 : 1.0 / 3.0);
  return radius * uniform_on_sphere(rng, planar);
}

}  // namespace cmt
