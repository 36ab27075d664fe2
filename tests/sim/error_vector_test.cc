// Error vectors (sim/error_vector.h): every vector decodes to errors within the task's bounds, the bounds'
// extremes are reachable, switches happen at the sorted times, and a vector replays its rollout bit for bit.
#include "sim/error_vector.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "models/loaded_task.h"
#include "models/polygon_distance.h"
#include "sim/rollout.h"

namespace cmt {
namespace {

std::shared_ptr<const LoadedTask> builtin(const std::string& name) {
  return load_task(std::filesystem::path(CMT_SOURCE_DIR) / "models" / "tasks" / (name + ".yaml"));
}

std::vector<double> random_vector(int n, Rng& rng) {
  std::vector<double> v(static_cast<std::size_t>(n));
  for (double& x : v) x = uniform01(rng) < 0.2 ? (uniform01(rng) < 0.5 ? 0.0 : 1.0) : uniform01(rng);
  return v;
}

// The angle between v and its image under e (the deviation it imposes).
double deviation(const DirectionError& e, const Vec3& v) {
  const Vec3 w = e.apply(v);
  return std::atan2(v.cross(w).norm(), v.dot(w));
}

TEST(ErrorVector, DecodedErrorsStayWithinTheirBounds) {
  Rng rng = rollout_stream(7, 0);
  for (const bool planar : {false, true})
    for (int i = 0; i < 2000; ++i) {
      const std::vector<double> u = random_vector(3, rng);
      const DirectionError d = decode_direction(u.data(), 0.1, planar);
      EXPECT_LE(std::abs(d.angle), 0.1);
      const Vec3 v = uniform_on_sphere(rng, planar);
      EXPECT_LE(deviation(d, v), 0.1 + 1e-12);
      const Vec3 o = decode_offset(u.data(), 0.3, planar);
      EXPECT_LE(o.norm(), 0.3);
      if (planar) {
        EXPECT_EQ(o.y(), 0.0);
      }
    }
}

TEST(ErrorVector, TheBoundsAreReached) {
  const double ones[3] = {1, 1, 1}, zeros[3] = {0, 0, 0}, half[3] = {0.5, 0.5, 0.5};
  EXPECT_EQ(decode_direction(ones, 0.1, false).angle, 0.1);
  EXPECT_EQ(decode_direction(ones, 0.1, true).angle, 0.1);
  EXPECT_EQ(decode_direction(zeros, 0.1, true).angle, -0.1);
  EXPECT_EQ(decode_direction(zeros, 0.1, false).angle, 0.0);
  EXPECT_NEAR(decode_offset(ones, 0.3, false).norm(), 0.3, 1e-15);
  EXPECT_NEAR(decode_offset(zeros, 0.3, true).norm(), 0.3, 1e-15);
  EXPECT_EQ(decode_offset(half, 0.3, false).norm(), 0.0);
}

TEST(ErrorVector, StartPointsLieInTheirRegion) {
  Region square{Region::Kind::kPolygon, {{-1, -1, 2}, {3, -1, 2}, {3, 1, 2}, {-1, 1, 2}}, "start"};
  Region segment{Region::Kind::kSegment, {{0, 0, 0}, {2, 4, 0}}, "start"};
  Rng rng = rollout_stream(8, 0);
  double farthest = 0;
  for (int i = 0; i < 2000; ++i) {
    const std::vector<double> u = random_vector(2, rng);
    const Vec3 p = decode_start(square, u.data());
    EXPECT_LE(distance_to_convex_polygon(p, square.points, polygon_normal(square.points)), 1e-12);
    farthest = std::max(farthest, (p - Vec3(1, 0, 2)).norm());
    EXPECT_LE(distance_to_segment(decode_start(segment, u.data()), segment.points[0], segment.points[1]),
              1e-12);
  }
  // Fraction 1 of the way to the rim in the direction of a vertex is that vertex (angle 0: towards v[0]).
  const double corner[2] = {0, 1};
  EXPECT_LE((decode_start(square, corner) - Vec3(-1, -1, 2)).norm(), 1e-12);
  EXPECT_GT(farthest, std::sqrt(5.0) - 0.05);
}

TEST(ErrorVector, LayoutSizeAndShapeRoundTrip) {
  const auto task = builtin("two_blocks");
  for (const Strategy& s : task->task.strategies) {
    ErrorVectorShape shape = default_error_shape(false, 0.2);
    const int start = task->task.start.kind == Region::Kind::kPoint ? 0 : 2;
    for (shape.switches = 0; shape.switches < 5; ++shape.switches) {
      const ErrorVectorLayout layout(task->task, s, shape);
      int readings = 0;
      for (const StrategyNode& n : s.nodes) readings += !n.branches.empty();
      EXPECT_EQ(layout.size(),
                start + static_cast<int>(s.nodes.size()) * (6 + 3 * (shape.switches + 1) + shape.switches) +
                    6 * readings);
      EXPECT_EQ(shape_of_vector(task->task, s, layout.size(), false, 0.2).switches, shape.switches) << s.name;
    }
    EXPECT_THROW(shape_of_vector(task->task, s, start + 1, false, 0.2), std::invalid_argument);
  }
}

TEST(ErrorVector, VelocityErrorSwitchesAtTheSortedTimes) {
  const auto task = builtin("two_blocks");
  const Strategy& s = task->task.strategies.front();
  ErrorVectorShape shape = default_error_shape(false, 0.2);
  shape.switches = 2;
  const ErrorVectorLayout layout(task->task, s, shape);
  std::vector<double> v(static_cast<std::size_t>(layout.size()), 0.5);
  const int block = layout.motion_offset(0);
  v[static_cast<std::size_t>(block + layout.switch_times_offset())] = 3.0 / 8;      // 3 s
  v[static_cast<std::size_t>(block + layout.switch_times_offset() + 1)] = 1.0 / 6;  // 1 s
  for (int k = 0; k < 3; ++k)  // segment k turns by (k + 1) / 4 of theta_v
    v[static_cast<std::size_t>(block + ErrorVectorLayout::kVelocity + 3 * k + 2)] = 0.25 * (k + 1);
  ScriptedErrors errors(task->task, layout, v);
  errors.begin_motion(0);
  const double theta_v = task->task.uncertainty.theta_v;
  const auto angle_at = [&](double t) {
    errors.advance(t);
    return errors.velocity().angle;
  };
  EXPECT_DOUBLE_EQ(angle_at(0.0), 0.25 * theta_v);
  EXPECT_DOUBLE_EQ(angle_at(0.99), 0.25 * theta_v);
  EXPECT_DOUBLE_EQ(angle_at(1.01), 0.5 * theta_v);
  EXPECT_DOUBLE_EQ(angle_at(2.99), 0.5 * theta_v);
  EXPECT_DOUBLE_EQ(angle_at(3.01), 0.75 * theta_v);
  EXPECT_EQ(errors.switches(), 2);
  // A switch number of 1 never switches: the error stays constant for the whole motion.
  v[static_cast<std::size_t>(block + layout.switch_times_offset())] = 1;
  v[static_cast<std::size_t>(block + layout.switch_times_offset() + 1)] = 1;
  ScriptedErrors constant(task->task, layout, v);
  constant.begin_motion(0);
  constant.advance(1e9);
  EXPECT_EQ(constant.switches(), 0);
}

TEST(ErrorVector, TextRoundTripsAndBadEntriesAreNamed) {
  const std::vector<double> v = {0, 1, 0.1, 1.0 / 3, 0.7071067811865476};
  EXPECT_EQ(parse_error_vector(format_error_vector(v)), v);
  EXPECT_THROW(parse_error_vector("0.5,x"), std::invalid_argument);
  EXPECT_THROW(parse_error_vector("0.5,1.5"), std::invalid_argument);
  EXPECT_THROW(parse_error_vector("0.5,nan"), std::invalid_argument);
  try {
    parse_error_vector("0.1,0.2,-0.3");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("entry 2"), std::string::npos) << e.what();
  }
}

TEST(ErrorVector, AVectorReplaysItsRolloutBitForBit) {
  const auto task = builtin("two_blocks");
  const Strategy& s = task->task.strategy_named("slide");
  SimOptions options;
  options.form = ControllerForm::kImpedance;
  const auto scene = RolloutScene::build(task, options);
  const ErrorVectorLayout layout(task->task, s, default_error_shape(false, options.damper_speed_per_scale));
  Rng rng = rollout_stream(9, 0);
  const std::vector<double> v = random_vector(layout.size(), rng);
  RolloutRunner a(scene), b(scene);
  ScriptedErrors ea(task->task, layout, v), eb(task->task, layout, v);
  const RolloutOutcome first = a.run(s, ea, 0);
  a.run(s, eb, 1);  // the runner's state from another rollout must not leak into the replay
  ScriptedErrors ec(task->task, layout, v);
  const RolloutOutcome again = a.run(s, ec, 0), other = b.run(s, eb, 0);
  ASSERT_FALSE(first.motions.empty());
  EXPECT_EQ(first.end, again.end);
  EXPECT_EQ(first.end, other.end);
  EXPECT_EQ(first.motions.back().steps, other.motions.back().steps);
}

TEST(ErrorVector, BadVectorsAreRefused) {
  const auto task = builtin("two_blocks");
  const Strategy& s = task->task.strategies.front();
  const ErrorVectorLayout layout(task->task, s, default_error_shape(false, 0.2));
  EXPECT_THROW(ScriptedErrors(task->task, layout,
                              std::vector<double>(static_cast<std::size_t>(layout.size() - 1), 0.5)),
               std::invalid_argument);
  std::vector<double> v(static_cast<std::size_t>(layout.size()), 0.5);
  v.back() = 2;
  EXPECT_THROW(ScriptedErrors(task->task, layout, v), std::invalid_argument);
}

}  // namespace
}  // namespace cmt
