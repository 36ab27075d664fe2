// Error vectors (sim/error_vector.h): the layout, the decoders and the scripted error source.
#include "sim/error_vector.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "models/polygon_distance.h"

namespace cmt {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The exact-bound guard of ErrorSampler::offset: rounding of radius x unit vector can exceed the radius by
// an ulp.
Vec3 within_radius(Vec3 v, double radius) {
  const double n = v.norm();
  if (n > radius) v *= radius / n;
  while (v.norm() > radius) v *= std::nextafter(1.0, 0.0);
  return v;
}

// The unit vector of polar number a (cos of the polar angle = 2a - 1, uniform on the sphere for uniform a)
// and azimuth number b.
Vec3 unit_from(double a, double b) {
  const double z = 2 * a - 1;
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  const double phi = 2 * kPi * b;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// The boundary point of a convex polygon (vertices in order) on the ray from c in direction d (d in the
// polygon's plane); c itself when the ray meets nothing (a degenerate polygon).
Vec3 ray_to_boundary(const std::vector<Vec3>& v, const Vec3& c, const Vec3& d) {
  double best = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec3 a = v[i], b = v[(i + 1) % v.size()];
    // Solve c + s d = a + t (b - a) for s >= 0, t in [0, 1], in the plane: least squares on the 3x2 system.
    Eigen::Matrix<double, 3, 2> m;
    m.col(0) = d;
    m.col(1) = a - b;
    const Eigen::Vector2d st = m.colPivHouseholderQr().solve(a - c);
    if (!st.allFinite() || (m * st - (a - c)).norm() > 1e-9 * (1 + (a - c).norm())) continue;
    if (st(1) < -1e-12 || st(1) > 1 + 1e-12 || st(0) < 0) continue;
    best = std::max(best, st(0));
  }
  return c + best * d;
}

void check_unit_numbers(const std::vector<double>& v) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]) || v[i] < 0 || v[i] > 1)
      throw std::invalid_argument("error vector entry " + std::to_string(i) + " is " + std::to_string(v[i]) +
                                  ": every entry must be a number in [0, 1]");
}

}  // namespace

ErrorVectorShape default_error_shape(bool position_form, double damper_speed_per_scale) {
  ErrorVectorShape shape;
  shape.switches = 3;
  shape.via_points = position_form ? 2 : 0;
  shape.horizon = 1 / damper_speed_per_scale;
  return shape;
}

ErrorVectorShape shape_of_vector(const Task& task, const Strategy& strategy, int size, bool position_form,
                                 double damper_speed_per_scale) {
  const ErrorVectorShape defaults = default_error_shape(position_form, damper_speed_per_scale);
  ErrorVectorShape shape = defaults;
  // The size grows by 4 per node with every extra switch: search K upward.
  for (shape.switches = 0;; ++shape.switches) {
    const int n = ErrorVectorLayout(task, strategy, shape).size();
    if (n == size) return shape;
    if (n > size || strategy.nodes.empty()) break;
  }
  throw std::invalid_argument("an error vector of " + std::to_string(size) +
                              " entries fits no switch count for strategy '" + strategy.name + "' (" +
                              std::to_string(ErrorVectorLayout(task, strategy, defaults).size()) +
                              " entries with " + std::to_string(defaults.switches) + " switches per motion)");
}

ErrorVectorLayout::ErrorVectorLayout(const Task& task, const Strategy& strategy,
                                     const ErrorVectorShape& shape)
    : shape_(shape) {
  if (shape.switches < 0 || shape.via_points < 0 || !(shape.horizon > 0))
    throw std::invalid_argument("error vector shape: switches and via points must be >= 0, horizon > 0");
  start_size_ = task.start.kind == Region::Kind::kPoint ? 0 : 2;
  motion_size_ = via_offset() + 3 * shape.via_points;
  size_ = start_size_;
  for (const StrategyNode& node : strategy.nodes) {
    motion_offsets_.push_back(size_);
    size_ += motion_size_;
    reading_offsets_.push_back(node.branches.empty() ? -1 : size_);
    if (!node.branches.empty()) size_ += 6;
  }
}

DirectionError decode_direction(const double* u, double bound, bool planar) {
  DirectionError e;
  if (planar) {
    e.axis = Vec3::UnitY();
    e.angle = std::clamp(bound * (2 * u[2] - 1), -bound, bound);
  } else {
    e.axis = unit_from(u[0], u[1]);
    e.angle = std::clamp(bound * u[2], 0.0, bound);
  }
  return e;
}

