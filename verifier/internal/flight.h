// Private to verifier/ .cc files: free-space flight of the generalized damper from a convex source (Buckley
// Alg 4.1 step 1, §4.3.2-4.3.4), computed exactly in each target face's chart (design step D).
#pragma once

#include <vector>

#include "verifier/internal/face_regions.h"

namespace cmt::fp {

// Rays of a polygonal cone containing cone(v, theta_v): the regular kFlightConeRays-gon circumscribing the
// circle of radius tan(theta_v + kFlightAngleSlack) at unit height along v. Each ray has v-component 1.
inline constexpr int kFlightConeRays = 24;
// Angular slack (rad) on every cone and wedge built from floating-point trigonometry (flight cone, sliding
// and tangential wedges): covers rounding of the rotated directions.
inline constexpr double kFlightAngleSlack = 1e-9;
struct FlightCone {
  std::vector<Vec3> rays;
  double far = 0;  // truncation length: >= 2 x scene scale (see flight.cc)
};
FlightCone flight_cone(const Vec3& v, double theta_v, double scale);

struct FlightSource {
  std::vector<Point3> vertices;    // conv(vertices) is the source
  std::vector<Plane3> keep_front;  // only points on the non-negative side of each plane are reachable
  int face = -1;                   // source face index (not a target), or -1
};

struct FlightHit {
  int face = -1;       // face index
  ChartRegion region;  // reached region with umbras removed, when the section has area
  Points2 lower;       // otherwise the section: a segment (2 points) or a point (1)
};

// Relative margin (x scene scale) by which each occluder's umbra is shrunk before it is subtracted.
inline constexpr double kUmbraRelativeMargin = 1e-9;

// reach(g) = g ∩ (conv(X) + cone(C)) ∩ keep_front, minus the umbras of single occluders (design step D).
std::vector<FlightHit> fly(const ReachedSet::Impl& geometry, const FlightSource& source,
                           const FlightCone& cone);

}  // namespace cmt::fp
