// Halving start regions (start_cells.h).
#include "verifier/teaching/start_cells.h"

#include <cmath>

namespace cmt::teaching {
namespace {

Region with_points(const Region& like, std::vector<Vec3> points) {
  Region out = like;
  out.points = std::move(points);
  return out;
}

// The convex polygon's two sides of the plane (x - c) . d = 0. A crossing point is computed from the edge
// oriented from its negative to its positive end, so both halves receive the same doubles.
std::vector<Region> split_polygon(const Region& polygon) {
  const std::vector<Vec3>& v = polygon.points;
  double longest = 0;
  Vec3 d = Vec3::Zero();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (std::size_t j = i + 1; j < v.size(); ++j)
      if ((v[j] - v[i]).norm() > longest) {
        longest = (v[j] - v[i]).norm();
        d = v[j] - v[i];
      }
  if (longest <= 0) return {};
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : v) c += p;
  c /= static_cast<double>(v.size());
  std::vector<double> side(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) side[i] = (v[i] - c).dot(d);
  std::vector<Vec3> low, high;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::size_t j = (i + 1) % v.size();
    if (side[i] <= 0) low.push_back(v[i]);
    if (side[i] >= 0) high.push_back(v[i]);
    if ((side[i] < 0 && side[j] > 0) || (side[i] > 0 && side[j] < 0)) {
      const std::size_t neg = side[i] < 0 ? i : j, pos = side[i] < 0 ? j : i;
      const double t = side[neg] / (side[neg] - side[pos]);
      const Vec3 x = v[neg] + t * (v[pos] - v[neg]);
      low.push_back(x);
      high.push_back(x);
    }
  }
  if (low.size() < 3 || high.size() < 3) return {};
  return {with_points(polygon, std::move(low)), with_points(polygon, std::move(high))};
}

}  // namespace

std::vector<Region> split_region(const Region& region) {
  switch (region.kind) {
    case Region::Kind::kPoint:
      return {};
    case Region::Kind::kSegment: {
      const Vec3 a = region.points[0], b = region.points[1];
      if (a == b) return {};
      const Vec3 m = 0.5 * (a + b);
      return {with_points(region, {a, m}), with_points(region, {m, b})};
    }
    case Region::Kind::kPolygon:
      return split_polygon(region);
  }
  return {};
}

double region_measure(const Region& region) {
  const std::vector<Vec3>& v = region.points;
  if (region.kind == Region::Kind::kSegment) return (v[1] - v[0]).norm();
  if (region.kind != Region::Kind::kPolygon) return 0;
  Vec3 twice = Vec3::Zero();
  for (std::size_t i = 1; i + 1 < v.size(); ++i) twice += (v[i] - v[0]).cross(v[i + 1] - v[0]);
  return 0.5 * twice.norm();
}

}  // namespace cmt::teaching
