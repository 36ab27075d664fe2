// Confusability and disambiguability (Buckley Def 5.1, Def 6.1) checked against the cube row of Table 6.3.
#include "verifier/sensing.h"

#include <gtest/gtest.h>

#include <functional>

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

TEST(Sensing, CubeTable63PrimitiveStates) {
  // Buckley Table 6.3, cube (mu = .25, eps_s = .2, theta_f = .3): 26 atoms, 122 primitive states of <= 2
  // atoms, 226 of <= 3, 258 in all. A primitive state is a set of atoms no two of which are disambiguable.
  auto t = load_task_from_string(test::kCubeYaml, "cube.yaml");
  const CSpace& c = t->cspace;
  const int n = c.atom_count();
  std::vector<std::vector<bool>> conf(n, std::vector<bool>(n));
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) conf[a][b] = a != b && confusable(c, a, b, 0.2, 0.3);
  std::vector<int> by_size(n + 1, 0);
  std::vector<int> clique;
  std::function<void(int)> grow = [&](int next) {
    ++by_size[clique.size()];
    for (int v = next; v < n; ++v) {
      bool ok = true;
      for (int u : clique) ok = ok && conf[u][v];
      if (!ok) continue;
      clique.push_back(v);
      grow(v + 1);
      clique.pop_back();
    }
  };
  grow(0);
  EXPECT_EQ(by_size[1], 26);
  EXPECT_EQ(by_size[1] + by_size[2], 122);
  EXPECT_EQ(by_size[1] + by_size[2] + by_size[3], 226);
  int total = 0;
  for (int k = 1; k <= n; ++k) total += by_size[k];
  EXPECT_EQ(total, 258);
}

}  // namespace
}  // namespace cmt
