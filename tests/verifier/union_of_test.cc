// union_of: many regions united by pairwise overlays (verifier/internal/face_regions.h).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "verifier/internal/face_regions.h"

namespace cmt::fp {
namespace {

std::vector<Polygon2> read_polygons(const std::string& path) {
  std::ifstream in(path);
  std::vector<Polygon2> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    Polygon2 p;
    double u = 0, v = 0;
    while (words >> u >> v) p.push_back(Point2(u, v));
    out.push_back(p);
  }
  return out;
}

bool all_simple(const PolygonSet2& set) {
  std::vector<PolygonWithHoles2> parts;
  set.polygons_with_holes(std::back_inserter(parts));
  for (const PolygonWithHoles2& p : parts) {
    if (!p.outer_boundary().is_simple()) return false;
    for (auto h = p.holes_begin(); h != p.holes_end(); ++h)
      if (!h->is_simple()) return false;
  }
  return true;
}

FT exact_area(const PolygonSet2& set) {
  std::vector<PolygonWithHoles2> parts;
  set.polygons_with_holes(std::back_inserter(parts));
  FT total = 0;
  for (const PolygonWithHoles2& p : parts) {
    total += p.outer_boundary().area();
    for (auto h = p.holes_begin(); h != p.holes_end(); ++h) total += h->area();  // holes are clockwise
  }
  return total;
}

// Pieces of one slide share edges on the face boundary and on cutting lines; CGAL 5.5's aggregated join of
// them returned a non-simple union in about one run in six (in process, with nothing else changed), and a
// later operation on that union crashed. Every union_of of them is simple and equals the union built by
// joining one piece at a time.
TEST(UnionOf, PiecesOverlappingOnCommonLinesGiveASimpleUnionEveryTime) {
  const std::vector<Polygon2> pieces =
      read_polygons(CMT_SOURCE_DIR "/tests/verifier/data/overlapping_slide_pieces.txt");
  ASSERT_EQ(pieces.size(), 32u);
  PolygonSet2 one_at_a_time;
  for (const Polygon2& p : pieces) {
    ASSERT_TRUE(p.is_simple());
    one_at_a_time.join(p);
  }
  const FT expected = exact_area(one_at_a_time);
  ASSERT_TRUE(all_simple(one_at_a_time));
  for (int run = 0; run < 40; ++run) {
    const PolygonSet2 u = union_of(pieces);
    ASSERT_TRUE(all_simple(u)) << "run " << run;
    EXPECT_EQ(exact_area(u), expected) << "run " << run;
    PolygonSet2 symmetric = u;
    symmetric.symmetric_difference(one_at_a_time);
    EXPECT_TRUE(symmetric.is_empty()) << "run " << run;
  }
}

TEST(UnionOf, OfNothingIsEmptyAndOfOneIsItself) {
  EXPECT_TRUE(union_of(std::vector<Polygon2>{}).is_empty());
  const Polygon2 square = to_polygon({Point2(0, 0), Point2(1, 0), Point2(1, 1), Point2(0, 1)});
  const PolygonSet2 u = union_of(std::vector<Polygon2>{square});
  EXPECT_EQ(exact_area(u), FT(1));
}

TEST(UnionOf, ThreeSquaresOnALineShareEdges) {
  // [0,1]x[0,1], [1,2]x[0,1], [0.5,2.5]x[0,1]: the union is [0,2.5]x[0,1], one polygon without holes.
  const auto box = [](double a, double b) {
    return to_polygon({Point2(a, 0), Point2(b, 0), Point2(b, 1), Point2(a, 1)});
  };
  const PolygonSet2 u = union_of(std::vector<Polygon2>{box(0, 1), box(1, 2), box(0.5, 2.5)});
  EXPECT_EQ(exact_area(u), FT(2.5));
  EXPECT_EQ(u.number_of_polygons_with_holes(), 1u);
}

}  // namespace
}  // namespace cmt::fp
