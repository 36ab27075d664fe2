// Confusability and disambiguability (Buckley Def 5.1, Def 6.1) on the cube; the primitive states they define
// (Table 6.3) are tested in tests/verifier/planner/primitive_states_test.cc.
#include "verifier/sensing.h"

#include <gtest/gtest.h>

#include "models/loaded_task.h"
#include "tests/models/test_tasks.h"

namespace cmt {
namespace {

TEST(Sensing, CubeDistancesAndForces) {
  auto t = load_task_from_string(test::kCubeYaml, "cube.yaml");
  const CSpace& c = t->cspace;
  const int bottom = c.nearest_atom(Vec3(0, 0, -1), 1e-9), top = c.nearest_atom(Vec3(0, 0, 1), 1e-9);
  const int side = c.nearest_atom(Vec3(1, 0, 0), 1e-9);
  EXPECT_DOUBLE_EQ(atom_distance(c, bottom, top), 2.0);
  EXPECT_DOUBLE_EQ(atom_distance(c, bottom, side), 0.0);
  // Perpendicular faces: the closest reaction forces differ by pi/2 − 2 phi = 1.0808 > 2 theta_f = .6.
  EXPECT_NEAR(force_angle_lower_bound(c, bottom, side), std::numbers::pi / 2 - 2 * std::atan(0.25), 1e-3);
  EXPECT_TRUE(disambiguable(c, bottom, side, 0.2, 0.3));
  EXPECT_TRUE(disambiguable(c, bottom, top, 0.2, 0.3));
  const int bottom_edge = c.nearest_atom(Vec3(1, 0, -1), 1e-9);
  EXPECT_FALSE(disambiguable(c, bottom, bottom_edge, 0.2, 0.3));  // shares the bottom face
  // The sensed positions of the bottom face contain points eps_s above it but not 2 eps_s.
  const Polyhedron sensed = sensed_positions(c, bottom, 0.2);
  EXPECT_TRUE(sensed.contains(Vec3(0.5, 0.5, -0.81)));
  EXPECT_FALSE(sensed.contains(Vec3(0.5, 0.5, -0.5)));
}

}  // namespace
}  // namespace cmt
