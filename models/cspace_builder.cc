// Exact construction of the configuration space and its atoms (Buckley ch. 2 and §6.1).
//
// 1. C-obstacles: for convex robot part R and convex environment part O, the C-obstacle O ⊕ (−R) is the
// convex
//    hull of the vertex differences o − r (Lozano-Pérez; Buckley §2.2). C-space parts are taken as given.
// 2. Faces: for every oriented plane P carrying an obstacle facet or a bounds wall, the boundary of free
// space on
//    P is (facets on P with outward normal n) minus (facets on P facing −n) minus (cross-sections of
//    obstacles whose interior P cuts), clipped to the bounds box. This regularized Boolean is exact
//    (Polygon_set_2, Epeck) and merges coplanar adjacent facets into maximal regions, which are then split
//    into convex pieces only where they are not convex (planar_regions.cc).
// 3. Vertices are the corners of all faces; edges are the face sides split at every vertex lying on them, so
// a
//    T-junction (a corner of one face on the side of another) is a vertex of the complex, as in Buckley's
//    hole.
// Scale: every step only looks at the obstacles, polygons and points that can matter to it, found through
// conservative bounding boxes (CGAL Box_intersection_d, Zomorodian and Edelsbrunner 2002) and sorted orders;
// the exact predicates then decide as before. For n disjoint obstacles the cost is near-linear.
#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include "models/cspace.h"
#include "models/internal/exact_kernel.h"
#include "models/task_error.h"
#include "models/task_loader.h"
#include "models/task_transform.h"

