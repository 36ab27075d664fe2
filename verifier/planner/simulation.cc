// Buckley's simulation of an atom for type 1 arcs (simulation.h, §6.7).
#include "verifier/planner/simulation.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>

#include "verifier/atom_cone.h"
#include "verifier/convex_polygon.h"
#include "verifier/sensing.h"
#include "verifier/spring.h"
#include "verifier/spring_projection.h"

namespace cmt::planner {
namespace {

// Relative tolerances (x the C-space's scale) of the facet test in flight_reach: a generator within this of
// a candidate plane is tight on it. Only decides which valid supporting planes are kept; every kept plane is
// valid, so the set stays an over-approximation.
constexpr double kTightRelative = 1e-9;
// A point of A within this (x scale) of B's closure is shared by the two closures.
constexpr double kSharedRelative = 1e-9;
// A face whose friction angle plus theta_v reaches this (radians, below pi/2) has no goal sticking set: the
// disc where the robot may stick grows without bound with the depth of p.
constexpr double kMaxGoalStickAngle = 1.5;

Vec3 centroid(const std::vector<Vec3>& points) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : points) c += p;
  return c / static_cast<double>(points.size());
}

// The unit normal, in face f's plane, of the line through a and b, pointing out of the face.
Vec3 outward_in_plane(const Face& f, const Vec3& a, const Vec3& b) {
  Vec3 m = (b - a).cross(f.normal).normalized();
  if (m.dot(centroid(f.polygon) - a) > 0) m = -m;
  return m;
}

// p . d >= level, as a half-space.
HalfSpace at_least(const Vec3& d, double level) { return {-d, -level}; }

// Rank (0..3) of a set of vectors, relative to their largest length.
int rank_of(const std::vector<Vec3>& vectors, double tolerance) {
  if (vectors.empty()) return 0;
  Eigen::MatrixXd m(3, static_cast<Eigen::Index>(vectors.size()));
  for (std::size_t i = 0; i < vectors.size(); ++i) m.col(static_cast<Eigen::Index>(i)) = vectors[i];
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(m);
  const auto& s = svd.singularValues();
  int r = 0;
  for (Eigen::Index i = 0; i < s.size(); ++i)
    if (s[i] > tolerance * std::max(1.0, s[0])) ++r;
  return r;
}

// Facets of conv(points) + cone(rays) for a full-dimensional set: candidate normals are cross products of
// pairs of `directions`; a candidate is kept when it is valid (no ray has a positive component along it, so
// the half-space holds the set) and tight on generators spanning a plane (a facet). Every kept half-space
// holds the set, so their intersection is an over-approximation, exact when the directions include every
// facet's spanning pair. Empty when no candidate is valid.
std::vector<HalfSpace> facets(const std::vector<Vec3>& points, const std::vector<Vec3>& rays,
                              const std::vector<Vec3>& directions, double scale) {
  std::vector<Vec3> unit_rays;
  for (const Vec3& r : rays)
    if (r.norm() > 0) unit_rays.push_back(r.normalized());
  const double tight = kTightRelative * scale;
  std::vector<HalfSpace> out;
  for (std::size_t i = 0; i < directions.size(); ++i)
    for (std::size_t j = i + 1; j < directions.size(); ++j) {
      const Vec3 c = directions[i].cross(directions[j]);
      if (c.norm() < 1e-9) continue;
      for (const Vec3& u : {Vec3(c.normalized()), Vec3(-c.normalized())}) {
        if (std::any_of(unit_rays.begin(), unit_rays.end(),
                        [&](const Vec3& r) { return u.dot(r) > kPolarSlack; }))
          continue;
        double h = -std::numeric_limits<double>::infinity();
        for (const Vec3& x : points) h = std::max(h, u.dot(x));
        if (std::any_of(out.begin(), out.end(), [&](const HalfSpace& e) {
              return (e.normal - u).norm() < 1e-9 && std::abs(e.offset - h) <= tight;
            }))
          continue;
        std::vector<Vec3> span;
        const Vec3* base = nullptr;
        for (const Vec3& x : points)
          if (h - u.dot(x) <= tight) {
            if (base == nullptr)
              base = &x;
            else
              span.push_back(x - *base);
          }
        for (const Vec3& r : unit_rays)
          if (std::abs(u.dot(r)) <= 1e-9) span.push_back(r);
        if (rank_of(span, 1e-9) >= 2) out.push_back({u, h});
      }
    }
  return out;
}

