// Private to verifier/ .cc files: the generalized spring's free-space reach (Buckley §3.3, Fig 3.13; §4.4)
// and its in-plane sliding strip (Fig 3.14), computed exactly in face charts (docs/verifier.md, "Spring").
#pragma once

#include <vector>

#include "verifier/internal/damper_flight.h"
#include "verifier/internal/frame.h"

namespace cmt::face_geometry {

// Sides of the polygons circumscribing the eps_t disks and the overshoot disk (outer approximations).
inline constexpr int kSpringDiskSides = 24;
// Layers of the eps_t slab about a target plane (tighter than one slab; see spring_flight.cc).
inline constexpr int kSpringSlabLayers = 4;
// Relative slack on every radius and projected direction built with floating-point arithmetic.
inline constexpr double kSpringRelativeSlack = 1e-9;
// Outward rounding of the grown polygons (minkowski_outward in spring_flight.cc): their vertices become
// doubles, with every exact point's interval enclosure grown by this fraction of (1 + the largest coordinate)
// to cover the rounding of the double sums (at most 2^-53 of it, so 1e-12 leaves a factor 4500).
inline constexpr double kSpringRoundingSlack = 1e-12;
// Below this cosine the overshoot directions are not bounded by a cap: a polytope about the whole eps_o ball
// about p is used instead.
inline constexpr double kSpringMinCapCosine = 0.1;

// Generators of a convex set containing every point of seg[x, p + eps_o u(x)], x in conv(source), u(x) the
// unit direction from x to p: the source vertices, p, and p + (eps_o / c) u_i (c = min_i u_i . mean
// direction), or the corners of the cube of half-width eps_o about p when c < kSpringMinCapCosine.
std::vector<Point3> spring_generators(const std::vector<Point3>& source, const Vec3& p, double eps_o);

// Free-space reach: for every face g but `source_face`, g ∩ (conv(gens) ⊕ ball(eps_t)), an outer
// approximation from kSpringSlabLayers slabs (exact sections, projected orthogonally onto g's plane, each
// grown by its in-plane radius bound). Occlusion is not subtracted (spring paths bend: sound, looser).
std::vector<FlightHit> spring_fly(const ReachedSet::Impl& geometry, const std::vector<Point3>& gens,
                                  int source_face, double eps_t);

// Sliding strip on face `face_index` from the convex chart piece `part` toward p' (Fig 3.14): the face ∩
// (conv(part ∪ p' ∪ overshoot points) ⊕ disk(eps_t)), the overshoot points built in the plane as in
// spring_generators.
Points2 spring_strip(const ReachedSet::Impl& geometry, int face_index, const Points2& part,
                     const Vec3& p_proj, double eps_t, double eps_o);

// Convex chart polygon circumscribing (outer) or inscribed in (inner) the disk of radius r about `center` in
// the face's plane.
Points2 chart_disk(const ReachedSet::Impl& geometry, int face_index, const Vec3& center, double r,
                   bool outer);

// Motion along an edge (spring_projection.cc, "Edges" in docs/verifier.md): the half-width about q (p
// projected on the edge's line) where the robot may move either way (|x − q| = s with s − eps_s <=
// sin(theta_v) (|p − x| + eps_s)), or `overshoot` if larger (the via-point model's eps_o; 0 for the velocity
// model, which does not overshoot p*), grown by kSpringRelativeSlack.
double edge_either_way_halfwidth(const Edge& e, const Vec3& p, const Uncertainty& u, double overshoot);

// The half-width (edge parameter) of the open interval about parameter tp where the robot must leave the
// edge: it keeps an edge contact only while it may push into every face meeting there, and the pull surely
// points away from face f beyond theta_v when (−depth_f − eps_s) > sin(theta_v) (|p − x| + eps_s), i.e.
// within R_f = (−depth_f − eps_s) / sin(theta_v) − eps_s of p; on the line the interval's half-width is
// sqrt(R^2 − perp^2) / len, R = max_f R_f, shrunk by `margin` (task units, on the pull) and kEdgeParamSlack
// (favours staying). 0 when there is none (non-manifold edges: none), infinity when the robot must leave
// everywhere.
double edge_must_leave_halfwidth(const CSpace& cspace, const Edge& e, double tp, const Vec3& p,
                                 const Uncertainty& u, double margin);

// Chart offsets of the kSpringDiskSides-gon circumscribing the disk of radius r in the plane with normal n.
std::vector<Vector2> disk_offsets(const FaceChart& chart, const Vec3& n, double r);

// conv(points) ⊕ conv(offsets), rounded outward to double vertices (a superset of the exact sum).
Points2 minkowski_outward(const Points2& points, const std::vector<Vector2>& offsets);

}  // namespace cmt::face_geometry
