// Hand-worked cases for the spring's sticking regions (Buckley §6.7.4, App. B, Fig 3.16).
#include "verifier/spring.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "models/loaded_task.h"
#include "tests/models/test_tasks.h"
#include "verifier/atom_cone.h"
#include "verifier/convex_polygon.h"

namespace cmt {
namespace {

int find_face(const CSpace& c, const Vec3& normal, double offset) {
  for (const Face& f : c.faces())
    if ((f.normal - normal).norm() < 1e-12 && std::abs(f.offset - offset) < 1e-12) return f.id;
  return -1;
}

TEST(Spring, EpsTMatchesTheThesis) {
  Uncertainty u;
  u.theta_v = 0.25;
  u.eps_p = 0.2;
  u.step = 0.2;
  EXPECT_NEAR(eps_t(u), 0.2186, 5e-5);  // Buckley quotes .218 (§5.2); buckley-notes §1: .2186
  EXPECT_GT(eps_o(u), eps_t(u));
}

class HoleBottom : public testing::Test {
 protected:
  void SetUp() override {
    task_ = load_task_from_string(test::kHoleYaml, "hole.yaml");
    bottom_ = find_face(task_->cspace, Vec3::UnitZ(), -2.0);  // the hole bottom z = -2
    ASSERT_GE(bottom_, 0);
    regions_ = spring_sticking_regions(task_->cspace, bottom_, task_->task.uncertainty);
  }
  std::shared_ptr<const LoadedTask> task_;
  int bottom_ = -1;
  SpringStickingRegions regions_;
};

TEST_F(HoleBottom, StrongRegionNeedsDepthAndMargin) {
  // mu = .48 (phi = .4475), theta_v = .25, eps_s = .2, eps_t = .2186: depth >= .2 + .4186 / tan(.1975)
  // = 2.292.
  EXPECT_EQ(classify_spring(regions_, Vec3(0, 0, -2 - 2.5)), StickClass::kMust);
  EXPECT_EQ(classify_spring(regions_, Vec3(0, 0, -2 - 2.2)), StickClass::kMay);
  // Projection .1 from the edge x = 1 (< eps_t): not guaranteed, but possible.
  EXPECT_EQ(classify_spring(regions_, Vec3(0.9, 0, -5)), StickClass::kMay);
}

TEST_F(HoleBottom, WeakRegionBounds) {
  // Parallel plane eps_s outside the face: z <= -1.8.
  EXPECT_EQ(classify_spring(regions_, Vec3(0, 0, -1.9)), StickClass::kMay);
  EXPECT_EQ(classify_spring(regions_, Vec3(0, 0, -1.7)), StickClass::kNever);
  // Edge planes tilted by phi + theta_v = .6975 from the inward normal, through the edge x = 1, moved out by
  // eps_s: (1.3, 0, -3) is .3 across at depth 1 (atan .3 = .29 < .6975): may; (5, 0, -2.5) is 4 across at
  // depth .5: never.
  EXPECT_EQ(classify_spring(regions_, Vec3(1.3, 0, -3)), StickClass::kMay);
  EXPECT_EQ(classify_spring(regions_, Vec3(5, 0, -2.5)), StickClass::kNever);
}

TEST_F(HoleBottom, StickingConfigurationsOnTheFace) {
  const Face& f = task_->cspace.faces()[bottom_];
  // p 2 below the bottom: weak disk radius 2 tan(.6975) + .2 / cos(.6975) = 1.937 covers the 2 x 2 face;
  // strong disk radius (2 − .2 / sin(.1975)) tan(.1975) = .1964.
  const auto conf = face_sticking_configurations(f, Vec3(0, 0, -4), task_->task.uncertainty);
  EXPECT_NEAR(polygon_area(conf.weak, f.normal), 4.0, 1e-9);
  const double alpha = std::atan(0.48) - 0.25;
  const double r = (2 - 0.2 / std::sin(alpha)) * std::tan(alpha);
  const double disk = std::numbers::pi * r * r;
  EXPECT_LE(polygon_area(conf.strong, f.normal), disk);
  EXPECT_GE(polygon_area(conf.strong, f.normal), 0.99 * disk);
  // p above the face: nothing is guaranteed.
  EXPECT_TRUE(face_sticking_configurations(f, Vec3(0, 0, -1.9), task_->task.uncertainty).strong.empty());
}

TEST(SpringConcave, FaceWithPhiPlusThetaBeyondHalfPi) {
  // mu = 1 (phi = .785), theta_v = .9: psi = 1.685 > pi/2. A position .05 above the face centre may stick
  // (from an edge point x = (1, 0, 0) the pull (−1, 0, .05) is 1.621 < psi from −n); far above it may not
  // (2.94 > psi).
  const std::string yaml = R"(
name: grippy
friction: 1.0
uncertainty: {eps_s: 0.01, eps_p: 0.01, theta_v: 0.9, theta_f: 0.1}
cspace:
  - box: {min: [-1, -1, -1], max: [1, 1, 0]}
bounds: {min: [-1, -1, -1], max: [1, 1, 6]}
start: {point: [0, 0, 0]}
goal: {point: [0, 0, 0]}
)";
  auto t = load_task_from_string(yaml, "grippy.yaml");
  const int top = find_face(t->cspace, Vec3::UnitZ(), 0.0);
  ASSERT_GE(top, 0);
  const auto r = spring_sticking_regions(t->cspace, top, t->task.uncertainty);
  EXPECT_EQ(r.weak.kind, Polyhedron::Kind::kComplement);
  EXPECT_EQ(classify_spring(r, Vec3(0, 0, 0.05)), StickClass::kMay);
  EXPECT_EQ(classify_spring(r, Vec3(0, 0, 5)), StickClass::kNever);
  EXPECT_EQ(classify_spring(r, Vec3(0, 0, -1)),
            StickClass::kMay);  // phi < theta_v: never guaranteed on a face
}

TEST_F(HoleBottom, CornerVertexRegions) {
  // The bottom corner (-1, -1, -2): faces +z, +x, +y. Far along −(1,1,1) must stick; above the corner never.
  const CSpace& c = task_->cspace;
  const int corner = c.nearest_atom(Vec3(-1, -1, -2), 1e-9);
  ASSERT_EQ(c.atom_kind(corner), AtomKind::kVertex);
  const auto r = spring_sticking_regions(c, corner, task_->task.uncertainty);
  EXPECT_EQ(classify_spring(r, Vec3(-1, -1, -2) - 5 * Vec3(1, 1, 1).normalized()), StickClass::kMust);
  // Pulling straight out of the corner. The weak region uses the sum of the faces' cones each widened by
  // theta_v (Buckley L2342), which contains the true theta_v-neighbourhood of the vertex cone but not
  // conversely: with half-angles .4475 + .25 = .6975 (tan = .8379) the rim directions (1, -.5925, -.5925) and
  // their permutations sum to -.185 (1, 1, 1), so the over-approximation holds this position and soundness
  // demands "may" (see docs).
  EXPECT_EQ(classify_spring(r, Vec3(-1, -1, -2) + Vec3(1, 1, 1)), StickClass::kMay);
  // Straight below the corner: p − v = (−.1, −.1, −8). The strong region is v + shift + K_s with the shift
  // eps_s / sin(.1975) = 1.0187 along the first generator's inward direction; whichever face that is, the
  // remainder (e.g. (.9187, −.1, −8)) is within atan(.9187 / 8) = .114 < .1975 of −z, inside the bottom's
  // narrowed cone alone: must.
  EXPECT_EQ(classify_spring(r, Vec3(-1, -1, -2) + Vec3(-0.1, -0.1, -8)), StickClass::kMust);
}

TEST_F(HoleBottom, ConcaveEdgeRegions) {
  // The bottom edge along y at x = -1: faces +z and +x (summed cone). Far below-and-outside along −(1,0,1)
  // must stick; far along the edge direction outside the edge's span, or above the bottom, never.
  const CSpace& c = task_->cspace;
  const int edge = c.nearest_atom(Vec3(-1, 0, -2), 1e-9);
  ASSERT_EQ(c.atom_kind(edge), AtomKind::kEdge);
  EXPECT_EQ(c.edges()[c.atom_index(edge)].shape, EdgeShape::kConcave);
  const auto r = spring_sticking_regions(c, edge, task_->task.uncertainty);
  EXPECT_EQ(classify_spring(r, Vec3(-1, 0, -2) - 5 * Vec3(1, 0, 1).normalized()), StickClass::kMust);
  EXPECT_EQ(classify_spring(r, Vec3(-1, 6, -2)), StickClass::kNever);
  EXPECT_EQ(classify_spring(r, Vec3(0, 0, -1)), StickClass::kNever);
}

TEST_F(HoleBottom, ConvexRimEdge) {
  // The hole rim along y at x = -1, z = 0: top face (normal +z, x < -1) and hole wall (normal +x). Its cone
  // is the same sum as a concave edge's (cones depend only on normals), but the free space wraps around it.
  const CSpace& c = task_->cspace;
  const int rim = c.nearest_atom(Vec3(-1, 0, 0), 1e-9);
  ASSERT_EQ(c.atom_kind(rim), AtomKind::kEdge);
  ASSERT_EQ(c.edges()[c.atom_index(rim)].shape, EdgeShape::kConvex);
  const auto r = spring_sticking_regions(c, rim, task_->task.uncertainty);
  // Deep into the obstacle corner along −(1,0,1): inside the summed cone, so sticking may happen (may), but
  // not must: the pull makes 45° with either face's inward normal, beyond phi = .4475, so sliding down the
  // wall (or along the top, off the rim) is also a Coulomb solution.
  EXPECT_EQ(classify_spring(r, Vec3(-1, 0, 0) - 5 * Vec3(1, 0, 1).normalized()), StickClass::kMay);
  // Pulling almost straight down at the rim, a hair toward the wall: on the top face it would stick, but the
  // wall's normal force is tiny, so sliding down the wall is also a solution. Only "inside every face's cone"
  // is certain at a convex edge, and no direction is within phi − theta_v = .1975 of both −z and −x: may.
  EXPECT_EQ(classify_spring(r, Vec3(-1.05, 0, -5)), StickClass::kMay);
  // Out in the free space above the hole (pulling up and into the hole): never.
  EXPECT_EQ(classify_spring(r, Vec3(0, 0, 2)), StickClass::kNever);
}

TEST_F(HoleBottom, ConcaveEdgeMustStickInsideOneFaceCone) {
  // The bottom edge along y at x = -1: pulling straight down (p − x = (.3, ·, −8) from both ends y = ±1 after
  // the 1.02 erosion shift along −z, angle atan(|(.3, 1)| / 7) = .149 < .1975) stays inside the floor's
  // narrowed cone: the wall only adds normal force and friction against any sliding, so sticking is the only
  // solution.
  const CSpace& c = task_->cspace;
  const int edge = c.nearest_atom(Vec3(-1, 0, -2), 1e-9);
  ASSERT_EQ(c.atom_kind(edge), AtomKind::kEdge);
  const auto r = spring_sticking_regions(c, edge, task_->task.uncertainty);
  EXPECT_EQ(classify_spring(r, Vec3(-0.7, 0, -10)), StickClass::kMust);
  // Pulling along the floor, away from the wall (p − x = (4, ·, −.5)): it slides off the edge; the ratio 8 of
  // +x to −z is beyond any direction of the summed cone widened by theta_v (at most tan(.6975) = .84): never.
  EXPECT_EQ(classify_spring(r, Vec3(3, 0, -2.5)), StickClass::kNever);
}

TEST(SpringConvexCorner, DiagonalPullIntoTheBlockIsNotMust) {
  // A convex block corner (mu .48, theta_v .25, eps_s .2), the pull 1.5 in along the diagonal into the block:
  // on the top face the pull's tangential/normal ratio is sqrt 2 > mu, so sliding onto the top (or a side) is
  // a Coulomb solution too. Buckley's summed cone of the three narrowed face cones holds this direction, so
  // a strong region built from that sum would call it "must" and stop the projection at the vertex.
  const std::string yaml = R"(
name: corner
friction: 0.48
uncertainty: {eps_s: 0.2, eps_p: 0.2, theta_v: 0.25, theta_f: 0.05}
cspace:
  - box: {min: [-2, -2, -2], max: [0, 0, 0]}
bounds: {min: [-3, -3, -3], max: [2, 2, 2]}
start: {point: [0, 0, 0]}
goal: {point: [0, 0, 0]}
)";
  auto t = load_task_from_string(yaml, "corner.yaml");
  const int corner = t->cspace.nearest_atom(Vec3(0, 0, 0), 1e-9);
  ASSERT_EQ(t->cspace.atom_kind(corner), AtomKind::kVertex);
  const auto r = spring_sticking_regions(t->cspace, corner, t->task.uncertainty);
  const Vec3 target = -1.5 * Vec3(1, 1, 1).normalized();
  EXPECT_EQ(classify_spring(r, target), StickClass::kMay);
  EXPECT_TRUE(r.strong.empty());  // no direction lies within phi − theta_v of all three inward normals
}

}  // namespace
}  // namespace cmt
