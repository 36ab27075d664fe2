// Convex polygon intersection (verifier/internal/face_regions.h `clip`): the hull of each polygon's vertices
// inside the other and the crossings of their edges must be exactly the set that clipping by one edge line
// after another gives (the textbook Sutherland–Hodgman), including the degenerate meets (shared edges and
// vertices, containment, touching, disjoint) that small integer grids make frequent.
#include <gtest/gtest.h>

#include <random>

#include "verifier/internal/face_regions.h"

namespace cmt {
namespace {

face_geometry::Points2 clip_by_edge_lines(const face_geometry::Points2& convex,
                                          const face_geometry::Points2& convex_clip) {
  face_geometry::Points2 out = convex;
  const std::size_t n = convex_clip.size();
  for (std::size_t i = 0; i < n && !out.empty(); ++i) {
    const face_geometry::Point2& p = convex_clip[i];
    const face_geometry::Point2& q = convex_clip[(i + 1) % n];
    const face_geometry::FT dx = q.x() - p.x(), dy = q.y() - p.y();
    out = face_geometry::clip(out, face_geometry::HalfPlane2{-dy, dx, dy * p.x() - dx * p.y()});
  }
  return out;
}

face_geometry::Points2 random_convex(std::mt19937_64& rng, int grid, double offset) {
  std::uniform_int_distribution<int> coordinate(0, grid);
  std::uniform_int_distribution<int> count(3, 7);
  face_geometry::Points2 points;
  for (int k = count(rng); k > 0; --k)
    points.emplace_back(offset + 0.5 * coordinate(rng), offset + 0.25 * coordinate(rng));
  return face_geometry::convex_hull(points);
}

TEST(ConvexClip, EqualsClippingByEachEdgeLine) {
  std::mt19937_64 rng(11);
  int proper = 0, degenerate = 0, empty = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int grid = trial % 3 == 0 ? 3 : 12;  // coarse grids: shared edges and vertices
    const double offset = trial % 5 == 0 ? 1e6 : 0;
    const face_geometry::Points2 a = random_convex(rng, grid, offset), b = random_convex(rng, grid, offset);
    if (a.size() < 3 || b.size() < 3) continue;
    const face_geometry::Points2 fast = face_geometry::clip(a, b), reference = clip_by_edge_lines(a, b);
    ASSERT_EQ(fast, reference) << "trial " << trial;
    (fast.size() >= 3 ? proper : fast.empty() ? empty : degenerate) += 1;
  }
  EXPECT_GT(proper, 500);
  EXPECT_GT(degenerate, 20);  // meets in a shared edge or vertex
  EXPECT_GT(empty, 100);
}

}  // namespace
}  // namespace cmt