namespace cmt {

using namespace exact;

namespace {

using Polyhedron = CGAL::Polyhedron_3<Kernel>;

struct ExactObstacle {
  std::vector<Point3> vertices;
  std::vector<Plane3> planes;               // outward: the obstacle lies on the negative side
  std::vector<std::vector<Point3>> facets;  // facet polygons, one per plane
  double friction = 0;
  std::string source;
};

struct ExactFace {
  Plane3 plane;                 // oriented: positive side is free space
  std::vector<Point3> polygon;  // CCW around the plane normal
  double friction = 0;
  bool phantom = false;  // lies on a clipping plane that is not a real wall
};

Point3 to_exact(const Vec3& v) { return Point3(v.x(), v.y(), v.z()); }
Vec3 to_double(const Point3& p) {
  return Vec3(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}

// Projection of an oriented plane to a coordinate plane: drop the axis where the normal is largest; keep the
// other two in cyclic order so that counter-clockwise in 2-D is counter-clockwise about +axis in 3-D.
struct PlaneChart {
  Plane3 plane;
  int drop = 2;
  int u = 0, v = 1;

  explicit PlaneChart(const Plane3& p) : plane(p) {
    const FT ax = CGAL::abs(p.a()), ay = CGAL::abs(p.b()), az = CGAL::abs(p.c());
    if (ax >= ay && ax >= az)
      drop = 0;
    else if (ay >= az)
      drop = 1;
    else
      drop = 2;
    u = (drop + 1) % 3;
    v = (drop + 2) % 3;
  }
  static FT coord(const Point3& p, int i) { return i == 0 ? p.x() : (i == 1 ? p.y() : p.z()); }
  FT coef(int i) const { return i == 0 ? plane.a() : (i == 1 ? plane.b() : plane.c()); }
  Point2 project(const Point3& p) const { return Point2(coord(p, u), coord(p, v)); }
  Point3 lift(const Point2& q) const {
    FT c[3];
    c[u] = q.x();
    c[v] = q.y();
    c[drop] = -(coef(u) * q.x() + coef(v) * q.y() + plane.d()) / coef(drop);
    return Point3(c[0], c[1], c[2]);
  }
  // True when CCW in the chart is CW about the plane normal.
  bool flips() const { return coef(drop) < 0; }
};

ExactObstacle make_obstacle(const std::vector<Point3>& points, double friction, std::string source,
                            const std::string& file) {
  Polyhedron hull;
  CGAL::convex_hull_3(points.begin(), points.end(), hull);
  if (hull.size_of_vertices() < 4 || !hull.is_closed())
    throw TaskError(file, source, "degenerate C-obstacle: its points do not span a solid");
  ExactObstacle ob;
  ob.friction = friction;
  ob.source = std::move(source);
  for (auto v = hull.vertices_begin(); v != hull.vertices_end(); ++v) ob.vertices.push_back(v->point());
  for (auto f = hull.facets_begin(); f != hull.facets_end(); ++f) {
    auto h = f->halfedge();
    const Plane3 plane(h->vertex()->point(), h->next()->vertex()->point(),
                       h->next()->next()->vertex()->point());
    if (std::find(ob.planes.begin(), ob.planes.end(), plane) == ob.planes.end()) ob.planes.push_back(plane);
  }
  for (const Plane3& plane : ob.planes) {
    std::vector<Point3> on;
    for (const Point3& p : ob.vertices)
      if (plane.has_on(p)) on.push_back(p);
    ob.facets.push_back(std::move(on));  // hull order is fixed later in the plane's chart
  }
  return ob;
}

// Closed cross-section of a convex point set's hull with a plane (points, unordered), and whether the plane
// passes through the hull's interior.
std::vector<Point3> cross_section(const std::vector<Point3>& vertices, const Plane3& plane,
                                  bool* cuts_interior) {
  std::vector<Point3> pos, neg, out;
  for (const Point3& p : vertices) {
    switch (plane.oriented_side(p)) {
      case CGAL::ON_POSITIVE_SIDE:
        pos.push_back(p);
        break;
      case CGAL::ON_NEGATIVE_SIDE:
        neg.push_back(p);
        break;
      default:
        out.push_back(p);
    }
  }
  *cuts_interior = !pos.empty() && !neg.empty();
  for (const Point3& a : pos)
    for (const Point3& b : neg) {
      const auto x = CGAL::intersection(plane, Kernel::Segment_3(a, b));
      if (x)
        if (const Point3* p = boost::get<Point3>(&*x)) out.push_back(*p);
    }
  return out;
}

std::vector<Point3> box_corners(const AxisBox& b) {
  std::vector<Point3> c;
  for (int i = 0; i < 8; ++i)
    c.emplace_back((i & 1) ? b.max.x() : b.min.x(), (i & 2) ? b.max.y() : b.min.y(),
                   (i & 4) ? b.max.z() : b.min.z());
  return c;
}

struct PointLess {
  bool operator()(const Point3& a, const Point3& b) const { return CGAL::compare_xyz(a, b) == CGAL::SMALLER; }
};

// A total order on oriented planes: by the coefficients scaled so that the first non-zero normal coordinate
// is ±1, so two planes are equivalent exactly when they are the same oriented plane (CGAL's Plane_3 ==).
// Decided on the interval approximations and only on failure on the exact values, like CGAL's filtered
// predicates: the exact values are computed only for (nearly) equal planes, as Plane_3 == computes them.
template <class NT>
bool scaled_less(const std::array<NT, 4>& p, const std::array<NT, 4>& q) {
  auto scale = [](const std::array<NT, 4>& c) {
    return c[0] != 0 ? CGAL::abs(c[0]) : c[1] != 0 ? CGAL::abs(c[1]) : CGAL::abs(c[2]);
  };
  const NT sp = scale(p), sq = scale(q);
  for (int i = 0; i < 4; ++i) {
    const NT l = p[i] * sq, r = q[i] * sp;
    if (l < r) return true;
    if (r < l) return false;
  }
  return false;
}
template <class P>
auto coefficients(const P& p) {
  return std::array{p.a(), p.b(), p.c(), p.d()};
}
struct PlaneLess {
  bool operator()(const Plane3& p, const Plane3& q) const {
    {
      CGAL::Protect_FPU_rounding<true> protect;
      try {
        return scaled_less(coefficients(CGAL::approx(p)), coefficients(CGAL::approx(q)));
      } catch (CGAL::Uncertain_conversion_exception&) {
      }
    }
    return scaled_less(coefficients(CGAL::exact(p)), coefficients(CGAL::exact(q)));
  }
};

using Box3 = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;
using Box2 = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t>;

// Conservative bounding boxes of exact points (CGAL rounds outwards: the exact points lie inside).
CGAL::Bbox_3 bbox_of(const std::vector<Point3>& pts) {
  CGAL::Bbox_3 b;
  for (const Point3& p : pts) b += p.bbox();
  return b;
}
CGAL::Bbox_2 bbox_of(const Polygon2Points& pts) {
  CGAL::Bbox_2 b;
  for (const Point2& p : pts) b += p.bbox();
  return b;
}

// Groups polygons of one plane whose closed bounding boxes overlap, transitively (union-find over the
// overlapping pairs). Polygons in different groups are disjoint as closed sets, so the regularized Boolean
// of the plane is the union of the Booleans of the groups. Returns a group label per polygon.
std::vector<std::size_t> overlap_groups(const std::vector<const Polygon2Points*>& polys) {
  std::vector<std::size_t> parent(polys.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::vector<Box2> boxes;
  for (std::size_t i = 0; i < polys.size(); ++i)
    if (!polys[i]->empty()) boxes.emplace_back(bbox_of(*polys[i]), i);
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box2& x, const Box2& y) {
    parent[find(x.info())] = find(y.info());
  });
  std::vector<std::size_t> label(polys.size());
  for (std::size_t i = 0; i < polys.size(); ++i) label[i] = find(i);
  return label;
}

// Three lexicographic orders of exact points: coordinates (x, y, z), (y, z, x) and (z, x, y). Along any line
// each order is monotone in the line parameter, so the points strictly inside a segment lie strictly between
// its end points in every order; the order led by the coordinates constant on the segment gives the
// narrowest range.
CGAL::Comparison_result compare_axis(const Point3& p, const Point3& q, int axis) {
  return axis == 0 ? CGAL::compare_x(p, q) : axis == 1 ? CGAL::compare_y(p, q) : CGAL::compare_z(p, q);
}
struct CyclicLess {
  int first = 0;
  bool operator()(const Point3& p, const Point3& q) const {
    for (int k = 0; k < 3; ++k)
      if (const auto r = compare_axis(p, q, (first + k) % 3); r != CGAL::EQUAL) return r == CGAL::SMALLER;
    return false;
  }
};
int leading_equal_coordinates(const Point3& a, const Point3& b, int first) {
  int n = 0;
  while (n < 3 && compare_axis(a, b, (first + n) % 3) == CGAL::EQUAL) ++n;
  return n;
}

// The points of a complex, sorted in the three cyclic orders, to find the points strictly inside a segment.
class SegmentPointIndex {
 public:
  explicit SegmentPointIndex(const std::vector<Point3>& points) : points_(points) {
    for (int o = 0; o < 3; ++o) {
      order_[o].resize(points.size());
      std::iota(order_[o].begin(), order_[o].end(), 0);
      std::sort(order_[o].begin(), order_[o].end(),
                [&](int x, int y) { return CyclicLess{o}(points_[x], points_[y]); });
    }
  }
  // Indices of the points strictly between a and b in the best order: a superset of the points strictly
  // inside segment ab.
  std::vector<int> candidates(const Point3& a, const Point3& b) const {
    int best = 0;
    for (int o = 1; o < 3; ++o)
      if (leading_equal_coordinates(a, b, o) > leading_equal_coordinates(a, b, best)) best = o;
    const CyclicLess less{best};
    const Point3& lo = less(a, b) ? a : b;
    const Point3& hi = less(a, b) ? b : a;
    const auto& order = order_[best];
    auto first = std::upper_bound(order.begin(), order.end(), lo,
                                  [&](const Point3& p, int i) { return less(p, points_[i]); });
    auto last = std::lower_bound(order.begin(), order.end(), hi,
                                 [&](int i, const Point3& p) { return less(points_[i], p); });
    return first < last ? std::vector<int>(first, last) : std::vector<int>{};
  }

