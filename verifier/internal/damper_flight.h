// Private to verifier/ .cc files: free-space flight of the generalized damper from a convex source (Buckley
// Alg 4.1 step 1, §4.3.2-4.3.4), computed exactly in each target face's chart (design step D).
#pragma once

#include <vector>

#include "verifier/internal/face_regions.h"

namespace cmt::face_geometry {

// Rays of a polygonal cone containing cone(v, theta_v): the regular kFlightConeRays-gon circumscribing the
// circle of radius tan(theta_v + kFlightAngleSlack) at unit height along v. Each ray has v-component 1.
inline constexpr int kFlightConeRays = 24;
// Angular slack (rad) on every cone and wedge built from floating-point trigonometry (flight cone, sliding
// and tangential wedges): covers rounding of the rotated directions.
inline constexpr double kFlightAngleSlack = 1e-9;
struct FlightCone {
  std::vector<Vec3> rays;
  double far = 0;  // truncation length: >= 2 x scene scale (see damper_flight.cc)
};
FlightCone flight_cone(const Vec3& v, double theta_v, double scale);

struct FlightSource {
  std::vector<Point3> vertices;    // conv(vertices) is the source
  std::vector<Plane3> keep_front;  // only points on the non-negative side of each plane are reachable
  int face = -1;                   // source face index (not a target), or -1
  // Faces meeting the source face at a concave edge (a -> b): a source vertex strictly inside that edge sees
  // nothing behind the face's plane (the segment enters the obstacle at once), so the face still occludes
  // for that vertex (fly's umbras). Empty: such faces do not occlude (sound, looser).
  struct Wall {
    int face = -1;
    Point3 a, b;
  };
  std::vector<Wall> walls;
};

struct FlightHit {
  int face = -1;       // face index
  ChartRegion region;  // reached region with umbras removed, when the section has area
  Points2 lower;       // otherwise the section: a segment (2 points) or a point (1)
};

// Relative error bound of the flight section's double arithmetic: a plane value a x + b y + c z + d computed
// in doubles is within this x (|a x| + |b y| + |c z| + |d|) of the exact value (90 x the 2^-53 rounding,
// against at most a dozen roundings: the conversions of exact coordinates and coefficients, the generator
// sums, the products and sums), and the section's hull is grown by this x (1 + largest coordinate) against
// rounding of its points. A section whose growth would exceed half a region cell (a scene far from the
// origin) is computed exactly instead: growth beyond the cell would be propagated by the fixpoint round after
// round (a creep).
inline constexpr double kFlightSectionRelativeError = 1e-14;
// A double section whose width (2 area / diameter) is below this many of its growth pads is recomputed
// exactly, so that a section that is a segment or a point stays lower-dimensional.
inline constexpr double kFlightThinSection = 1e3;
// The section of conv(x_i) ⊕ conv(s_k) (s_0 = 0, s_1.. a ring of cone generators) by the chart's plane, in
// doubles from the Minkowski sum's edges, grown to a superset of the exact section (damper_flight.cc). False
// when no edge can cross the plane; *thin when the section is narrower than kFlightThinSection pads or its
// pad exceeds half the chart's region cell (then *out is unset and the exact section is to be used).
// Generators are numbered i |s| + k for x_i + s_k; *crossing (when given) receives every edge whose plane
// values can have opposite signs or vanish (all the edges that can meet the plane), with each end's sign
// where its error bound already decides it (+1 or -1; 0: undecided).
struct GeneratorEdge {
  std::size_t p, q;
  int sign_p, sign_q;
};
bool section_in_doubles(const std::vector<Vec3>& x, const std::vector<Vec3>& s, const FaceChart& chart,
                        Points2* out, bool* thin, std::vector<GeneratorEdge>* crossing = nullptr);
// The exact section from those edges only (x exact, s_k as in section_in_doubles, s_0 = 0): the hull of their
// exact crossings and of their ends on the plane.
Points2 section_exact(const std::vector<Point3>& x, const std::vector<Vec3>& s,
                      const std::vector<GeneratorEdge>& crossing, const FaceChart& chart);
// Relative margin (x scene scale) by which each occluder's umbra is shrunk before it is subtracted.
inline constexpr double kUmbraRelativeMargin = 1e-9;

// reach(g) = g ∩ (conv(X) + cone(C)) ∩ keep_front, minus the umbras of single occluders (design step D).
std::vector<FlightHit> fly(const ReachedSet::Impl& geometry, const FlightSource& source,
                           const FlightCone& cone);

}  // namespace cmt::face_geometry