Vec3 decode_offset(const double* u, double radius, bool planar) {
  Vec3 w(2 * u[0] - 1, planar ? 0.0 : 2 * u[1] - 1, 2 * u[2] - 1);
  // The cube [-1, 1]^3 pulled onto the unit ball: every point outside the ball goes to the sphere, so the
  // bound's boundary is a set of positive volume of the vector space (a search reaches it easily).
  const double n = w.norm();
  if (n > 1) w /= n;
  return within_radius(radius * w, radius);
}

Vec3 decode_start(const Region& region, const double* u) {
  const std::vector<Vec3>& v = region.points;
  if (region.kind == Region::Kind::kPoint) return v.at(0);
  if (region.kind == Region::Kind::kSegment) return v.at(0) + u[0] * (v.at(1) - v.at(0));
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : v) c += p;
  c /= static_cast<double>(v.size());
  const Vec3 normal = polygon_normal(v);
  const Vec3 e1 = (v[0] - c).norm() > 0 ? Vec3((v[0] - c).normalized()) : Vec3(normal.unitOrthogonal());
  const Vec3 e2 = normal.cross(e1);
  const double phi = 2 * kPi * u[0];
  const Vec3 rim = ray_to_boundary(v, c, std::cos(phi) * e1 + std::sin(phi) * e2);
  return c + u[1] * (rim - c);
}

ScriptedErrors::ScriptedErrors(const Task& task, const ErrorVectorLayout& layout, std::vector<double> vector)
    : task_(&task), layout_(&layout), vector_(std::move(vector)), planar_(task.dimension == 2) {
  if (static_cast<int>(vector_.size()) != layout.size())
    throw std::invalid_argument("error vector has " + std::to_string(vector_.size()) +
                                " entries; this task's " + "strategy needs " + std::to_string(layout.size()));
  check_unit_numbers(vector_);
}

Vec3 ScriptedErrors::start(const Region& start_region) { return decode_start(start_region, at(0)); }

void ScriptedErrors::begin_motion(int node) {
  const Uncertainty& b = task_->uncertainty;
  const ErrorVectorShape& shape = layout_->shape();
  block_ = layout_->motion_offset(node);
  force_ = decode_direction(at(block_ + ErrorVectorLayout::kForce), b.theta_f, planar_);
  sensing_offset_ = decode_offset(at(block_ + ErrorVectorLayout::kSensing), b.eps_s, planar_);
  velocity_.clear();
  for (int k = 0; k <= shape.switches; ++k)
    velocity_.push_back(
        decode_direction(at(block_ + ErrorVectorLayout::kVelocity + 3 * k), b.theta_v, planar_));
  switch_times_.assign(at(block_ + layout_->switch_times_offset()),
                       at(block_ + layout_->switch_times_offset() + shape.switches));
  for (double& t : switch_times_)
    t = t < 1 ? shape.horizon * t / (1 - t) : std::numeric_limits<double>::infinity();
  std::sort(switch_times_.begin(), switch_times_.end());
  segment_ = 0;
  via_ = 0;
}

void ScriptedErrors::advance(double t) {
  while (segment_ < static_cast<int>(switch_times_.size()) &&
         t >= switch_times_[static_cast<std::size_t>(segment_)])
    ++segment_;
}

Vec3 ScriptedErrors::positioning_error() {
  const int p = layout_->shape().via_points;
  if (p == 0) return Vec3::Zero();
  const int k = via_++ % p;
  return decode_offset(at(block_ + layout_->via_offset() + 3 * k), task_->uncertainty.eps_p, planar_);
}

ReadingErrors ScriptedErrors::reading(int node) {
  ReadingErrors r;
  const int offset = layout_->reading_offset(node);
  if (offset < 0) return r;
  r.sensing_offset = decode_offset(at(offset), task_->uncertainty.eps_s, planar_);
  r.force = decode_direction(at(offset + 3), task_->uncertainty.theta_f, planar_);
  return r;
}

std::string format_error_vector(const std::vector<double>& vector) {
  std::string out;
  char buffer[32];
  for (std::size_t i = 0; i < vector.size(); ++i) {
    std::snprintf(buffer, sizeof buffer, "%.17g", vector[i]);
    if (i > 0) out += ',';
    out += buffer;
  }
  return out;
}

std::vector<double> parse_error_vector(const std::string& text) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    const auto rest = item.find_first_not_of(" \t\n", used);
    if (used == 0 || rest != std::string::npos)
      throw std::invalid_argument("error vector entry " + std::to_string(out.size()) + " ('" + item +
                                  "') is not a number");
    out.push_back(value);
  }
  check_unit_numbers(out);
  return out;
}

}  // namespace cmt