 private:
  const std::vector<Point3>& points_;
  std::vector<int> order_[3];
};

}  // namespace

class CSpaceBuilder {
 public:
  explicit CSpaceBuilder(const Task& task) : task_(task) {}

  CSpace build() {
    make_obstacles();
    make_clip_box();
    make_faces();
    make_complex();
    return std::move(out_);
  }

 private:
  void make_obstacles() {
    const std::string& file = task_.source_file;
    if (task_.physical()) {
      std::vector<std::vector<Point3>> diffs;
      for (std::size_t i = 0; i < task_.robot.size(); ++i)
        for (std::size_t j = 0; j < task_.environment.size(); ++j) {
          std::vector<Point3> diff;
          for (const Vec3& o : task_.environment[j].vertices)
            for (const Vec3& r : task_.robot[i].vertices)
              diff.push_back(to_exact(o) + (CGAL::ORIGIN - to_exact(r)));
          diffs.push_back(std::move(diff));
        }
      snap_coincident_coordinates(&diffs);
      for (std::size_t i = 0, k = 0; i < task_.robot.size(); ++i)
        for (std::size_t j = 0; j < task_.environment.size(); ++j, ++k)
          obstacles_.push_back(make_obstacle(diffs[k], task_.environment[j].friction,
                                             task_.robot[i].key + " x " + task_.environment[j].key, file));
    } else {
      for (const ConvexPart& part : task_.cspace) {
        std::vector<Point3> pts;
        for (const Vec3& v : part.vertices) pts.push_back(to_exact(v));
        obstacles_.push_back(make_obstacle(pts, part.friction, part.key, file));
      }
    }
    for (const ExactObstacle& ob : obstacles_) {
      ConvexObstacle c;
      c.friction = ob.friction;
      c.source = ob.source;
      for (const Point3& p : ob.vertices) c.vertices.push_back(to_double(p));
      for (const Plane3& pl : ob.planes) {
        const Vector3 n = pl.orthogonal_vector();
        const Vec3 nd(CGAL::to_double(n.x()), CGAL::to_double(n.y()), CGAL::to_double(n.z()));
        const double len = nd.norm();
        c.normals.push_back(nd / len);
        c.offsets.push_back(-CGAL::to_double(pl.d()) / len);
      }
      out_.obstacles_.push_back(std::move(c));
    }
    drop_repeated_obstacles();
  }

