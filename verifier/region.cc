// The region kernel of face charts (verifier/internal/face_regions.h, class ChartRegion): Clipper overlays on
// an integer grid. Why a grid and not CGAL's exact polygon sets: docs/verifier-speed.md, "Region kernel".
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "verifier/internal/face_regions.h"

namespace cmt::face_geometry {
namespace {

using ClipperLib::cInt;
using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

// Grid coordinates of chart coordinates on a grid of cell `cell` (a power of two: scaling is exact).
struct Grid {
  double cell;
  double to_grid(double x) const {
    const double g = x / cell;
    if (!(std::abs(g) <= kRegionRangeCells))
      throw std::range_error("a face chart coordinate (" + std::to_string(x) +
                             ") lies beyond the region kernel's range of 2^60 grid cells of " +
                             std::to_string(cell) + " task units from the origin");
    return g;
  }
  // The grid interval [floor, ceil] around an exact coordinate, from its certified double interval.
  std::pair<cInt, cInt> bounds(const FT& x) const {
    const std::pair<double, double> iv = CGAL::to_interval(x);
    return {static_cast<cInt>(std::floor(to_grid(iv.first))),
            static_cast<cInt>(std::ceil(to_grid(iv.second)))};
  }
  cInt nearest(double x) const { return static_cast<cInt>(std::llround(to_grid(x))); }
  Point2 point(const IntPoint& p) const {
    return Point2(static_cast<double>(p.X) * cell, static_cast<double>(p.Y) * cell);
  }
};

void check_cell(double cell) {
  int exponent = 0;
  if (!(cell > 0) || std::frexp(cell, &exponent) != 0.5)
    throw std::logic_error("ChartRegion: the grid cell must be a positive power of two");
}

__int128 cross(const IntPoint& o, const IntPoint& a, const IntPoint& b) {
  return static_cast<__int128>(a.X - o.X) * (b.Y - o.Y) - static_cast<__int128>(a.Y - o.Y) * (b.X - o.X);
}

// Counter-clockwise convex hull without collinear points (Andrew's monotone chain, exact in 128 bits).
Path int_hull(Path pts) {
  std::sort(pts.begin(), pts.end(),
            [](const IntPoint& a, const IntPoint& b) { return a.X < b.X || (a.X == b.X && a.Y < b.Y); });
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if (pts.size() < 3) return {};
  Path hull(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], pts[i - 1]) <= 0) --k;
    hull[k++] = pts[i - 1];
  }
  hull.resize(k - 1);
  return hull.size() >= 3 ? hull : Path{};
}

// A convex polygon rounded outward: the hull of the grid cells that hold its vertices' interval bounds
// contains every vertex, hence the polygon.
Path outward_convex(const Polygon2& polygon, const Grid& grid) {
  Path corners;
  corners.reserve(4 * polygon.size());
  for (auto v = polygon.vertices_begin(); v != polygon.vertices_end(); ++v) {
    const auto [x0, x1] = grid.bounds(v->x());
    const auto [y0, y1] = grid.bounds(v->y());
    corners.push_back({x0, y0});
    corners.push_back({x1, y0});
    corners.push_back({x0, y1});
    corners.push_back({x1, y1});
  }
  return int_hull(std::move(corners));
}

// A simple polygon that is not convex: its vertices rounded to the nearest grid points, offset outward by
// two cells (more than the rounding's 0.71).
Paths outward_simple(const Polygon2& polygon, const Grid& grid) {
  Path path;
  for (auto v = polygon.vertices_begin(); v != polygon.vertices_end(); ++v)
    path.push_back({grid.nearest(CGAL::to_double(v->x())), grid.nearest(CGAL::to_double(v->y()))});
  if (!ClipperLib::Orientation(path)) ClipperLib::ReversePath(path);
  ClipperLib::ClipperOffset offset;
  offset.AddPath(path, ClipperLib::jtMiter, ClipperLib::etClosedPolygon);
  Paths out;
  offset.Execute(out, 2.0);
  return out;
}

Polygon2 to_polygon2(const Path& path, const Grid& grid) {
  Polygon2 out;
  for (const IntPoint& p : path) out.push_back(grid.point(p));
  return out;
}

// Outer contours of a Clipper tree with their holes; islands inside holes become outers of their own.
void collect(const ClipperLib::PolyNode& outer, const Grid& grid, std::vector<PolygonWithHoles2>* out) {
  PolygonWithHoles2 pwh(to_polygon2(outer.Contour, grid));
  for (const ClipperLib::PolyNode* hole : outer.Childs) {
    Polygon2 h = to_polygon2(hole->Contour, grid);
    if (h.orientation() != CGAL::CLOCKWISE) h.reverse_orientation();
    pwh.add_hole(std::move(h));
  }
  if (pwh.outer_boundary().orientation() != CGAL::COUNTERCLOCKWISE)
    pwh.outer_boundary().reverse_orientation();
  out->push_back(std::move(pwh));
  for (const ClipperLib::PolyNode* hole : outer.Childs)
    for (const ClipperLib::PolyNode* island : hole->Childs) collect(*island, grid, out);
}

}  // namespace

ChartRegion::ChartRegion(const Polygon2& polygon, double cell) : cell_(cell) {
  check_cell(cell);
  if (polygon.size() < 3) return;
  const Grid grid{cell};
  if (polygon.is_convex()) {
    Path hull = outward_convex(polygon, grid);
    if (!hull.empty()) paths_.push_back(std::move(hull));
    return;
  }
  if (!polygon.is_simple()) throw std::invalid_argument("ChartRegion: polygon is not simple");
  paths_ = outward_simple(polygon, grid);
}

