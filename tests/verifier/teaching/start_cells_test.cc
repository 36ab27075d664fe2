// Halving start regions (verifier/teaching/start_cells.h): the halves cover the region and meet exactly.
#include "verifier/teaching/start_cells.h"

#include <gtest/gtest.h>

namespace cmt::teaching {
namespace {

Region polygon(std::vector<Vec3> points) { return {Region::Kind::kPolygon, std::move(points), "start"}; }

TEST(SplitRegion, ASegmentIsHalvedAtItsMidpoint) {
  const Region s{Region::Kind::kSegment, {Vec3(-1, -3, 0), Vec3(1, -3, 0)}, "start"};
  const std::vector<Region> halves = split_region(s);
  ASSERT_EQ(halves.size(), 2u);
  EXPECT_EQ(halves[0].points[0], Vec3(-1, -3, 0));
  EXPECT_EQ(halves[0].points[1], Vec3(0, -3, 0));
  EXPECT_EQ(halves[1].points[0], Vec3(0, -3, 0));
  EXPECT_EQ(halves[1].points[1], Vec3(1, -3, 0));
  EXPECT_DOUBLE_EQ(region_measure(s), 2);
  EXPECT_DOUBLE_EQ(region_measure(halves[0]) + region_measure(halves[1]), 2);
}

TEST(SplitRegion, APointAndADegenerateSegmentHaveNoHalves) {
  EXPECT_TRUE(split_region({Region::Kind::kPoint, {Vec3(3, 0, 3)}, "start"}).empty());
  EXPECT_TRUE(split_region({Region::Kind::kSegment, {Vec3(1, 2, 3), Vec3(1, 2, 3)}, "start"}).empty());
  EXPECT_EQ(region_measure({Region::Kind::kPoint, {Vec3(3, 0, 3)}, "start"}), 0);
}

TEST(SplitRegion, APolygonIsCutAcrossItsLongestExtentIntoHalvesThatShareTheCut) {
  // A 4 x 1 rectangle on the plane z = 2: the cut is x = 0, across the diagonal-dominated long side.
  const Region r = polygon({Vec3(-2, 0, 2), Vec3(2, 0, 2), Vec3(2, 1, 2), Vec3(-2, 1, 2)});
  const std::vector<Region> halves = split_region(r);
  ASSERT_EQ(halves.size(), 2u);
  EXPECT_DOUBLE_EQ(region_measure(r), 4);
  EXPECT_NEAR(region_measure(halves[0]) + region_measure(halves[1]), 4, 1e-12);
  for (const Region& h : halves) {
    EXPECT_GE(h.points.size(), 3u);
    EXPECT_GT(region_measure(h), 1);  // neither half is a sliver
    for (const Vec3& p : h.points) EXPECT_EQ(p.z(), 2);
  }
  // The cut points appear, bit for bit, in both halves.
  int shared = 0;
  for (const Vec3& p : halves[0].points)
    for (const Vec3& q : halves[1].points) shared += p == q;
  EXPECT_EQ(shared, 2);
}

TEST(SplitRegion, ATriangleHalvesIntoPiecesOfItsArea) {
  const Region t = polygon({Vec3(0, 0, 0), Vec3(3, 0, 1), Vec3(0, 2, 0)});
  const std::vector<Region> halves = split_region(t);
  ASSERT_EQ(halves.size(), 2u);
  EXPECT_NEAR(region_measure(halves[0]) + region_measure(halves[1]), region_measure(t), 1e-12);
  // Halving again keeps covering: four quarters of the same total.
  double quarters = 0;
  for (const Region& h : halves)
    for (const Region& q : split_region(h)) quarters += region_measure(q);
  EXPECT_NEAR(quarters, region_measure(t), 1e-12);
}

}  // namespace
}  // namespace cmt::teaching