  // Physical form: along each axis, the C-obstacle vertex coordinates and the bounds planes that lie within
  // kCoincidentCoordinateRelativeTolerance x extent of each other (chained in sorted order) become one value,
  // the bounds plane's where one is among them (the bounds stay as given), else the least of them, kept
  // exact. A coordinate no other comes near keeps its exact value. See
  // kCoincidentCoordinateRelativeTolerance.
  void snap_coincident_coordinates(std::vector<std::vector<Point3>>* diffs) const {
    struct Entry {
      double approx;
      FT exact;
      bool wall;
      FT* slot;  // the coordinate it comes from (null for a bounds plane)
    };
    std::vector<std::array<FT, 3>> coords;
    for (const std::vector<Point3>& d : *diffs)
      for (const Point3& p : d) coords.push_back({p.x(), p.y(), p.z()});
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
    for (const auto& c : coords)
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], CGAL::to_double(c[a]));
        hi[a] = std::max(hi[a], CGAL::to_double(c[a]));
      }
    if (task_.bounds) {
      lo = lo.cwiseMin(task_.bounds->min);
      hi = hi.cwiseMax(task_.bounds->max);
    }
    const double tol = kCoincidentCoordinateRelativeTolerance * (hi - lo).norm();
    for (int a = 0; a < 3; ++a) {
      std::vector<Entry> v;
      for (auto& c : coords) v.push_back({CGAL::to_double(c[a]), c[a], false, &c[a]});
      if (task_.bounds)
        for (const double w : {task_.bounds->min[a], task_.bounds->max[a]})
          v.push_back({w, FT(w), true, nullptr});
      std::sort(v.begin(), v.end(), [](const Entry& x, const Entry& y) { return x.exact < y.exact; });
      for (std::size_t b = 0; b < v.size();) {
        std::size_t e = b + 1;
        while (e < v.size() && v[e].approx - v[e - 1].approx <= tol) ++e;
        FT value = v[b].exact;  // the least
        for (std::size_t k = b; k < e; ++k)
          if (v[k].wall) value = v[k].exact;
        for (std::size_t k = b; k < e; ++k)
          if (v[k].slot && *v[k].slot != value) *v[k].slot = value;
        b = e;
      }
    }
    std::size_t k = 0;
    for (std::vector<Point3>& d : *diffs)
      for (Point3& p : d) {
        const auto& c = coords[k++];
        p = Point3(c[0], c[1], c[2]);
      }
  }

  // An obstacle repeated exactly (the same friction and vertex set, as when a file lists a part twice) adds
  // nothing to the union but its cost: every copy carries and cuts the same planes, so the face construction
  // grew with the square of the copies (300 copies of a part took tens of seconds). The faces are built from
  // the first of each; CSpace::obstacles() still lists every one.
  void drop_repeated_obstacles() {
    using Key = std::pair<double, std::vector<Point3>>;
    const auto key_less = [](const Key& a, const Key& b) {
      if (a.first != b.first) return a.first < b.first;
      return std::lexicographical_compare(a.second.begin(), a.second.end(), b.second.begin(), b.second.end(),
                                          PointLess());
    };
    std::set<Key, decltype(key_less)> seen(key_less);
    std::vector<ExactObstacle> distinct;
    for (ExactObstacle& ob : obstacles_) {
      std::vector<Point3> corners = ob.vertices;
      std::sort(corners.begin(), corners.end(), PointLess());
      if (seen.emplace(ob.friction, std::move(corners)).second) distinct.push_back(std::move(ob));
    }
    obstacles_ = std::move(distinct);
  }

  // The clip box: the task bounds where given; otherwise a box strictly containing every obstacle whose walls
  // are phantoms (no atoms). Planar tasks always have phantom walls at |y| = kPlanarClipHalfDepth.
  void make_clip_box() {
    out_.planar_ = task_.dimension == 2;
    if (task_.bounds) {
      clip_ = *task_.bounds;
      for (int s = 0; s < 6; ++s) wall_real_[s] = true;
      out_.bounds_ = *task_.bounds;
      out_.has_bounds_ = true;
    } else {
      Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
      for (const ConvexObstacle& ob : out_.obstacles_)
        for (const Vec3& v : ob.vertices) {
          lo = lo.cwiseMin(v);
          hi = hi.cwiseMax(v);
        }
      clip_.min = lo - Vec3::Constant(1.0);
      clip_.max = hi + Vec3::Constant(1.0);
      for (int s = 0; s < 6; ++s) wall_real_[s] = false;
    }
    if (out_.planar_) {
      clip_.min.y() = -kPlanarClipHalfDepth;
      clip_.max.y() = kPlanarClipHalfDepth;
      wall_real_[2] = wall_real_[3] = false;  // sides 2, 3 are the y walls
    }
    // Walls: side 2k is min of axis k (inward normal +e_k), side 2k+1 is max (inward normal −e_k).
    for (int s = 0; s < 6; ++s) {
      const int axis = s / 2;
      FT n[3] = {0, 0, 0};
      n[axis] = (s % 2 == 0) ? 1 : -1;
      const double coord = (s % 2 == 0) ? clip_.min[axis] : clip_.max[axis];
      // n . x + d = 0 with the plane at x_axis = coord.
      walls_[s] = Plane3(n[0], n[1], n[2], -n[axis] * FT(coord));
    }
    clip_corners_ = box_corners(clip_);
  }

  // Index of the oriented plane in planes_, added on first sight (planes_ keeps first-sight order).
  std::size_t add_plane(const Plane3& p) {
    const auto [it, inserted] = plane_index_.emplace(p, planes_.size());
    if (inserted) {
      planes_.push_back(p);
      plane_obstacles_.emplace_back();
    }
    return it->second;
  }
  std::optional<std::size_t> find_plane(const Plane3& p) const {
    const auto it = plane_index_.find(p);
    if (it == plane_index_.end()) return std::nullopt;
    return it->second;
  }

  // Every oriented plane carrying an obstacle facet (with the obstacles whose facet it carries), then the
  // walls.
  void collect_planes() {
    for (std::size_t i = 0; i < obstacles_.size(); ++i)
      for (const Plane3& p : obstacles_[i].planes) plane_obstacles_[add_plane(p)].push_back(i);
    for (const Plane3& w : walls_) add_plane(w);
  }

  // A box holding every point of `plane` inside `world` (conservative; empty when the plane misses it).
  // Interval arithmetic on the plane's approximation: solved for the coordinate whose coefficient is surely
  // largest in size, over the world's extent in the other two.
  static std::optional<CGAL::Bbox_3> plane_box(const Plane3& plane, const CGAL::Bbox_3& world) {
    using I = CGAL::Interval_nt<false>;
    CGAL::Protect_FPU_rounding<true> protect;
    const auto approx = CGAL::approx(plane);
    const I coef[3] = {approx.a(), approx.b(), approx.c()};
    int k = 0;
    for (int j = 1; j < 3; ++j)
      if (CGAL::abs(coef[j]).inf() > CGAL::abs(coef[k]).inf()) k = j;
    if (CGAL::abs(coef[k]).inf() <= 0) return world;  // no certain leading coefficient: the whole world
    I rest = approx.d();
    for (int j = 0; j < 3; ++j)
      if (j != k) rest += coef[j] * I(world.min(j), world.max(j));
    const I at = -rest / coef[k];
    if (at.sup() < world.min(k) || at.inf() > world.max(k)) return std::nullopt;
    double lo[3] = {world.xmin(), world.ymin(), world.zmin()},
           hi[3] = {world.xmax(), world.ymax(), world.zmax()};
    lo[k] = std::max(lo[k], at.inf());
    hi[k] = std::min(hi[k], at.sup());
    return CGAL::Bbox_3(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
  }

  // For every plane, the obstacles whose bounding box meets the plane: a superset of those the plane cuts.
  std::vector<std::vector<std::size_t>> cut_candidates() const {
    CGAL::Bbox_3 world(clip_.min.x(), clip_.min.y(), clip_.min.z(), clip_.max.x(), clip_.max.y(),
                       clip_.max.z());
    std::vector<Box3> obstacle_boxes, plane_boxes;
    for (std::size_t i = 0; i < obstacles_.size(); ++i) {
      const CGAL::Bbox_3 b = bbox_of(obstacles_[i].vertices);
      obstacle_boxes.emplace_back(b, i);
      world += b;
    }
    for (std::size_t pi = 0; pi < planes_.size(); ++pi)
      if (const auto b = plane_box(planes_[pi], world)) plane_boxes.emplace_back(*b, pi);
    std::vector<std::vector<std::size_t>> out(planes_.size());
    CGAL::box_intersection_d(
        plane_boxes.begin(), plane_boxes.end(), obstacle_boxes.begin(), obstacle_boxes.end(),
        [&](const Box3& plane, const Box3& obstacle) { out[plane.info()].push_back(obstacle.info()); });
    return out;
  }

  // The obstacles that can contribute to plane pi's faces (a facet on it or on its opposite, or a cut by it),
  // in obstacle order.
  std::vector<std::size_t> plane_contributors(std::size_t pi, std::vector<std::size_t> cuts) const {
    cuts.insert(cuts.end(), plane_obstacles_[pi].begin(), plane_obstacles_[pi].end());
    if (const auto opposite = find_plane(planes_[pi].opposite()))
      cuts.insert(cuts.end(), plane_obstacles_[*opposite].begin(), plane_obstacles_[*opposite].end());
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    return cuts;
  }

  void make_faces() {
    collect_planes();
    std::vector<std::vector<std::size_t>> cuts = cut_candidates();
    for (std::size_t pi = 0; pi < planes_.size(); ++pi)
      make_plane_faces(planes_[pi], plane_contributors(pi, std::move(cuts[pi])));
  }

  // The faces on one oriented plane; `contributors` are the only obstacles with a facet on the plane or its
  // opposite or cut by it (the others add nothing).
  void make_plane_faces(const Plane3& plane, const std::vector<std::size_t>& contributors) {
    // A plane facing out of the clip box at one of its walls has no free space on its positive side.
    for (const Plane3& w : walls_)
      if (plane == w.opposite()) return;
    const PlaneChart chart(plane);
    const Plane3 opposite = plane.opposite();

    // Below: facets with outward normal n, grouped by friction; the bounds wall uses the task's friction.
    std::map<double, std::vector<Polygon2Points>, std::greater<>> below_by_friction;
    std::vector<Polygon2Points> above;
    for (const std::size_t i : contributors) {
      const ExactObstacle& ob = obstacles_[i];
      for (std::size_t k = 0; k < ob.planes.size(); ++k) {
        if (ob.planes[k] == plane) below_by_friction[ob.friction].push_back(project(chart, ob.facets[k]));
        if (ob.planes[k] == opposite) above.push_back(project(chart, ob.facets[k]));
      }
      bool cuts = false;
      const std::vector<Point3> section = cross_section(ob.vertices, plane, &cuts);
      if (cuts) above.push_back(project(chart, section));
    }
    bool phantom = false;
    for (int s = 0; s < 6; ++s)
      if (plane == walls_[s]) {
        bool cuts = false;
        below_by_friction[task_.friction].push_back(
            project(chart, cross_section(clip_corners_, plane, &cuts)));
        phantom = !wall_real_[s];
      }
    if (below_by_friction.empty()) return;
    bool cuts_clip = false;
    const Polygon2Points clip = project(chart, cross_section(clip_corners_, plane, &cuts_clip));
    bool on_wall = false;
    for (const Plane3& w : walls_) on_wall = on_wall || plane == w;
    if (!cuts_clip && !on_wall) return;  // the plane misses the clip box's interior
    carve_plane(plane, chart, phantom, clip, above, below_by_friction);
  }

  // Larger friction wins where coplanar facets of different friction overlap (documented in docs/): each
  // friction's facets minus the facets above and the facets of larger friction. The Boolean is done per
  // group of polygons with overlapping bounding boxes (overlap_groups), so its cost follows the groups'
  // sizes, not the plane's polygon count; polygons keep their relative order within a group.
  void carve_plane(const Plane3& plane, const PlaneChart& chart, bool phantom, const Polygon2Points& clip,
                   const std::vector<Polygon2Points>& above,
                   const std::map<double, std::vector<Polygon2Points>, std::greater<>>& below_by_friction) {
    std::vector<const Polygon2Points*> items;  // above, then each friction's facets, largest friction first
    std::vector<std::size_t> rank;             // 0 above, k for the k-th friction
    for (const Polygon2Points& a : above) items.push_back(&a), rank.push_back(0);
    std::size_t r = 0;
    for (const auto& entry : below_by_friction) {
      ++r;
      for (const Polygon2Points& b : entry.second) items.push_back(&b), rank.push_back(r);
    }
    const std::vector<std::size_t> label = overlap_groups(items);
    std::map<std::size_t, std::vector<std::size_t>> groups;  // by label: member items in order
    for (std::size_t i = 0; i < items.size(); ++i) groups[label[i]].push_back(i);
    r = 0;
    for (const auto& [friction, unused] : below_by_friction) {
      ++r;
      for (const auto& entry : groups) {
        std::vector<Polygon2Points> below, taken;
        for (const std::size_t i : entry.second) {
          if (rank[i] == r) below.push_back(*items[i]);
          if (rank[i] < r) taken.push_back(*items[i]);
        }
        if (below.empty()) continue;
        for (const RegionWithHoles& region : planar_region(below, taken, clip, true))
          for (const Polygon2Points& piece : convex_pieces(region))
            add_face(plane, chart, friction, phantom, piece);
      }
    }
  }

  void add_face(const Plane3& plane, const PlaneChart& chart, double friction, bool phantom,
                const Polygon2Points& piece) {
    ExactFace face;
    face.plane = plane;
    face.friction = friction;
    face.phantom = phantom;
    for (const Point2& q : piece) face.polygon.push_back(chart.lift(q));
    if (chart.flips()) std::reverse(face.polygon.begin(), face.polygon.end());
    faces_.push_back(std::move(face));
  }

  static Polygon2Points project(const PlaneChart& chart, const std::vector<Point3>& pts) {
    Polygon2Points out;
    for (const Point3& p : pts) out.push_back(chart.project(p));
    return out;
  }

  bool on_phantom_wall(const Point3& p) const {
    for (int s = 0; s < 6; ++s)
      if (!wall_real_[s] && walls_[s].has_on(p)) return true;
    return false;
  }
  bool on_same_phantom_wall(const Point3& a, const Point3& b) const {
    for (int s = 0; s < 6; ++s)
      if (!wall_real_[s] && walls_[s].has_on(a) && walls_[s].has_on(b)) return true;
    return false;
  }

  // The complex of the faces' sides and corners, before phantom atoms are dropped: corners exactly
  // deduplicated, sides split at every corner on them (edges by their (smaller, larger) point index).
  struct Incidence {
    std::vector<Point3> points;
    std::map<std::pair<int, int>, std::vector<int>> edge_faces;  // the faces (indices) along each edge
    std::vector<std::vector<std::pair<int, int>>> face_edges;    // per face, its edges
    std::vector<std::set<int>> face_points;                      // per face, the points on its boundary
  };

  // The atoms' ids: faces first, then edges, then vertices, each in a stable order.
  struct AtomOrder {
    std::vector<int> faces;                  // face indices
    std::vector<std::pair<int, int>> edges;  // edge keys
    std::vector<int> vertices;               // point indices
    std::vector<int> face_id, vertex_id;     // index -> atom id, -1 for a phantom
    std::map<std::pair<int, int>, int> edge_id;
  };

  void make_complex() {
    const Incidence inc = incidence();
    const AtomOrder order = atom_order(inc);
    emit_faces(inc, order);
    emit_edges(inc, order);
    emit_vertices(inc, order);
    if (order.faces.empty())
      throw TaskError(task_.source_file, task_.bounds ? "bounds" : "",
                      "the free space is empty: the obstacles cover the whole workspace");
  }

  Incidence incidence() const {
    Incidence inc;
    std::map<Point3, int, PointLess> vertex_index;
    for (const ExactFace& f : faces_)
      for (const Point3& p : f.polygon)
        if (vertex_index.emplace(p, static_cast<int>(inc.points.size())).second) inc.points.push_back(p);
    inc.face_edges.resize(faces_.size());
    inc.face_points.resize(faces_.size());
    const SegmentPointIndex point_index(inc.points);
    for (std::size_t fi = 0; fi < faces_.size(); ++fi) {
      const auto& poly = faces_[fi].polygon;
      for (std::size_t k = 0; k < poly.size(); ++k) {
        const Point3& a = poly[k];
        const Point3& b = poly[(k + 1) % poly.size()];
        std::vector<int> on{vertex_index.at(a)};
        const std::vector<int> inner = points_inside_side(inc.points, point_index, a, b);
        on.insert(on.end(), inner.begin(), inner.end());
        on.push_back(vertex_index.at(b));
        for (std::size_t s = 0; s + 1 < on.size(); ++s) {
          const auto key = std::minmax(on[s], on[s + 1]);
          auto& list = inc.edge_faces[{key.first, key.second}];
          if (list.empty() || list.back() != static_cast<int>(fi)) list.push_back(static_cast<int>(fi));
          inc.face_edges[fi].push_back({key.first, key.second});
          inc.face_points[fi].insert(on[s]);
        }
      }
    }
    return inc;
  }

  // The points strictly inside the side (a, b), ordered from a (exact predicates).
  static std::vector<int> points_inside_side(const std::vector<Point3>& points,
                                             const SegmentPointIndex& index, const Point3& a,
                                             const Point3& b) {
    std::vector<int> inner;
    for (const int pi : index.candidates(a, b)) {
      const Point3& p = points[pi];
      if (p != a && p != b && CGAL::collinear(a, p, b) &&
          CGAL::collinear_are_strictly_ordered_along_line(a, p, b))
        inner.push_back(pi);
    }
    std::sort(inner.begin(), inner.end(),
              [&](int x, int y) { return CGAL::has_smaller_distance_to_point(a, points[x], points[y]); });
    return inner;
  }

  // The real atoms, in a stable order: faces by (normal, offset, lowest corner), vertices and edges by
  // coordinates; phantom faces (on walls the bounds only add) and atoms on them are dropped.
  AtomOrder atom_order(const Incidence& inc) const {
    AtomOrder order;
    for (std::size_t i = 0; i < faces_.size(); ++i)
      if (!faces_[i].phantom) order.faces.push_back(static_cast<int>(i));
    std::vector<std::vector<double>> face_keys(faces_.size());
    for (const int i : order.faces) face_keys[i] = face_sort_key(faces_[i]);
    std::sort(order.faces.begin(), order.faces.end(),
              [&](int a, int b) { return face_keys[a] < face_keys[b]; });

    const std::vector<Point3>& points = inc.points;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (!on_phantom_wall(points[i])) order.vertices.push_back(static_cast<int>(i));
    std::sort(order.vertices.begin(), order.vertices.end(),
              [&](int a, int b) { return PointLess()(points[a], points[b]); });

    for (const auto& [key, fl] : inc.edge_faces) {
      bool real_face = false;
      for (int f : fl) real_face = real_face || !faces_[f].phantom;
      if (real_face && !on_same_phantom_wall(points[key.first], points[key.second]))
        order.edges.push_back(key);
    }
    std::sort(order.edges.begin(), order.edges.end(), [&](const auto& a, const auto& b) {
      const Point3 &a0 = points[a.first], &a1 = points[a.second], &b0 = points[b.first],
                   &b1 = points[b.second];
      const Point3& alo = PointLess()(a0, a1) ? a0 : a1;
      const Point3& ahi = PointLess()(a0, a1) ? a1 : a0;
      const Point3& blo = PointLess()(b0, b1) ? b0 : b1;
      const Point3& bhi = PointLess()(b0, b1) ? b1 : b0;
      if (alo != blo) return PointLess()(alo, blo);
      return PointLess()(ahi, bhi);
    });

    const int nf = static_cast<int>(order.faces.size());
    const int ne = static_cast<int>(order.edges.size());
    order.face_id.assign(faces_.size(), -1);
    order.vertex_id.assign(points.size(), -1);
    for (int i = 0; i < nf; ++i) order.face_id[order.faces[i]] = i;
    for (int i = 0; i < static_cast<int>(order.vertices.size()); ++i)
      order.vertex_id[order.vertices[i]] = nf + ne + i;
    for (int i = 0; i < ne; ++i) order.edge_id[order.edges[i]] = nf + i;
    return order;
  }

  // A face's place in the order: its unit normal (negated), offset and lowest corner, in doubles.
  static std::vector<double> face_sort_key(const ExactFace& f) {
    const Vector3 n = f.plane.orthogonal_vector();
    const double len = std::sqrt(CGAL::to_double(n.squared_length()));
    std::vector<double> key{-CGAL::to_double(n.x()) / len, -CGAL::to_double(n.y()) / len,
                            -CGAL::to_double(n.z()) / len, CGAL::to_double(f.plane.d()) / len};
    Point3 lowest = f.polygon[0];
    for (const Point3& p : f.polygon)
      if (PointLess()(p, lowest)) lowest = p;
    const Vec3 l = to_double(lowest);
    key.insert(key.end(), {l.x(), l.y(), l.z()});
    return key;
  }

  // The faces in doubles with their edges and vertices, and the C-space's scale: the diagonal of their
  // bounding box (1 without faces).
  void emit_faces(const Incidence& inc, const AtomOrder& order) {
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (int i = 0; i < static_cast<int>(order.faces.size()); ++i) {
      const ExactFace& ef = faces_[order.faces[i]];
      Face f;
      f.id = i;
      const Vector3 n = ef.plane.orthogonal_vector();
      const Vec3 nd(CGAL::to_double(n.x()), CGAL::to_double(n.y()), CGAL::to_double(n.z()));
      const double len = nd.norm();
      f.normal = nd / len;
      f.offset = -CGAL::to_double(ef.plane.d()) / len;
      f.friction = ef.friction;
      for (const Point3& p : ef.polygon) {
        f.polygon.push_back(to_double(p));
        for (int k = 0; k < 3; ++k) {
          lo[k] = std::min(lo[k], f.polygon.back()[k]);
          hi[k] = std::max(hi[k], f.polygon.back()[k]);
        }
      }
      for (const auto& key : inc.face_edges[order.faces[i]])
        if (auto it = order.edge_id.find(key); it != order.edge_id.end()) f.edges.push_back(it->second);
      for (int p : inc.face_points[order.faces[i]])
        if (order.vertex_id[p] >= 0) f.vertices.push_back(order.vertex_id[p]);
      std::sort(f.edges.begin(), f.edges.end());
      std::sort(f.vertices.begin(), f.vertices.end());
      out_.faces_.push_back(std::move(f));
    }
    double diag2 = 0;
    for (int k = 0; k < 3; ++k) diag2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    out_.scale_ = order.faces.empty() ? 1.0 : std::sqrt(diag2);
  }

  // The edges, each from its lower end to its upper one (PointLess), with its faces and shape.
  void emit_edges(const Incidence& inc, const AtomOrder& order) {
    const int nf = static_cast<int>(order.faces.size());
    for (int i = 0; i < static_cast<int>(order.edges.size()); ++i) {
      const auto [pa, pb] = order.edges[i];
      Edge e;
      e.id = nf + i;
      const bool swap = !PointLess()(inc.points[pa], inc.points[pb]);
      const int a = swap ? pb : pa, b = swap ? pa : pb;
      e.a = to_double(inc.points[a]);
      e.b = to_double(inc.points[b]);
      e.vertex_a = order.vertex_id[a];
      e.vertex_b = order.vertex_id[b];
      const std::vector<int>& along = inc.edge_faces.at(order.edges[i]);
      for (int f : along)
        if (order.face_id[f] >= 0) e.faces.push_back(order.face_id[f]);
      std::sort(e.faces.begin(), e.faces.end());
      e.shape = classify_edge(along, inc.points[a], inc.points[b]);
      out_.edges_.push_back(std::move(e));
    }
  }

  // The vertices with the faces and edges at them (after emit_faces and emit_edges).
  void emit_vertices(const Incidence& inc, const AtomOrder& order) {
    const int first = static_cast<int>(order.faces.size() + order.edges.size());
    for (std::size_t i = 0; i < order.vertices.size(); ++i) {
      Vertex v;
      v.id = first + static_cast<int>(i);
      v.point = to_double(inc.points[order.vertices[i]]);
      out_.vertices_.push_back(std::move(v));
    }
    for (const Face& f : out_.faces_)
      for (int v : f.vertices) out_.vertices_[v - first].faces.push_back(f.id);
    for (const Edge& e : out_.edges_)
      for (int v : {e.vertex_a, e.vertex_b})
        if (v >= 0) out_.vertices_[v - first].edges.push_back(e.id);
  }

  // Buckley's convex/concave edges, decided exactly: face 1 lies on the free side of face 2's plane ⇒
  // concave.
  EdgeShape classify_edge(const std::vector<int>& fl, const Point3& a, const Point3& b) const {
    if (fl.size() != 2) return EdgeShape::kNonManifold;
    const ExactFace& f1 = faces_[fl[0]];
    const ExactFace& f2 = faces_[fl[1]];
    if (f1.plane == f2.plane) return EdgeShape::kFlat;
    if (f1.plane == f2.plane.opposite()) return EdgeShape::kNonManifold;
    for (const Point3& p : f1.polygon) {
      if (CGAL::collinear(a, b, p)) continue;
      switch (f2.plane.oriented_side(p)) {
        case CGAL::ON_POSITIVE_SIDE:
          return EdgeShape::kConcave;
        case CGAL::ON_NEGATIVE_SIDE:
          return EdgeShape::kConvex;
        default:
          break;
      }
    }
    return EdgeShape::kFlat;
  }

  const Task& task_;
  std::vector<ExactObstacle> obstacles_;
  AxisBox clip_;
  bool wall_real_[6] = {false, false, false, false, false, false};
  Plane3 walls_[6];
  std::vector<Point3> clip_corners_;
  std::vector<Plane3> planes_;                             // distinct oriented planes, first-sight order
  std::map<Plane3, std::size_t, PlaneLess> plane_index_;   // into planes_
  std::vector<std::vector<std::size_t>> plane_obstacles_;  // per plane: obstacles with a facet on it
  std::vector<ExactFace> faces_;
  CSpace out_;
};

