// Private to verifier/ .cc files: the convex-geometry tools of the velocity-form spring model
// (verifier/internal/spring_velocity.h): sections of convex sets by a face plane computed from their support
// functions, the spiral regions' support, and the cutting of convex sources into pieces whose directions and
// distances from a centre vary little (every bound is computed per piece).
#pragma once

#include <functional>
#include <utility>
#include <vector>

#include "verifier/internal/face_regions.h"
#include "verifier/polyhedron.h"

namespace cmt::face_geometry {

// Relative slack on angles, radii and bounds computed in floating point (all rounded toward "more").
inline constexpr double kVelocitySlack = 1e-9;
// In-plane directions of the support half-planes bounding a convex set's section by a face plane (an outer
// polygon; its excess over the exact section is about its size x (1 / cos(pi / n) − 1)).
inline constexpr int kVelocitySupportDirections = 32;
// Sources are cut into pieces of angular radius <= kVelocityMaxSpread (rad) about their mean direction from
// the centre, at most kVelocityMaxPieces per source (past it the remaining pieces are taken as they are:
// sound, looser).
inline constexpr double kVelocityMaxSpread = 0.1;
inline constexpr int kVelocityMaxPieces = 64;

// The support function w -> max { y . w : y in the set } of a convex set (w need not be a unit vector).
using Support = std::function<double(const Vec3&)>;

// The angle between two vectors (atan2 of |a x b| and a . b: accurate near 0 and pi).
double angle_between(const Vec3& a, const Vec3& b);

// The support bounds' search over lambda (support_section): the least value found of f on [−1e3, 1e3], from a
// bracket about *guess, which returns the minimiser found. With value_tolerance > 0 the search also stops
// once the values found bound the minimum of a convex f to within it (convexity_gap); every returned value is
// an f(lambda), so a stop only sets how tight the bound is, never whether it is sound.
double minimize_over_lambda(const std::function<double(double)>& f, double* guess,
                            double value_tolerance = 0);

// Keeps the part of the planar convex polygon `poly` (3-D points) where n . x <= c (Sutherland-Hodgman, in
// doubles).
std::vector<Vec3> clip_halfspace(const std::vector<Vec3>& poly, const Vec3& n, double c);

// Outer polygon (chart coordinates, clipped to face fi) of the section of the intersection of the convex sets
// `sets` by face fi's plane, also clipped to the half-spaces `cuts` (if any). `in_plane`: every set's support
// is of the form g(v) + (w . n) c (a set given by its in-plane section). Empty if the sets miss the plane.
Points2 support_section(const ReachedSet::Impl& geometry, int fi, const std::vector<Support>& sets,
                        bool in_plane = false, const std::vector<HalfSpace>* cuts = nullptr);

// The support function of the ball B(center, radius).
Support ball_support(const Vec3& center, double radius);

// The spiral region of a path whose velocity stays within theta of the direction to p*: its support in a
// unit direction at angle gamma from the start's direction from p*, as p* . w + r0 x spiral_factor(gamma,
// theta) beyond the knee pi/2 − theta (the start's own support below it).
double spiral_factor(double gamma, double theta);
// The same support relative to the start (over r0): an upper bound of its excess over x0 . w for gamma in
// [lo, hi].
double spiral_excess(double lo, double hi, double theta);

// A convex source piece (polygon, segment or point, 3-D doubles) cut by the plane n . x = c: the parts on
// either side, each grown across the plane by `margin` (their union covers the piece).
std::pair<std::vector<Vec3>, std::vector<Vec3>> cut(const std::vector<Vec3>& piece, const Vec3& n, double c,
                                                    double margin);

// Distance from q (in the plane) to the convex planar polygon `poly` with plane normal n, whatever the
// polygon's orientation about n: 0 inside.
double distance_in_plane(const std::vector<Vec3>& poly, const Vec3& n, const Vec3& q);

// Cuts the convex source `poly` into pieces of small angular radius about their mean direction from `center`
// and of radial extent <= radial_limit, and calls take(piece, R_lower) for each (R_lower <= |x − center| on
// the piece); pieces overlap by `margin` across every cut.
void split_source(const std::vector<Vec3>& poly, const Vec3& center, double eps, double radial_limit,
                  double margin, const std::function<void(const std::vector<Vec3>&, double)>& take);

}  // namespace cmt::face_geometry
