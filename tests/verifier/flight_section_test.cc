// The damper flight's section in doubles (verifier/flight.cc `section_in_doubles`: Minkowski-sum edges,
// interval signs, grown hull) against the exact section of all generator pairs (`section_of_all_pairs`): it
// must contain every exact vertex, exceed the exact section by no more than its rounding pads, and hand thin
// sections (a source on the plane flying away from it) to the exact path so that they stay segments and
// points.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "verifier/internal/damper_flight.h"
#include "verifier/reached_set.h"

namespace cmt {
namespace {

// The exact section of conv(gens) by the chart's plane from every generator pair on opposite sides (the
// reference: it needs no knowledge of which pairs are edges).
face_geometry::Points2 section_of_all_pairs(const std::vector<face_geometry::Point3>& gens,
                                            const face_geometry::FaceChart& chart) {
  const face_geometry::Plane3& h = chart.plane;
  std::vector<face_geometry::FT> s;
  for (const face_geometry::Point3& g : gens)
    s.push_back(h.a() * g.x() + h.b() * g.y() + h.c() * g.z() + h.d());
  face_geometry::Points2 pts;
  for (std::size_t i = 0; i < gens.size(); ++i) {
    if (s[i] == 0) pts.push_back(chart.project(gens[i]));
    if (s[i] <= 0) continue;
    const face_geometry::Point2 p2 = chart.project(gens[i]);
    for (std::size_t j = 0; j < gens.size(); ++j)
      if (s[j] < 0) pts.push_back(p2 + (chart.project(gens[j]) - p2) * (s[i] / (s[i] - s[j])));
  }
  return pts.empty() ? pts : face_geometry::convex_hull(pts);
}

struct Section {
  face_geometry::Points2 doubles, exact, exact_on_edges;
  bool crosses = false, thin = false;
};

Section both(const std::vector<Vec3>& source, const face_geometry::FlightCone& cone,
             const face_geometry::FaceChart& chart) {
  std::vector<Vec3> ring{Vec3::Zero()};
  for (const Vec3& r : cone.rays) ring.push_back(cone.far * r);
  std::vector<face_geometry::Point3> gens;
  for (const Vec3& x : source) gens.push_back(face_geometry::exact(x));
  for (const Vec3& x : source)
    for (const Vec3& r : cone.rays) {
      const Vec3 d = cone.far * r;
      gens.push_back(face_geometry::exact(x) + face_geometry::Vector3(d.x(), d.y(), d.z()));
    }
  Section s;
  std::vector<face_geometry::GeneratorEdge> crossing;
  s.crosses = face_geometry::section_in_doubles(source, ring, chart, &s.doubles, &s.thin, &crossing);
  s.exact = section_of_all_pairs(gens, chart);
  std::vector<face_geometry::Point3> exact_source;
  for (const Vec3& x : source) exact_source.push_back(face_geometry::exact(x));
  s.exact_on_edges = face_geometry::section_exact(exact_source, ring, crossing, chart);
  return s;
}

std::vector<face_geometry::Point2> sorted(face_geometry::Points2 p) {
  std::sort(p.begin(), p.end());
  return p;
}

double area(const face_geometry::Points2& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const face_geometry::Point2& q = p[i];
    const face_geometry::Point2& r = p[(i + 1) % p.size()];
    a += CGAL::to_double(q.x() * r.y() - r.x() * q.y());
  }
  return a / 2;
}

Face face_through(const Vec3& a, const Vec3& b, const Vec3& c) {
  Face f;
  f.normal = (b - a).cross(c - a).normalized();
  f.offset = f.normal.dot(a);
  f.polygon = {a, b, c};
  return f;
}

TEST(FlightSection, DoublesContainTheExactSectionWithinTheirPads) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  auto random_vec = [&](double s) { return Vec3(s * unit(rng), s * unit(rng), s * unit(rng)); };
  int compared = 0, on_plane_sources = 0, thin = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const double scale = trial % 4 == 0 ? 300 : 8;
    const Vec3 origin = trial % 5 == 0 ? Vec3(1e3, -2e3, 5e2) : Vec3::Zero();
    // Axis-aligned planes (as in box scenes) and slanted ones.
    Vec3 a = origin + random_vec(scale), b = a + random_vec(scale), c = a + random_vec(scale);
    if (trial % 2 == 0) b.z() = c.z() = a.z();
    face_geometry::FaceChart chart = face_geometry::make_chart(face_through(a, b, c));
    chart.cell = region_cell(scale);
    // Sources: random points, some of them the face's corners (exactly on its plane).
    std::vector<Vec3> source;
    const int n = 1 + trial % 12;
    for (int k = 0; k < n; ++k)
      source.push_back(k < 3 && trial % 3 == 0 ? (k == 0 ? a : k == 1 ? b : c) : a + random_vec(scale / 4));
    on_plane_sources += trial % 3 == 0;
    const face_geometry::FlightCone cone = face_geometry::flight_cone(
        random_vec(1) + Vec3(0, 0, 1e-3), 0.05 + 0.4 * (unit(rng) + 1), scale + origin.norm());
    const Section s = both(source, cone, chart);
    if (!s.exact.empty()) {
      ASSERT_TRUE(s.crosses) << "trial " << trial << ": the exact section is not empty";
    }
    // A thin section is computed exactly from the edges that can cross: the same vertices as from all pairs.
    if (s.thin) {
      ++thin;
      ASSERT_EQ(sorted(s.exact_on_edges), sorted(s.exact)) << "trial " << trial;
    }
    if (!s.crosses || s.thin || s.exact.size() < 3) continue;
    ++compared;
    for (const face_geometry::Point2& q : s.exact)
      ASSERT_TRUE(face_geometry::inside_closed(s.doubles, q))
          << "trial " << trial << ": an exact vertex lies outside";
    // Grown by at most pad = 1e-14 x (1 + largest coordinate) per side: the excess area is at most the
    // perimeter times that pad plus the pad square, far below 1e-6 of the area for these sizes.
    const double excess = area(s.doubles) - area(s.exact);
    EXPECT_GE(excess, 0) << "trial " << trial;
    EXPECT_LT(excess, 1e-6 * area(s.exact) + 1e-12) << "trial " << trial;
  }
  EXPECT_GT(compared, 150);
  EXPECT_GT(on_plane_sources, 75);
  // Thin sections: one or two source points on a floor z = h, cones pointing up at random.
  for (int trial = 0; trial < 200; ++trial) {
    const double h = 0.1 * (trial % 7), scale = 8;
    face_geometry::FaceChart chart =
        face_geometry::make_chart(face_through(Vec3(0, 0, h), Vec3(1, 0, h), Vec3(0, 1, h)));
    chart.cell = region_cell(scale);
    std::vector<Vec3> source{Vec3(2 * unit(rng), 2 * unit(rng), h)};
    if (trial % 2) source.push_back(Vec3(2 * unit(rng), 2 * unit(rng), h));
    const Vec3 v = random_vec(1) + Vec3(0, 0, 1.8);
    const Section s = both(source, face_geometry::flight_cone(v, 0.5 * (unit(rng) + 1), scale), chart);
    ASSERT_TRUE(s.crosses) << "thin trial " << trial;
    if (!s.thin) continue;
    ++thin;
    ASSERT_EQ(sorted(s.exact_on_edges), sorted(s.exact)) << "thin trial " << trial;
    ASSERT_EQ(s.exact.size(), source.size()) << "thin trial " << trial;
  }
  EXPECT_GT(thin, 100);
}

