// Membership checks of reached sets and motion lookups shared by the backprojection tests.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "models/loaded_task.h"
#include "verifier/reached_set.h"

namespace cmt::test {

// The commanded direction (damper) or position (spring) of a task's motion.
inline const Vec3& motion(const LoadedTask& t, const std::string& name) {
  return t.task.find_motion(name)->target;
}

// In the set (distance 0 up to rounding) or clearly out of it.
inline void expect_in(const ReachedSet& s, const Vec3& p) { EXPECT_LT(s.distance(p), 1e-9) << p.transpose(); }
inline void expect_out(const ReachedSet& s, const Vec3& p) {
  EXPECT_GT(s.distance(p), 0.05) << p.transpose();
}

}  // namespace cmt::test
