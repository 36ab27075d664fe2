#include "models/cspace.h"

#include <gtest/gtest.h>

#include <map>

#include "models/loaded_task.h"
#include "tests/models/test_tasks.h"

namespace cmt {
namespace {

std::map<EdgeShape, int> count_shapes(const CSpace& c) {
  std::map<EdgeShape, int> n;
  for (const Edge& e : c.edges()) ++n[e.shape];
  return n;
}

TEST(CSpace, CubeInteriorHasBuckleyCounts) {
  auto lt = load_task_from_string(test::kCubeYaml, "cube.yaml");
  const CSpace& c = lt->cspace;
  EXPECT_EQ(c.faces().size(), 6u);
  EXPECT_EQ(c.edges().size(), 12u);
  EXPECT_EQ(c.vertices().size(), 8u);
  EXPECT_EQ(c.atom_count(), 26);
  // Inside a box every edge is a corner the robot can be pushed into.
  EXPECT_EQ(count_shapes(c)[EdgeShape::kConcave], 12);
  for (const Face& f : c.faces()) {
    EXPECT_EQ(f.polygon.size(), 4u);
    EXPECT_EQ(f.edges.size(), 4u);
    EXPECT_DOUBLE_EQ(f.friction, 0.25);
    // Normals point into the cube: the centre is on the free side.
    EXPECT_GT(f.normal.dot(Vec3::Zero()) - f.offset, 0);
  }
  for (const Vertex& v : c.vertices()) {
    EXPECT_EQ(v.faces.size(), 3u);
    EXPECT_EQ(v.edges.size(), 3u);
  }
}

TEST(CSpace, HoleHasBuckleyTable63Counts) {
  auto lt = load_task_from_string(test::kHoleYaml, "hole.yaml");
  const CSpace& c = lt->cspace;
  EXPECT_EQ(c.faces().size(), 14u);
  EXPECT_EQ(c.edges().size(), 32u);
  EXPECT_EQ(c.vertices().size(), 20u);
  EXPECT_EQ(c.atom_count(), 66);
  auto shapes = count_shapes(c);
  EXPECT_EQ(shapes[EdgeShape::kFlat], 4);    // the cuts splitting the top surface
  EXPECT_EQ(shapes[EdgeShape::kConvex], 4);  // the rim of the hole
  EXPECT_EQ(shapes[EdgeShape::kConcave], 24);
  // The top surface z = 0 is split into 2 large + 2 small faces by extending the hole sides x = +-1.
  std::vector<double> top_areas;
  for (const Face& f : c.faces()) {
    if (f.normal.z() > 0.5 && std::abs(f.offset) < 1e-12) {
      double xmin = 1e9, xmax = -1e9, ymin = 1e9, ymax = -1e9;
      for (const Vec3& p : f.polygon) {
        xmin = std::min(xmin, p.x());
        xmax = std::max(xmax, p.x());
        ymin = std::min(ymin, p.y());
        ymax = std::max(ymax, p.y());
      }
      top_areas.push_back((xmax - xmin) * (ymax - ymin));
    }
  }
  std::sort(top_areas.begin(), top_areas.end());
  ASSERT_EQ(top_areas.size(), 4u);
  EXPECT_DOUBLE_EQ(top_areas[0], 10.0);  // 2 x 5
  EXPECT_DOUBLE_EQ(top_areas[1], 10.0);
  EXPECT_DOUBLE_EQ(top_areas[2], 60.0);  // 5 x 12
  EXPECT_DOUBLE_EQ(top_areas[3], 60.0);
}

TEST(CSpace, AtomIdsAreStable) {
  auto a = load_task_from_string(test::kHoleYaml, "hole.yaml");
  auto b = load_task_from_string(test::kHoleYaml, "hole.yaml");
  ASSERT_EQ(a->cspace.atom_count(), b->cspace.atom_count());
  for (std::size_t i = 0; i < a->cspace.faces().size(); ++i)
    EXPECT_EQ(a->cspace.faces()[i].polygon, b->cspace.faces()[i].polygon);
  for (std::size_t i = 0; i < a->cspace.edges().size(); ++i)
    EXPECT_EQ(a->cspace.edges()[i].a, b->cspace.edges()[i].a);
}

TEST(CSpace, ClassifiesPoints) {
  auto lt = load_task_from_string(test::kHoleYaml, "hole.yaml");
  const CSpace& c = lt->cspace;
  EXPECT_EQ(c.classify(Vec3(0, 0, 1), 1e-9), PointClass::kFree);
  EXPECT_EQ(c.classify(Vec3(0, 0, -1), 1e-9), PointClass::kFree);  // in the hole
  EXPECT_EQ(c.classify(Vec3(3, 3, -1), 1e-9), PointClass::kInsideObstacle);
  EXPECT_EQ(c.classify(Vec3(3, 3, 0), 1e-9), PointClass::kOnSurface);
  EXPECT_EQ(c.classify(Vec3(0, 0, 5), 1e-9), PointClass::kInsideObstacle);  // beyond the bounds
  const int corner = c.nearest_atom(Vec3(1, 1, -2), 1e-9);
  ASSERT_GE(corner, 0);
  EXPECT_EQ(c.atom_kind(corner), AtomKind::kVertex);
  const int rim = c.nearest_atom(Vec3(1, 0, 0), 1e-9);
  ASSERT_GE(rim, 0);
  EXPECT_EQ(c.atom_kind(rim), AtomKind::kEdge);
  EXPECT_EQ(c.edges()[c.atom_index(rim)].shape, EdgeShape::kConvex);
}

}  // namespace
}  // namespace cmt