// The rays that span cone(rays): when the rays are pointed (all within 90 degrees of their mean, by a
// margin), those whose central projection onto the plane across the mean is a corner of the projections' 2-D
// convex hull (points on the hull's edges are kept); otherwise all of them. Only narrows facets()'s candidate
// directions: the validity test still uses every ray.
std::vector<Vec3> extreme_rays(const std::vector<Vec3>& rays) {
  Vec3 mean = Vec3::Zero();
  for (const Vec3& r : rays)
    if (r.norm() > 0) mean += r.normalized();
  if (mean.norm() < 1e-9) return rays;
  mean.normalize();
  const Vec3 e1 = mean.unitOrthogonal(), e2 = mean.cross(e1);
  std::vector<std::pair<Eigen::Vector2d, std::size_t>> projected;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const double along = rays[i].dot(mean);
    if (along <= 1e-6 * rays[i].norm()) return rays;  // not pointed
    const Vec3 q = rays[i] / along;
    projected.push_back({Eigen::Vector2d(q.dot(e1), q.dot(e2)), i});
  }
  std::sort(projected.begin(), projected.end(), [](const auto& a, const auto& b) {
    return a.first.x() < b.first.x() || (a.first.x() == b.first.x() && a.first.y() < b.first.y());
  });
  // Andrew's monotone chain, keeping collinear points (a right turn, strictly, removes).
  const auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<std::size_t> hull;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t base = hull.size();
    for (std::size_t k = 0; k < projected.size(); ++k) {
      const auto& pt = projected[pass == 0 ? k : projected.size() - 1 - k];
      while (hull.size() >= base + 2 &&
             cross(projected[hull[hull.size() - 2]].first, projected[hull.back()].first, pt.first) < -1e-12)
        hull.pop_back();
      hull.push_back(pass == 0 ? k : projected.size() - 1 - k);
    }
  }
  std::vector<Vec3> out;
  std::vector<bool> taken(rays.size(), false);
  for (std::size_t h : hull)
    if (!taken[projected[h].second])
      taken[projected[h].second] = true, out.push_back(rays[projected[h].second]);
  return out;
}

}  // namespace

bool atoms_connected(const CSpace& cspace, int a, int b) {
  const auto bounds = [&](int outer, int inner) {
    const auto has = [](const std::vector<int>& v, int x) {
      return std::find(v.begin(), v.end(), x) != v.end();
    };
    switch (cspace.atom_kind(outer)) {
      case AtomKind::kFace: {
        const Face& f = cspace.faces()[cspace.atom_index(outer)];
        return has(f.edges, inner) || has(f.vertices, inner);
      }
      case AtomKind::kEdge: {
        const Edge& e = cspace.edges()[cspace.atom_index(outer)];
        return e.vertex_a == inner || e.vertex_b == inner;
      }
      case AtomKind::kVertex:
        return false;
    }
    return false;
  };
  return bounds(a, b) || bounds(b, a);
}

AxisBox atoms_box(const CSpace& cspace) {
  AxisBox box{Vec3::Constant(std::numeric_limits<double>::infinity()),
              Vec3::Constant(-std::numeric_limits<double>::infinity())};
  for (int atom = 0; atom < cspace.atom_count(); ++atom)
    for (const Vec3& p : atom_points(cspace, atom)) {
      box.min = box.min.cwiseMin(p);
      box.max = box.max.cwiseMax(p);
    }
  return box;
}

AxisBox planner_domain(const CSpace& cspace) {
  AxisBox box = atoms_box(cspace);
  const double grow = (box.max - box.min).norm();
  box.min.array() -= grow;
  box.max.array() += grow;
  return box;
}

AtomSimulation::AtomSimulation(const CSpace& cspace, const Uncertainty& u, GoalStops goal_stops)
    : cspace_(cspace),
      u_(u),
      goal_stops_(std::move(goal_stops)),
      domain_(planner_domain(cspace)),
      eps_t_(eps_t(u)),
      eps_o_(eps_o(u)),
      weak_stick_(static_cast<std::size_t>(cspace.atom_count())),
      strong_stick_(static_cast<std::size_t>(cspace.atom_count())),
      goal_stick_(static_cast<std::size_t>(cspace.atom_count())),
      reach_(static_cast<std::size_t>(cspace.atom_count()) * static_cast<std::size_t>(cspace.atom_count())) {}