// The C-space built in the task's own axes (Task::axes) and turned into the world: faces, edges, vertices,
// C-obstacles and bounds mapped by the signed permutation `axes`, exactly. The scale and the atom order are
// the own-axes build's, so a task turned together with its axes has the turned C-space atom for atom.
CSpace CSpace::build(const Task& task) {
  if (task.axes.isIdentity()) return CSpaceBuilder(task).build();
  const Task own = geometry_in_own_axes(task);
  CSpace c = CSpaceBuilder(own).build();
  const Eigen::Matrix3d& r = task.axes;
  const auto box = [&](const AxisBox& b) {
    const Vec3 a = r * b.min, d = r * b.max;
    return AxisBox{a.cwiseMin(d), a.cwiseMax(d)};
  };
  for (Face& f : c.faces_) {
    f.normal = r * f.normal;
    for (Vec3& p : f.polygon) p = r * p;
  }
  for (Edge& e : c.edges_) e.a = r * e.a, e.b = r * e.b;
  for (Vertex& v : c.vertices_) v.point = r * v.point;
  for (ConvexObstacle& o : c.obstacles_) {
    for (Vec3& n : o.normals) n = r * n;
    for (Vec3& p : o.vertices) p = r * p;
  }
  c.bounds_ = box(c.bounds_);
  return c;
}

}  // namespace cmt
