#include "controllers/termination.h"

#include <cmath>

namespace cmt {

const char* termination_name(Termination t) {
  switch (t) {
    case Termination::kSticking:
      return "sticking";
    case Termination::kPosition:
      return "position";
    case Termination::kForce:
      return "force";
    case Termination::kNone:
      return "none";
    case Termination::kUnstable:
      return "unstable";
  }
  return "?";
}

void PositionSet::add_box(const AxisBox& box) {
  Polytope p;
  for (int k = 0; k < 3; ++k) {
    p.normals.push_back(Vec3::Unit(k));
    p.offsets.push_back(box.max[k]);
    p.normals.push_back(-Vec3::Unit(k));
    p.offsets.push_back(-box.min[k]);
  }
  polytopes_.push_back(std::move(p));
}

void PositionSet::add_polytope(std::vector<Vec3> normals, std::vector<double> offsets) {
  polytopes_.push_back({std::move(normals), std::move(offsets)});
}

bool PositionSet::contains(const Vec3& x) const {
  for (const Polytope& p : polytopes_) {
    bool inside = true;
    for (std::size_t i = 0; i < p.normals.size() && inside; ++i) inside = p.normals[i].dot(x) <= p.offsets[i];
    if (inside) return true;
  }
  return false;
}

void ForceDirectionSet::add_cone(const Vec3& axis, double half_angle) {
  cones_.push_back({axis.normalized(), half_angle});
}

bool ForceDirectionSet::contains(const Vec3& force) const {
  if (force.squaredNorm() == 0) return false;
  for (const CircularCone& c : cones_)
    if (c.signed_angle(force) <= 0) return true;
  return false;
}

TerminationSpec termination_spec(const MotionTermination& terminate) {
  TerminationSpec spec;
  if (!terminate.position.empty()) {
    PositionSet p;
    for (const AxisBox& b : terminate.position) p.add_box(b);
    spec.sensed_position = std::move(p);
  }
  if (!terminate.force.empty()) {
    ForceDirectionSet f;
    for (const ForceCone& c : terminate.force) f.add_cone(c.direction, c.angle);
    spec.sensed_force = std::move(f);
  }
  return spec;
}

TerminationMonitor::TerminationMonitor(TerminationSpec spec, double reference_speed, double guard_force,
                                       double control_step)
    : spec_(std::move(spec)),
      stop_speed_(kStopRelativeSpeed * reference_speed),
      guard_force_(guard_force),
      dt_(control_step),
      window_steps_(static_cast<std::size_t>(std::lround(kStopWindow / control_step))),
      window_(window_steps_ + 1) {}

std::optional<Termination> TerminationMonitor::update(const Sensed& s, bool stop_rule) {
  if (s.force.norm() > guard_force_) last_contact_time_ = s.time;
  in_contact_ = s.time - last_contact_time_ <= kContactHold;

  if (spec_.sensed_force && spec_.sensed_force->contains(s.force) &&
      (!spec_.sensed_position || spec_.sensed_position->contains(s.position)))
    return Termination::kForce;
  if (spec_.sensed_position && !spec_.sensed_force && in_contact_ &&
      spec_.sensed_position->contains(s.position))
    return Termination::kPosition;

  // window_steps_ + 1 positions span window_steps_ steps; slot count_ % size holds the newest.
  const std::size_t size = window_steps_ + 1;
  window_[count_ % size] = s.position;
  ++count_;
  if (stop_rule && count_ >= size) {
    const Vec3& newest = window_[(count_ - 1) % size];
    const Vec3& oldest = window_[count_ % size];
    const double speed = (newest - oldest).norm() / (static_cast<double>(window_steps_) * dt_);
    if (speed < stop_speed_) return Termination::kSticking;
  }
  return std::nullopt;
}

}  // namespace cmt