namespace {

// The set cached in `slot`, made on first use.
template <class Make>
const CPositionSet& cached(std::optional<CPositionSet>& slot, const Make& make) {
  if (!slot) slot.emplace(make());
  return *slot;
}

}  // namespace

const CPositionSet& AtomSimulation::weak_sticking(int atom) {
  return cached(weak_stick_.at(static_cast<std::size_t>(atom)),
                [&] { return CPositionSet::of(spring_weak_region(cspace_, atom, u_), domain_); });
}

const CPositionSet& AtomSimulation::strong_sticking(int atom) {
  return cached(strong_stick_.at(static_cast<std::size_t>(atom)),
                [&] { return CPositionSet::of_union(spring_strong_regions(cspace_, atom, u_), domain_); });
}

const CPositionSet& AtomSimulation::goal_sticking(int atom) {
  return cached(goal_stick_.at(static_cast<std::size_t>(atom)), [&] {
    CPositionSet out = CPositionSet::none(domain_);
    if (cspace_.atom_kind(atom) != AtomKind::kFace) return out;
    const Face& f = cspace_.faces()[cspace_.atom_index(atom)];
    const double alpha = std::atan(f.friction) + u_.theta_v;
    if (alpha >= kMaxGoalStickAngle) return out;  // the sticking disc is unbounded
    const double t = std::tan(alpha);
    for (const PartialGoalFace& g : goal_stops_.partial_faces) {
      if (g.atom != atom) continue;
      // m . p + t (offset - n . p) <= c - eps_s (1 + t), the depth d = offset - n . p (goal_stops.h).
      std::vector<HalfSpace> hs;
      for (const HalfSpace& side : g.sides) {
        const Vec3 normal = side.normal - t * f.normal;
        const double offset = side.offset - u_.eps_s * (1 + t) - t * f.offset;
        hs.push_back({normal.normalized(), offset / normal.norm()});
      }
      out = out.unite(weak_sticking(atom).intersect(CPositionSet::convex(hs, domain_)));
    }
    return out;
  });
}

const CPositionSet& AtomSimulation::free_rest() {
  if (free_rest_) return *free_rest_;
  const double r = spring_rest_radius(u_);
  CPositionSet rest = CPositionSet::domain(domain_);
  if (cspace_.has_bounds()) {
    AxisBox grown = cspace_.bounds();
    grown.min.array() -= r;
    grown.max.array() += r;
    rest = rest.intersect(CPositionSet::convex(box_halfspaces(grown), domain_));
  }
  // Each obstacle shrunk by r: a point deeper than r inside one obstacle is farther than r from free space.
  for (const ConvexObstacle& o : cspace_.obstacles()) {
    std::vector<HalfSpace> eroded;
    for (std::size_t i = 0; i < o.normals.size(); ++i) eroded.push_back({o.normals[i], o.offsets[i] - r});
    rest = rest.minus(CPositionSet::convex(eroded, domain_));
  }
  free_rest_ = std::move(rest);
  return *free_rest_;
}