ChartRegion::ChartRegion(const PolygonWithHoles2& polygon, double cell)
    : ChartRegion(polygon.outer_boundary(), cell) {
  for (auto h = polygon.holes_begin(); h != polygon.holes_end(); ++h) difference(*h);
}

void ChartRegion::overlay(ClipperLib::ClipType type, const ChartRegion& other) {
  if (other.cell_ != cell_) throw std::logic_error("ChartRegion: operands on different grids");
  ClipperLib::Clipper clipper;
  clipper.AddPaths(paths_, ClipperLib::ptSubject, true);
  clipper.AddPaths(other.paths_, ClipperLib::ptClip, true);
  Paths out;
  clipper.Execute(type, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  paths_ = std::move(out);
}

void ChartRegion::join(const ChartRegion& other) {
  if (other.is_empty()) return;
  if (is_empty()) {
    *this = other;
    return;
  }
  overlay(ClipperLib::ctUnion, other);
}

void ChartRegion::difference(const ChartRegion& other) {
  if (is_empty() || other.is_empty()) return;
  overlay(ClipperLib::ctDifference, other);
}

void ChartRegion::difference(const Polygon2& polygon) {
  if (!is_empty()) difference(ChartRegion(polygon, cell_));
}

void ChartRegion::intersection(const ChartRegion& other) {
  if (is_empty()) return;
  if (other.is_empty()) {
    paths_.clear();
    return;
  }
  overlay(ClipperLib::ctIntersection, other);
}

void ChartRegion::intersection(const Polygon2& polygon) {
  if (!is_empty()) intersection(ChartRegion(polygon, cell_));
}

CGAL::Oriented_side ChartRegion::oriented_side(const Point2& p) const {
  if (is_empty()) return CGAL::ON_NEGATIVE_SIDE;
  const Grid grid{cell_};
  const IntPoint q{grid.nearest(CGAL::to_double(p.x())), grid.nearest(CGAL::to_double(p.y()))};
  int winding = 0;
  for (const Path& path : paths_) {
    const int in = ClipperLib::PointInPolygon(q, path);
    if (in < 0) return CGAL::ON_ORIENTED_BOUNDARY;
    if (in > 0) winding += ClipperLib::Orientation(path) ? 1 : -1;
  }
  return winding > 0 ? CGAL::ON_POSITIVE_SIDE : CGAL::ON_NEGATIVE_SIDE;
}

std::vector<PolygonWithHoles2> ChartRegion::polygons_with_holes() const {
  std::vector<PolygonWithHoles2> out;
  if (is_empty()) return out;
  ClipperLib::Clipper clipper;
  clipper.StrictlySimple(true);
  clipper.AddPaths(paths_, ClipperLib::ptSubject, true);
  ClipperLib::PolyTree tree;
  clipper.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  for (const ClipperLib::PolyNode* outer : tree.Childs) collect(*outer, Grid{cell_}, &out);
  return out;
}

double ChartRegion::area() const {
  double total = 0;
  for (const Path& path : paths_) total += ClipperLib::Area(path);
  return total * cell_ * cell_;
}

bool ChartRegion::wider_than(double cells) const {
  if (is_empty()) return false;
  ClipperLib::ClipperOffset offset;
  offset.AddPaths(paths_, ClipperLib::jtMiter, ClipperLib::etClosedPolygon);
  Paths eroded;
  offset.Execute(eroded, -cells / 2);
  return !eroded.empty();
}

ChartRegion ChartRegion::minkowski_sum(const std::vector<std::pair<double, double>>& pattern) const {
  if (is_empty() || pattern.empty()) return *this;
  const Grid grid{cell_};
  // The pattern's hull rounded outward: the hull of the grid cells around its vertices (and the origin).
  Path corners = {{0, 0}};
  for (const auto& [x, y] : pattern) {
    const double gx = grid.to_grid(x), gy = grid.to_grid(y);
    for (double cx : {std::floor(gx), std::ceil(gx)})
      for (double cy : {std::floor(gy), std::ceil(gy)})
        corners.push_back({static_cast<cInt>(cx), static_cast<cInt>(cy)});
  }
  Path hull = int_hull(std::move(corners));
  if (hull.empty()) return *this;
  ChartRegion out;
  out.cell_ = cell_;
  // Clipper's closed Minkowski sum: the region moved by the pattern's first vertex, united with the
  // boundary swept by the pattern (holes shrink as they should).
  ClipperLib::MinkowskiSum(hull, paths_, out.paths_, true);
  out.join(*this);
  return out;
}

ChartRegion ChartRegion::union_of(const std::vector<const ChartRegion*>& parts) {
  ChartRegion out;
  ClipperLib::Clipper clipper;
  for (const ChartRegion* r : parts) {
    if (r->is_empty()) continue;
    if (out.cell_ == 0) out.cell_ = r->cell_;
    if (r->cell_ != out.cell_) throw std::logic_error("ChartRegion: operands on different grids");
    clipper.AddPaths(r->paths_, ClipperLib::ptSubject, true);
  }
  if (out.cell_ == 0) return out;
  clipper.Execute(ClipperLib::ctUnion, out.paths_, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return out;
}

}  // namespace cmt::face_geometry

namespace cmt {

double region_cell(double scale) {
  const double s = std::isfinite(scale) && scale > 0 ? scale : 1.0;
  return std::ldexp(1.0, std::ilogb(s) + 1 - kRegionCellBits);
}

}  // namespace cmt