TEST(FlightSection, ASourceOnThePlaneFlyingAwayKeepsALowerDimensionalSection) {
  // Floor z = 0; the source lies on it; the cone points up (half-angle .3 < pi/2): every generator but the
  // source's vertices is strictly above, so the section is conv(source) itself.
  face_geometry::FaceChart chart =
      face_geometry::make_chart(face_through(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)));
  chart.cell = region_cell(10);
  const face_geometry::FlightCone cone = face_geometry::flight_cone(Vec3(0, 0, 1), 0.3, 10);
  const Section segment = both({Vec3(1, 2, 0), Vec3(3, -1, 0)}, cone, chart);
  ASSERT_TRUE(segment.crosses);
  EXPECT_TRUE(segment.thin);
  ASSERT_EQ(segment.exact.size(), 2u);
  EXPECT_EQ(sorted(segment.exact_on_edges), sorted(segment.exact));
  const Section point = both({Vec3(1, 2, 0)}, cone, chart);
  ASSERT_TRUE(point.crosses);
  EXPECT_TRUE(point.thin);
  ASSERT_EQ(point.exact.size(), 1u);
  EXPECT_EQ(point.exact[0], face_geometry::Point2(1, 2));
  EXPECT_EQ(point.exact_on_edges, point.exact);
  // Lifted by 1e-3 the source misses the floor: no edge can cross it.
  const Section above = both({Vec3(1, 2, 1e-3)}, cone, chart);
  EXPECT_FALSE(above.crosses);
  EXPECT_TRUE(above.exact.empty());
}

}  // namespace
}  // namespace cmt