CPositionSet AtomSimulation::connected_reach(int from, int to) const {
  const double r = eps_t_ + eps_o_;
  std::vector<int> common_faces;
  for (int atom : {from, to})
    if (cspace_.atom_kind(atom) == AtomKind::kFace) common_faces = {atom};
  if (common_faces.empty()) {  // an edge and one of its ends
    const int edge = cspace_.atom_kind(from) == AtomKind::kEdge ? from : to;
    common_faces = cspace_.edges()[cspace_.atom_index(edge)].faces;
  }
  CPositionSet out = CPositionSet::none(domain_);
  for (int face_atom : common_faces) {
    const Face& f = cspace_.faces()[cspace_.atom_index(face_atom)];
    std::vector<HalfSpace> hs = {{f.normal, f.offset + u_.eps_s}};
    const auto edge_normal = [&](int edge_atom) {
      const Edge& e = cspace_.edges()[cspace_.atom_index(edge_atom)];
      return std::pair{outward_in_plane(f, e.a, e.b), e.a};
    };
    const auto edges_at = [&](int vertex_atom) {
      std::vector<int> out;
      for (int e : f.edges) {
        const Edge& edge = cspace_.edges()[cspace_.atom_index(e)];
        if (edge.vertex_a == vertex_atom || edge.vertex_b == vertex_atom) out.push_back(e);
      }
      return out;
    };
    const AtomKind kf = cspace_.atom_kind(from), kt = cspace_.atom_kind(to);
    if (kf == AtomKind::kFace && kt == AtomKind::kEdge) {
      const auto [m, a] = edge_normal(to);
      hs.push_back(at_least(m, m.dot(a) - r));
    } else if (kf == AtomKind::kFace && kt == AtomKind::kVertex) {
      const Vec3 v = cspace_.vertices()[cspace_.atom_index(to)].point;
      for (int e : edges_at(to))
        hs.push_back(at_least(edge_normal(e).first, edge_normal(e).first.dot(v) - r));
    } else if (kf == AtomKind::kEdge && kt == AtomKind::kFace) {
      const auto [m, a] = edge_normal(from);
      hs.push_back({m, m.dot(a) + r});
    } else if (kf == AtomKind::kVertex && kt == AtomKind::kFace) {
      const Vec3 v = cspace_.vertices()[cspace_.atom_index(from)].point;
      for (int e : edges_at(from)) hs.push_back({edge_normal(e).first, edge_normal(e).first.dot(v) + r});
    } else {  // an edge and one of its ends: cross the plane through the end, perpendicular to the edge
      const bool edge_first = kf == AtomKind::kEdge;
      const Edge& e = cspace_.edges()[cspace_.atom_index(edge_first ? from : to)];
      const int vertex = edge_first ? to : from;
      const Vec3 v = e.vertex_a == vertex ? e.a : e.b, other = e.vertex_a == vertex ? e.b : e.a;
      const Vec3 d = edge_first ? Vec3((v - other).normalized()) : Vec3((other - v).normalized());
      hs.push_back(at_least(d, d.dot(v) - r));
    }
    out = out.unite(CPositionSet::convex(hs, domain_));
  }
  return out;
}

CPositionSet AtomSimulation::flight_reach(int from, int to) const {
  std::vector<Vec3> source = atom_points(cspace_, from);
  const std::vector<Vec3> target = atom_points(cspace_, to);
  const double scale = cspace_.scale();
  std::vector<Vec3> shared;
  for (const Vec3& p : source)
    if (cspace_.distance_to_atom(p, to) <= kSharedRelative * scale) shared.push_back(p);
  if (!shared.empty()) {  // touching closures: leave A's part near the shared boundary to the boundary atom
    const double r_clip = 2 * eps_t_ + eps_o_;
    Vec3 d;
    if (shared.size() >= 2 && cspace_.atom_kind(from) == AtomKind::kFace)
      d = outward_in_plane(cspace_.faces()[cspace_.atom_index(from)], shared[0], shared[1]);
    else
      d = (shared[0] - centroid(source)).normalized();
    source = clip_to_halfspace(source, d, d.dot(shared[0]) - r_clip);
    if (source.empty()) return CPositionSet::none(domain_);
  }
  std::vector<Vec3> grown, rays, directions;
  for (const Vec3& b : target)
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 e((corner & 1) ? eps_t_ : -eps_t_, (corner & 2) ? eps_t_ : -eps_t_,
                   (corner & 4) ? eps_t_ : -eps_t_);
      grown.push_back(b + e);
    }
  for (const Vec3& b : grown)
    for (const Vec3& a : source) rays.push_back(b - a);
  for (std::size_t i = 0; i < target.size(); ++i)
    if (target.size() > 1) directions.push_back(target[(i + 1) % target.size()] - target[i]);
  for (int axis = 0; axis < 3; ++axis) directions.push_back(Vec3::Unit(axis));
  for (const Vec3& r : extreme_rays(rays))
    if (r.norm() > 0) directions.push_back(r.normalized());
  std::vector<HalfSpace> hs = facets(grown, rays, directions, scale);
  if (hs.empty()) return CPositionSet::domain(domain_);
  for (HalfSpace& h : hs) h.offset += eps_o_;
  return CPositionSet::convex(hs, domain_);
}

