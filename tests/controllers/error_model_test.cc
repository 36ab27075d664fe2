// Error models: every sampled error is within its bound (never beyond, in any mode), extreme mode puts most
// samples exactly on the boundary, uniform mode spreads them over the cone / ball, and direction errors turn
// a vector by exactly their angle.
#include "controllers/error_model.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cmt {
namespace {

double angle_between(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

Uncertainty hole_bounds() {
  Uncertainty u;
  u.eps_s = 0.2;
  u.eps_p = 0.2;
  u.theta_v = 0.25;
  u.theta_f = 0.05;
  return u;
}

TEST(DirectionError, TurnsByExactlyItsAngleAndKeepsLength) {
  Rng rng = rollout_stream(5, 0);
  for (int i = 0; i < 2000; ++i) {
    DirectionError e{uniform_on_sphere(rng), uniform(rng, -0.5, 0.5)};
    const Vec3 v = uniform_in_ball(rng, 3.0) + Vec3(0, 0, 1e-3);
    const Vec3 w = e.apply(v);
    EXPECT_NEAR(w.norm(), v.norm(), 1e-12 * v.norm());
    EXPECT_NEAR(angle_between(v, w), std::abs(e.angle), 1e-9);
  }
  // Axis parallel to v: still an exact turn, deterministic.
  const DirectionError e{Vec3::UnitZ(), 0.3};
  EXPECT_NEAR(angle_between(Vec3::UnitZ(), e.apply(Vec3::UnitZ())), 0.3, 1e-12);
  EXPECT_EQ(e.apply(Vec3::Zero()), Vec3::Zero());
  // A constant error turns a rotating command consistently (Buckley App. B): in the x-z plane about +y,
  // every vector is turned the same way.
  const DirectionError planar{Vec3::UnitY(), 0.2};
  for (const double a : {0.0, 1.0, 2.0, 3.0, 4.0, 5.0}) {
    const Vec3 v(std::cos(a), 0, std::sin(a));
    const Vec3 w = planar.apply(v);
    EXPECT_NEAR(v.cross(w).dot(Vec3::UnitY()), std::sin(0.2), 1e-12);
  }
}

TEST(ErrorSampler, BoundsAreNeverExceeded) {
  const Uncertainty u = hole_bounds();
  for (const SampleMode mode : {SampleMode::kUniform, SampleMode::kExtreme})
    for (const bool planar : {false, true}) {
      SCOPED_TRACE(std::string(sample_mode_name(mode)) + (planar ? " planar" : ""));
      const ErrorSampler sampler(u, mode, planar);
      Rng rng = rollout_stream(11, planar);
      const Vec3 command = Vec3(0.3, 0, -1).normalized();
      for (int i = 0; i < 20000; ++i) {
        const DirectionError v = sampler.velocity_error(rng);
        ASSERT_LE(std::abs(v.angle), u.theta_v);
        ASSERT_LE(angle_between(command, v.apply(command)), u.theta_v + 1e-12);
        ASSERT_LE(std::abs(sampler.force_error(rng).angle), u.theta_f);
        const Vec3 s = sampler.sensing_offset(rng), p = sampler.positioning_error(rng);
        ASSERT_LE(s.norm(), u.eps_s);
        ASSERT_LE(p.norm(), u.eps_p);
        if (planar) {
          ASSERT_EQ(s.y(), 0);
          ASSERT_NEAR(v.apply(command).y(), 0, 1e-15);
        }
      }
    }
}

TEST(ErrorSampler, ExtremeModePutsMostSamplesOnTheBoundary) {
  const Uncertainty u = hole_bounds();
  const ErrorSampler extreme(u, SampleMode::kExtreme, false), uniform(u, SampleMode::kUniform, false);
  Rng rng = rollout_stream(12, 0);
  const int n = 20000;
  int rim = 0, surface = 0, uniform_rim = 0, uniform_surface = 0;
  for (int i = 0; i < n; ++i) {
    rim += extreme.velocity_error(rng).angle == u.theta_v;
    surface += std::abs(extreme.sensing_offset(rng).norm() - u.eps_s) <= 1e-15;
    uniform_rim += uniform.velocity_error(rng).angle >= 0.999 * u.theta_v;
    uniform_surface += uniform.sensing_offset(rng).norm() >= 0.999 * u.eps_s;
  }
  EXPECT_NEAR(rim / double(n), kExtremeBoundaryFraction, 0.01);
  EXPECT_NEAR(surface / double(n), kExtremeBoundaryFraction, 0.01);
  // Uniform: the outer 0.1 % shell of the ball holds 0.3 % of the volume, the outer 0.1 % of the cone's angle
  // ~0.2 % of its solid angle.
  EXPECT_LT(uniform_rim, n / 100);
  EXPECT_LT(uniform_surface, n / 100);
}

TEST(ErrorSampler, UniformDirectionsCoverTheConeBySolidAngle) {
  // Uniform over the cone's cap: P(angle <= t) = (1 - cos t) / (1 - cos theta).
  const Uncertainty u = hole_bounds();
  const ErrorSampler sampler(u, SampleMode::kUniform, false);
  Rng rng = rollout_stream(13, 0);
  const int n = 40000;
  int below_half = 0;
  for (int i = 0; i < n; ++i) below_half += sampler.velocity_error(rng).angle <= u.theta_v / 2;
  const double expected = (1 - std::cos(u.theta_v / 2)) / (1 - std::cos(u.theta_v));
  EXPECT_NEAR(below_half / double(n), expected, 0.01);
}

TEST(MotionErrors, VelocityErrorSwitchesOnlyWhenSwitching) {
  const ErrorSampler sampler(hole_bounds(), SampleMode::kUniform, false);
  int constant = 0, switching = 0;
  double total_switches = 0, total_time = 0;
  for (int k = 0; k < 400; ++k) {
    Rng rng = rollout_stream(21, k);
    MotionErrors e(sampler, rng, 0.1);
    const Vec3 offset = e.sensing_offset();
    const double angle0 = e.force().angle;
    for (int step = 0; step <= 2000; ++step) e.advance(step * 0.001, rng);
    EXPECT_EQ(e.sensing_offset(), offset);  // drawn once per motion
    EXPECT_EQ(e.force().angle, angle0);
    if (e.switches() == 0) {
      ++constant;
    } else {
      ++switching;
      total_switches += e.switches();
      total_time += 2.0;
    }
  }
  // Half the motions keep one error (P(no switch in 2 s | switching) = e^-20 is negligible).
  EXPECT_NEAR(constant / 400.0, 0.5, 0.1);
  EXPECT_NEAR(total_time / total_switches, 0.1, 0.01);  // Poisson, mean interval 0.1 s
}

TEST(SampleMode, ParsesItsNames) {
  EXPECT_EQ(parse_sample_mode("uniform"), SampleMode::kUniform);
  EXPECT_EQ(parse_sample_mode("extreme"), SampleMode::kExtreme);
  EXPECT_FALSE(parse_sample_mode("Extreme").has_value());
}

}  // namespace
}  // namespace cmt
