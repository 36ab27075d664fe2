// Termination monitors on sensed values: sticking (stopped for a window), type 2 (contact + position set),
// type 3 (force direction + position set).
#include "controllers/termination.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cmt {
namespace {

constexpr double kDt = 0.001;

Sensed at(double t, const Vec3& x, const Vec3& f = Vec3::Zero()) {
  Sensed s;
  s.time = t;
  s.position = x;
  s.force = f;
  return s;
}

TEST(Termination, StickingFiresAfterAWindowAtRest) {
  TerminationMonitor m({}, 2.0, 0.1, kDt);
  const int window = static_cast<int>(std::lround(kStopWindow / kDt));
  for (int i = 0; i < window; ++i) EXPECT_FALSE(m.update(at(i * kDt, Vec3(1, 2, 3)))) << i;
  EXPECT_EQ(m.update(at(window * kDt, Vec3(1, 2, 3))), Termination::kSticking);
}

TEST(Termination, MovingAboveTheThresholdDoesNotStick) {
  const double reference = 2.0;
  TerminationMonitor m({}, reference, 0.1, kDt);
  const double speed = 1.5 * kStopRelativeSpeed * reference;
  for (int i = 0; i < 2000; ++i) ASSERT_FALSE(m.update(at(i * kDt, Vec3(speed * i * kDt, 0, 0)))) << i;
  // Slower than the threshold: stops within a window.
  TerminationMonitor slow({}, reference, 0.1, kDt);
  const double creep = 0.5 * kStopRelativeSpeed * reference;
  int fired = -1;
  for (int i = 0; i < 2000 && fired < 0; ++i)
    if (slow.update(at(i * kDt, Vec3(creep * i * kDt, 0, 0)))) fired = i;
  EXPECT_EQ(fired, static_cast<int>(std::lround(kStopWindow / kDt)));
}

TEST(Termination, Type2NeedsContactAndThePositionSet) {
  PositionSet ps;
  ps.add_box({Vec3(-1, -1, -1), Vec3(1, 1, 0.1)});
  TerminationSpec spec;
  spec.sensed_position = ps;
  TerminationMonitor m(spec, 1.0, 0.5, kDt);
  // In the set but no force: free space, no termination (the robot keeps moving so sticking does not fire).
  EXPECT_FALSE(m.update(at(0, Vec3(0, 0, 0.05))));
  // Contact outside the set: no.
  EXPECT_FALSE(m.update(at(kDt, Vec3(0, 0, 0.5), Vec3(0, 0, 1))));
  // Contact inside: yes.
  EXPECT_EQ(m.update(at(2 * kDt, Vec3(0, 0, 0.0), Vec3(0, 0, 1))), Termination::kPosition);
  // Contact is held for kContactHold after the last force above the guard (hopping bodies).
  TerminationMonitor h(spec, 1.0, 0.5, kDt);
  EXPECT_FALSE(h.update(at(0, Vec3(0, 0, 0.5), Vec3(0, 0, 1))));
  EXPECT_EQ(h.update(at(0.5 * kContactHold, Vec3(0, 0, 0))).value_or(Termination::kNone),
            Termination::kPosition);
  TerminationMonitor g(spec, 1.0, 0.5, kDt);
  EXPECT_FALSE(g.update(at(0, Vec3(0, 0, 0.5), Vec3(0, 0, 1))));
  EXPECT_FALSE(g.update(at(2 * kContactHold, Vec3(0, 0, 0))));
}

TEST(Termination, Type3NeedsTheForceDirection) {
  ForceDirectionSet fs;
  fs.add_cone(Vec3(0, 0, 1), 0.1);
  TerminationSpec spec;
  spec.sensed_force = fs;
  TerminationMonitor m(spec, 1.0, 0.5, kDt);
  EXPECT_FALSE(m.update(at(0, Vec3::Zero(), Vec3(0, 0.2, 1))));  // 0.197 rad off the axis
  EXPECT_FALSE(m.update(at(kDt, Vec3::Zero(), Vec3::Zero())));   // no force: no direction
  EXPECT_EQ(m.update(at(2 * kDt, Vec3::Zero(), Vec3(0, 0.05, 1))), Termination::kForce);
  // With a position set too, both must hold.
  PositionSet ps;
  ps.add_box({Vec3(-1, -1, -1), Vec3(1, 1, 1)});
  spec.sensed_position = ps;
  TerminationMonitor both(spec, 1.0, 0.5, kDt);
  EXPECT_FALSE(both.update(at(0, Vec3(5, 0, 0), Vec3(0, 0, 1))));
  EXPECT_EQ(both.update(at(kDt, Vec3(0, 0, 0), Vec3(0, 0, 1))), Termination::kForce);
}

TEST(Termination, SpecFromATaskMotionsSets) {
  // Two boxes (a union) and two cones: points in either box are in P_s, nothing between them; a force within
  // .3 rad of +z or within .1 of -x is in F_s (cone(+z, .3) holds (sin .29, 0, cos .29), not (sin .31, ...)).
  MotionTermination t;
  t.position = {{Vec3(0, 0, 0), Vec3(1, 1, 1)}, {Vec3(2, 0, 0), Vec3(3, 1, 1)}};
  t.force = {{Vec3(0, 0, 1), 0.3}, {Vec3(-1, 0, 0), 0.1}};
  const TerminationSpec spec = termination_spec(t);
  ASSERT_TRUE(spec.sensed_position && spec.sensed_force);
  EXPECT_TRUE(spec.sensed_position->contains(Vec3(0.5, 0.5, 0.5)));
  EXPECT_TRUE(spec.sensed_position->contains(Vec3(3, 1, 1)));  // closed
  EXPECT_FALSE(spec.sensed_position->contains(Vec3(1.5, 0.5, 0.5)));
  EXPECT_TRUE(spec.sensed_force->contains(Vec3(std::sin(0.29), 0, std::cos(0.29))));
  EXPECT_FALSE(spec.sensed_force->contains(Vec3(std::sin(0.31), 0, std::cos(0.31))));
  EXPECT_TRUE(spec.sensed_force->contains(Vec3(-1, 0.05, 0)));
  // Lists not given stay unset (sticking only).
  const TerminationSpec none = termination_spec(MotionTermination{});
  EXPECT_FALSE(none.sensed_position || none.sensed_force);
  MotionTermination only_position;
  only_position.position = {{Vec3(0, 0, 0), Vec3(1, 1, 1)}};
  EXPECT_FALSE(termination_spec(only_position).sensed_force.has_value());
}

TEST(Termination, NamesAreTheContractStrings) {
  EXPECT_STREQ(termination_name(Termination::kSticking), "sticking");
  EXPECT_STREQ(termination_name(Termination::kNone), "none");
  EXPECT_STREQ(termination_name(Termination::kUnstable), "unstable");
}

}  // namespace
}  // namespace cmt