const CPositionSet& AtomSimulation::weak_reach(int from, int to) {
  const std::size_t n = static_cast<std::size_t>(cspace_.atom_count());
  return cached(reach_.at(static_cast<std::size_t>(from) * n + static_cast<std::size_t>(to)), [&] {
    return atoms_connected(cspace_, from, to) ? connected_reach(from, to) : flight_reach(from, to);
  });
}

bool AtomSimulation::senses(int atom) const {
  return static_cast<std::size_t>(atom) < goal_stops_.senses.size() &&
         goal_stops_.senses[static_cast<std::size_t>(atom)];
}

void AtomSimulation::traverse(const std::vector<int>& start, const Vec3& p,
                              const std::function<bool(int)>& at_atom,
                              const std::function<void(int, int, bool)>& at_pair) {
  std::vector<bool> reached(static_cast<std::size_t>(cspace_.atom_count()), false);
  std::vector<int> queue;
  const auto reach = [&](int a) {
    if (!reached[static_cast<std::size_t>(a)])
      reached[static_cast<std::size_t>(a)] = true, queue.push_back(a);
  };
  for (int a : start) reach(a);
  for (std::size_t i = 0; i < queue.size(); ++i) {
    const int b = queue[i];
    if (!at_atom(b)) continue;
    for (int next = 0; next < cspace_.atom_count(); ++next) {
      if (next == b) continue;
      const bool edge = weak_reach(b, next).contains(p);
      if (edge) reach(next);
      if (at_pair) at_pair(b, next, edge);
    }
  }
}

std::vector<int> AtomSimulation::targets_at(const std::vector<int>& start, const Vec3& p) {
  std::vector<int> targets;
  bool goal_stop = false;
  traverse(
      start, p,
      [&](int b) {
        if (senses(b)) goal_stop = true;
        if (weak_sticking(b).contains(p)) {
          if (goal_sticking(b).contains(p))
            goal_stop = true;
          else
            targets.push_back(b);
        }
        return !strong_sticking(b).contains(p);
      },
      nullptr);
  if (free_rest().contains(p)) targets.push_back(free_atom());
  if (goal_stop) targets.push_back(goal_stop_atom());
  std::sort(targets.begin(), targets.end());
  return targets;
}

namespace {

// Half-spaces whose intersection holds p and misses the set: for each piece, its facet p violates most.
void add_outside(const CPositionSet& set, const Vec3& p, std::vector<HalfSpace>& out) {
  for (const ConvexPiece& piece : set.pieces()) {
    const HalfSpace* worst = nullptr;
    for (const HalfSpace& h : piece.halfspaces)
      if (!worst || h.normal.dot(p) - h.offset > worst->normal.dot(p) - worst->offset) worst = &h;
    if (worst) out.push_back({-worst->normal, -worst->offset});
  }
}

// The half-spaces of the piece of `set` that holds p deepest.
void add_inside(const CPositionSet& set, const Vec3& p, std::vector<HalfSpace>& out) {
  const ConvexPiece* best = nullptr;
  double best_depth = -std::numeric_limits<double>::infinity();
  for (const ConvexPiece& piece : set.pieces()) {
    double depth = std::numeric_limits<double>::infinity();
    for (const HalfSpace& h : piece.halfspaces) depth = std::min(depth, h.offset - h.normal.dot(p));
    if (depth > best_depth) best_depth = depth, best = &piece;
  }
  if (best) out.insert(out.end(), best->halfspaces.begin(), best->halfspaces.end());
}

}  // namespace

CPositionSet AtomSimulation::cell_at(const std::vector<int>& start, const Vec3& p) {
  std::vector<HalfSpace> hs;
  const auto at_atom = [&](int b) {
    if (!weak_sticking(b).contains(p))
      add_outside(weak_sticking(b), p, hs);
    else if (goal_sticking(b).contains(p))
      add_inside(goal_sticking(b), p, hs);  // keep its stops in the goal
    else
      add_outside(goal_sticking(b), p, hs);
    if (!strong_sticking(b).contains(p)) return true;
    add_inside(strong_sticking(b), p, hs);  // no way on from b: keep p sticking there
    return false;
  };
  traverse(start, p, at_atom, [&](int b, int next, bool edge) {
    if (!edge) add_outside(weak_reach(b, next), p, hs);
  });
  if (!free_rest().contains(p)) add_outside(free_rest(), p, hs);
  return CPositionSet::convex(hs, domain_);
}

}  // namespace cmt::planner
