#include "models/cspace.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>
#include <vector>

#include "models/loaded_task.h"
#include "models/task_loader.h"
#include "models/task_transform.h"
#include "tests/models/test_tasks.h"

namespace cmt {
namespace {

std::map<EdgeShape, int> count_shapes(const CSpace& c) {
  std::map<EdgeShape, int> n;
  for (const Edge& e : c.edges()) ++n[e.shape];
  return n;
}

struct TestBox {
  Vec3 min, max;
};

// A C-space task of the given boxes inside bounds `lo`..`hi`, start and goal on the first box's top.
std::string boxes_yaml(const std::vector<TestBox>& boxes, const Vec3& lo, const Vec3& hi) {
  auto v = [](const Vec3& p) {
    std::ostringstream s;
    s.precision(17);
    s << "[" << p.x() << ", " << p.y() << ", " << p.z() << "]";
    return s.str();
  };
  std::ostringstream y;
  y << "name: boxes\nunits: in\nfriction: 0.25\n"
    << "uncertainty: {eps_s: 0.2, eps_p: 0.2, theta_v: 0.25, theta_f: 0.3}\ncspace:\n";
  for (const TestBox& b : boxes) y << "  - box: {min: " << v(b.min) << ", max: " << v(b.max) << "}\n";
  const Vec3 top(0.5 * (boxes[0].min.x() + boxes[0].max.x()), 0.5 * (boxes[0].min.y() + boxes[0].max.y()),
                 boxes[0].max.z());
  y << "bounds: {min: " << v(lo) << ", max: " << v(hi) << "}\n"
    << "start: {point: " << v(top) << "}\ngoal: {point: " << v(top) << "}\n"
    << "motions:\n  v1: {damper: [0, 0, -1]}\nstrategies:\n  down: [v1]\n";
  return y.str();
}

double polygon_area(const Face& f) {
  Vec3 twice = Vec3::Zero();
  for (std::size_t i = 0; i < f.polygon.size(); ++i)
    twice += f.polygon[i].cross(f.polygon[(i + 1) % f.polygon.size()]);
  return 0.5 * std::abs(twice.dot(f.normal));
}

// n boxes on a grid with gaps of at least 0.5, widths 1 to 1.5 and heights 1 to 2.5, so that planes of
// some boxes cut others; all strictly inside the returned bounds.
std::vector<TestBox> disjoint_boxes(int n, Vec3* lo, Vec3* hi) {
  std::vector<TestBox> boxes;
  const int side = static_cast<int>(std::ceil(std::sqrt(n)));
  for (int k = 0; k < n; ++k) {
    const Vec3 min(2.0 * (k % side), 2.0 * (k / side), 0.5 * (k % 2));
    const Vec3 size(1.0 + 0.25 * (k % 3), 1.0 + 0.25 * ((k / 3) % 3), 1.0 + 0.5 * (k % 4));
    boxes.push_back({min, min + size});
  }
  *lo = Vec3(-1, -1, -1);
  *hi = Vec3(2.0 * side, 2.0 * side, 4.0);
  return boxes;
}

// Disjoint boxes strictly inside the bounds: the surface is the bounds box plus every box, each a closed
// convex polyhedron of 6 faces, 12 edges (convex; the bounds' are concave) and 8 vertices.
TEST(CSpace, DisjointBoxesGiveOneBoxSurfaceEach) {
  const int n = 300;
  Vec3 lo, hi;
  const std::vector<TestBox> boxes = disjoint_boxes(n, &lo, &hi);
  const CSpace c = CSpace::build(parse_task_string(boxes_yaml(boxes, lo, hi), "boxes.yaml"));
  EXPECT_EQ(c.faces().size(), 6u * (n + 1));
  EXPECT_EQ(c.edges().size(), 12u * (n + 1));
  EXPECT_EQ(c.vertices().size(), 8u * (n + 1));
  auto shapes = count_shapes(c);
  EXPECT_EQ(shapes[EdgeShape::kConvex], 12 * n);
  EXPECT_EQ(shapes[EdgeShape::kConcave], 12);
  double area = 0, expected = 0;
  for (const Face& f : c.faces()) {
    EXPECT_EQ(f.polygon.size(), 4u);
    area += polygon_area(f);
  }
  auto surface = [](const Vec3& d) { return 2 * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x()); };
  for (const TestBox& b : boxes) expected += surface(b.max - b.min);
  expected += surface(hi - lo);
  EXPECT_NEAR(area, expected, 1e-9 * expected);
}

// Overlapping and touching boxes merge: two overlapping boxes of equal cross-section are one box; a box
// touching a taller one along a face is an L-shaped prism whose two L-shaped sides are split into two
// convex pieces each, the cut ending on the boundary at a new vertex (T-junction). Its counts follow from
// Euler's formula V - E + F = 2 with F = 10 (6 rectangles + 2 x 2 pieces) and V = 12 corners + 2 cut ends.
TEST(CSpace, OverlappingAndTouchingBoxesMerge) {
  const Vec3 lo(-1, -1, -1), hi(8, 4, 4);
  const CSpace overlap = CSpace::build(parse_task_string(
      boxes_yaml({{Vec3(0, 0, 0), Vec3(2, 1, 1)}, {Vec3(1, 0, 0), Vec3(3, 1, 1)}}, lo, hi), "overlap.yaml"));
  EXPECT_EQ(overlap.faces().size(), 12u);  // the bounds box and one merged box
  EXPECT_EQ(overlap.edges().size(), 24u);
  EXPECT_EQ(overlap.vertices().size(), 16u);
  const CSpace touch = CSpace::build(parse_task_string(
      boxes_yaml({{Vec3(0, 0, 0), Vec3(1, 1, 1)}, {Vec3(1, 0, 0), Vec3(2, 1, 2)}}, lo, hi), "touch.yaml"));
  EXPECT_EQ(touch.faces().size(), 6u + 10u);
  EXPECT_EQ(touch.vertices().size(), 8u + 14u);
  EXPECT_EQ(touch.edges().size(), 12u + 22u);
}

// A box listed many times is one box: the surface of one box inside the bounds box, while obstacles() still
// lists every copy. The copies are built once (hundreds of copies once took tens of seconds: fuzz corpus
// duplicate_parts_300); a copy with another friction is not a copy, and the larger friction wins.
TEST(CSpace, RepeatedBoxesAreOneBox) {
  const Vec3 lo(-1, -1, -1), hi(4, 4, 4);
  const TestBox box{Vec3(0, 0, 0), Vec3(2, 1, 1)};
  const CSpace c =
      CSpace::build(parse_task_string(boxes_yaml(std::vector<TestBox>(400, box), lo, hi), "repeated.yaml"));
  EXPECT_EQ(c.obstacles().size(), 400u);
  EXPECT_EQ(c.faces().size(), 12u);
  EXPECT_EQ(c.edges().size(), 24u);
  EXPECT_EQ(c.vertices().size(), 16u);
  std::string yaml = boxes_yaml({box, box}, lo, hi);
  const std::string copy = "max: [2, 1, 1]}\n";
  const auto at = yaml.rfind(copy);
  ASSERT_NE(at, std::string::npos) << yaml;
  yaml.replace(at, copy.size(), "max: [2, 1, 1], friction: 0.5}\n");
  const CSpace mixed = CSpace::build(parse_task_string(yaml, "mixed.yaml"));
  EXPECT_EQ(mixed.obstacles().size(), 2u);
  ASSERT_EQ(mixed.faces().size(), 12u);
  int box_faces = 0;
  for (const Face& f : mixed.faces()) box_faces += f.friction == 0.5;
  EXPECT_EQ(box_faces, 6);  // the bounds box keeps the task's 0.25
}

TEST(CSpace, CubeInteriorHasBuckleyCounts) {
  auto task = load_task_from_string(test::kCubeYaml, "cube.yaml");
  const CSpace& c = task->cspace;
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
  auto task = load_task_from_string(test::kHoleYaml, "hole.yaml");
  const CSpace& c = task->cspace;
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

// The faces of the top plane z = 0 that are 2 wide in x (the hole's width).
int top_faces_two_wide_in_x(const CSpace& c) {
  int n = 0;
  for (const Face& f : c.faces()) {
    if (f.normal.z() < 0.5 || f.offset != 0) continue;
    double xmin = 1e9, xmax = -1e9;
    for (const Vec3& p : f.polygon) xmin = std::min(xmin, p.x()), xmax = std::max(xmax, p.x());
    if (xmax - xmin == 2) ++n;
  }
  return n;
}

// The hole's top annulus is square: a quarter turn about z maps it onto itself, so no decomposition into
// Buckley's two large and two small faces follows the turn by geometry alone. Built in the task's own axes
// (Task::axes), the turned task, turned together with its axes, has the turned C-space atom for atom.
TEST(CSpace, ATaskTurnedWithItsAxesHasTheTurnedCSpaceAtomForAtom) {
  const auto original = load_task_from_string(test::kHoleYaml, "hole.yaml");
  const TaskTransform turn = TaskTransform::quarter_turns(2, 1);
  Task turned_task = transformed(original->task, turn);
  ASSERT_FALSE(turned_task.axes.isIdentity());
  const CSpace& a = original->cspace;
  const CSpace b = CSpace::build(turned_task);
  ASSERT_EQ(a.faces().size(), b.faces().size());
  ASSERT_EQ(a.edges().size(), b.edges().size());
  ASSERT_EQ(a.vertices().size(), b.vertices().size());
  EXPECT_EQ(a.scale(), b.scale());
  for (std::size_t i = 0; i < a.faces().size(); ++i) {
    const Face &f = a.faces()[i], &g = b.faces()[i];
    EXPECT_EQ(turn.direction(f.normal), g.normal) << "face " << i;
    EXPECT_EQ(f.offset, g.offset);
    ASSERT_EQ(f.polygon.size(), g.polygon.size());
    for (std::size_t k = 0; k < f.polygon.size(); ++k) EXPECT_EQ(turn.point(f.polygon[k]), g.polygon[k]);
    EXPECT_EQ(f.edges, g.edges);
    EXPECT_EQ(f.vertices, g.vertices);
  }
  for (std::size_t i = 0; i < a.edges().size(); ++i) {
    EXPECT_EQ(turn.point(a.edges()[i].a), b.edges()[i].a) << "edge " << i;
    EXPECT_EQ(turn.point(a.edges()[i].b), b.edges()[i].b);
    EXPECT_EQ(a.edges()[i].shape, b.edges()[i].shape);
  }
  for (std::size_t i = 0; i < a.vertices().size(); ++i)
    EXPECT_EQ(turn.point(a.vertices()[i].point), b.vertices()[i].point) << "vertex " << i;
  // The world-axes build of the same turned geometry cuts the annulus along the world's y instead: its
  // small faces (2 x 5) lie beside the hole in x, where the turned task's lie in front of and behind it.
  turned_task.axes = Eigen::Matrix3d::Identity();
  EXPECT_EQ(top_faces_two_wide_in_x(CSpace::build(turned_task)), 2);
  EXPECT_EQ(top_faces_two_wide_in_x(b), 0);
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

// The hole's boxes stand on the bounds' floor z = -2 and reach the walls x, y = +-6: those facets have only
// solid (the outside of the bounds) beyond them, so a point's depth is its distance to the other facets of
// the box that holds it: the top z = 0 and the hole's side x = 1 for box [1, 6] x [-6, 6] x [-2, 0].
TEST(CSpace, SolidDepthIgnoresFacetsOnTheBounds) {
  auto task = load_task_from_string(test::kHoleYaml, "hole.yaml");
  const CSpace& c = task->cspace;
  EXPECT_DOUBLE_EQ(c.solid_depth(Vec3(3, 3, -1)), 1.0);
  EXPECT_DOUBLE_EQ(c.solid_depth(Vec3(3, 3, -1.9)), 1.9);    // 0.1 above the floor facet, on the bounds
  EXPECT_DOUBLE_EQ(c.solid_depth(Vec3(5.9, 3, -1.5)), 1.5);  // 0.1 from the wall facet x = 6
  // A lower bound: beyond x = 1 at y = 3 lies box [-1, 1] x [1, 6], which the depth does not join.
  EXPECT_DOUBLE_EQ(c.solid_depth(Vec3(1.25, 3, -1)), 0.25);
  EXPECT_EQ(c.solid_depth(Vec3(0, 0, -1)), 0.0);  // in the hole
  EXPECT_EQ(c.solid_depth(Vec3(3, 3, 0)), 0.0);   // on the top
  EXPECT_EQ(c.solid_depth(Vec3(3, 3, 1)), 0.0);   // above it
}

// A generated ramp's floor facet (12-digit coordinates, far from the origin): its double offset is a quotient
// of rounded numbers and may come out just inside the bounds' floor; it is covered all the same, and a facet
// a millionth of the scene inside the bounds is not.
TEST(CSpace, FacetsOnTheBoundsAreCoveredDespiteRounding) {
  int covered = 0, floors = 0;
  for (int i = 0; i < 200; ++i) {
    const double z0 = -49722.3918344 - 0.0137 * i, x0 = 1635.95529095 + 0.71 * i;
    std::ostringstream yaml;
    yaml.precision(12);
    yaml << "name: ramp\nunits: mm\nfriction: 0.3\n"
         << "uncertainty: {eps_s: 1, eps_p: 1, theta_v: 0.1, theta_f: 0.05}\n"
         << "cspace:\n  - convex: {vertices: [[" << x0 << ", 38329.5117654, " << z0 << "], [" << x0 + 39.5
         << ", 38329.5117654, " << z0 << "], [" << x0 + 39.5 << ", 38384.4830096, " << z0 << "], [" << x0
         << ", 38384.4830096, " << z0 << "], [" << x0 << ", 38329.5117654, " << z0 + 1.9 << "], ["
         << x0 + 39.5 << ", 38329.5117654, " << z0 + 1.9 << "], [" << x0 + 39.5 << ", 38384.4830096, "
         << z0 + 7.1 << "], [" << x0 << ", 38384.4830096, " << z0 + 7.1 << "]]}\n"
         << "bounds: {min: [" << x0 - 40 << ", 38294.9384941, " << z0 << "], max: [" << x0 + 60
         << ", 38422.6068211, " << z0 + 55 << "]}\n"
         << "start: {point: [" << x0 - 20 << ", 38350, " << z0 << "]}\n"
         << "goal: {point: [" << x0 - 20 << ", 38350, " << z0 << "]}\n"
         << "motions: {m: {damper: [0, 0, -1]}}\nstrategies: {s: [m]}\n";
    const CSpace c = CSpace::build(parse_task_string(yaml.str(), "ramp.yaml"));
    for (const ConvexObstacle& ob : c.obstacles())
      for (std::size_t k = 0; k < ob.normals.size(); ++k)
        if (ob.normals[k] == -Vec3::UnitZ()) {
          ++floors;
          covered += c.covered_by_bounds(ob.normals[k], ob.offsets[k]);
          EXPECT_FALSE(c.covered_by_bounds(ob.normals[k], ob.offsets[k] - 1e-6 * c.scale()));
        }
  }
  EXPECT_EQ(floors, 200);
  EXPECT_EQ(covered, 200);
}

TEST(CSpace, ClassifiesPoints) {
  auto task = load_task_from_string(test::kHoleYaml, "hole.yaml");
  const CSpace& c = task->cspace;
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
