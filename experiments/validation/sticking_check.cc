#include "experiments/validation/sticking_check.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "controllers/random.h"
#include "sim/parallel_runs.h"
#include "sim/rollout.h"
#include "verifier/atom_cone.h"
#include "verifier/damper.h"

namespace cmt {
namespace {

struct Trial {
  int atom = 0;
  Vec3 point = Vec3::Zero();
  Vec3 command = Vec3::Zero();  // commanded direction v
  Vec3 actual = Vec3::Zero();   // sampled actual direction v_a in cone(v, theta_v)
  StickClass cls = StickClass::kMay;
  bool stuck = false;
  double speed = 0;   // observed speed / commanded speed over the measuring window
  double travel = 0;  // distance from the start over the whole drive / drive time, / commanded speed
  // The simulation became unstable (RolloutRunner::drive threw): the trial is not classified (its "stuck"
  // would be meaningless) but counted and listed, like the rollouts' unstable outcomes.
  bool unstable = false;
  std::string failure;
};

// A unit vector at angle `angle` from `axis`, in a direction set by `azimuth`.
Vec3 tilt(const Vec3& axis, double angle, double azimuth) {
  const Vec3 a = axis.normalized();
  const Vec3 u = a.cross(std::abs(a.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).normalized();
  const Vec3 w = a.cross(u);
  return std::cos(angle) * a + std::sin(angle) * (std::cos(azimuth) * u + std::sin(azimuth) * w);
}

// Trial i: an atom uniformly, a point on it (a face's interior, an edge's middle half, the vertex), a command
// near the atom's stick boundaries (tilted from the inward direction by up to 1.2 rad), and an actual
// direction in the velocity cone (half of them on its rim, where classifications are decided).
Trial make_trial(const LoadedTask& task, const AtomCones& cones, const std::vector<int>& atoms,
                 std::uint64_t seed, int i) {
  Rng rng = rollout_stream(seed, static_cast<std::uint64_t>(i));
  const CSpace& c = task.cspace;
  Trial t;
  t.atom = atoms[uniform_index(rng, static_cast<int>(atoms.size()))];
  const std::vector<Vec3> pts = atom_points(c, t.atom);
  if (pts.size() == 1) {
    t.point = pts[0];
  } else if (pts.size() == 2) {
    const double s = uniform(rng, 0.25, 0.75);
    t.point = (1 - s) * pts[0] + s * pts[1];
  } else {
    // Shrink toward the centroid so the robot starts well inside the face.
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& p : pts) centroid += p;
    centroid /= static_cast<double>(pts.size());
    const std::size_t k = 1 + static_cast<std::size_t>(uniform_index(rng, static_cast<int>(pts.size()) - 2));
    double a = uniform01(rng), b = uniform01(rng);
    if (a + b > 1) {
      a = 1 - a;
      b = 1 - b;
    }
    const Vec3 p = pts[0] + a * (pts[k] - pts[0]) + b * (pts[k + 1] - pts[0]);
    t.point = centroid + 0.5 * (p - centroid);
  }
  Vec3 inward = Vec3::Zero();
  for (int f : atom_faces(c, t.atom)) inward -= c.faces()[f].normal;
  const double theta_v = task.task.uncertainty.theta_v;
  t.command = tilt(inward, uniform(rng, 0, 1.2), uniform(rng, 0, 2 * std::numbers::pi));
  t.cls = classify_damper(cones, t.atom, t.command, theta_v);
  const double a = uniform01(rng) < 0.5 ? theta_v : theta_v * std::sqrt(uniform01(rng));
  t.actual = tilt(t.command, a, uniform(rng, 0, 2 * std::numbers::pi));
  return t;
}

void drive_trial(RolloutRunner& runner, Trial& t) {
  Motion m;
  m.name = "check";
  m.kind = Motion::Kind::kDamper;
  m.target = t.actual;
  Vec3 at_half = Vec3::Zero(), at_end = t.point;
  bool have_half = false;
  try {
    runner.drive(t.point, m, kCheckDriveSeconds, [&](const StepState& s) {
      if (!have_half && s.time >= kCheckDriveSeconds / 2) {
        at_half = s.position;
        have_half = true;
      }
      at_end = s.position;
    });
  } catch (const std::runtime_error& e) {  // an unstable simulation must not end the process
    t.unstable = true;
    t.failure = e.what();
    return;
  }
  (void)have_half;
  t.speed = (at_end - at_half).norm() / (kCheckDriveSeconds / 2);
  t.travel = (at_end - t.point).norm() / kCheckDriveSeconds;
}

}  // namespace

StickingCheckResult check_sticking(std::shared_ptr<const LoadedTask> task, int n, std::uint64_t seed,
                                   int threads, AtomKindFilter kinds, const SimOptions& sim) {
  const auto start = std::chrono::steady_clock::now();
  const auto scene = RolloutScene::build(task, sim);
  const AtomCones cones(task->cspace);
  const double command_speed = scene->controller_params().damper_speed;
  std::vector<int> atoms;
  for (int id = 0; id < task->cspace.atom_count(); ++id) {
    const AtomKind k = task->cspace.atom_kind(id);
    if ((k == AtomKind::kFace && kinds.faces) || (k == AtomKind::kEdge && kinds.edges) ||
        (k == AtomKind::kVertex && kinds.vertices))
      atoms.push_back(id);
  }
  if (atoms.empty()) throw std::invalid_argument("no atoms of the requested kinds");
  std::vector<Trial> trials(n);
  for (int i = 0; i < n; ++i) trials[i] = make_trial(*task, cones, atoms, seed, i);
  parallel_runs(
      n, threads, [&] { return std::make_unique<RolloutRunner>(scene); },
      [&](RolloutRunner& runner, int i) {
        drive_trial(runner, trials[i]);
        if (trials[i].unstable) return;
        trials[i].speed /= command_speed;
        trials[i].travel /= command_speed;
        // Stuck: still in the window, and it never went anywhere (a robot that slid to the end of its atom
        // and stopped at a corner has travelled).
        trials[i].stuck = trials[i].speed < kCheckStuckSpeed && trials[i].travel < kCheckStuckTravel;
      });

  StickingCheckResult r;
  r.trials = n;
  const CSpace& c = task->cspace;
  for (int i = 0; i < n; ++i) {
    const Trial& t = trials[i];
    if (t.unstable) {
      ++r.unstable;
      if (r.unstable_trials.size() < 20)
        r.unstable_trials.push_back({{"trial", i},
                                     {"atom", t.atom},
                                     {"name", c.atom_name(t.atom)},
                                     {"point", {t.point.x(), t.point.y(), t.point.z()}},
                                     {"actual", {t.actual.x(), t.actual.y(), t.actual.z()}},
                                     {"failure", t.failure}});
      continue;
    }
    const bool wrong = (t.cls == StickClass::kMust && !t.stuck) || (t.cls == StickClass::kNever && t.stuck);
    r.must += t.cls == StickClass::kMust;
    r.may += t.cls == StickClass::kMay;
    r.never += t.cls == StickClass::kNever;
    if (t.cls == StickClass::kMay && t.stuck) ++r.may_stuck;
    if (wrong) {
      ++r.disagreements;
      if (r.worst.size() < 20)
        r.worst.push_back({{"trial", i},
                           {"atom", t.atom},
                           {"name", c.atom_name(t.atom)},
                           {"kind", atom_kind_name(c.atom_kind(t.atom))},
                           {"class", stick_class_name(t.cls)},
                           {"point", {t.point.x(), t.point.y(), t.point.z()}},
                           {"command", {t.command.x(), t.command.y(), t.command.z()}},
                           {"actual", {t.actual.x(), t.actual.y(), t.actual.z()}},
                           {"relative_speed", t.speed},
                           {"relative_travel", t.travel}});
    }
  }
  for (int i = 0; i < n; ++i) {
    const Trial& t = trials[i];
    if (t.unstable) continue;
    Vec3 inward = Vec3::Zero();
    double mu = 0;
    const std::vector<int> faces = atom_faces(c, t.atom);
    for (int f : faces) {
      inward -= c.faces()[f].normal;
      mu = std::max(mu, c.faces()[f].friction);
    }
    StickingTrialRecord rec;
    rec.atom = t.atom;
    rec.kind = c.atom_kind(t.atom);
    rec.cls = t.cls;
    rec.command_angle = std::acos(std::clamp(inward.normalized().dot(t.command.normalized()), -1.0, 1.0));
    rec.phi = std::atan(mu);
    rec.stuck = t.stuck;
    rec.speed = t.speed;
    r.records.push_back(rec);
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

nlohmann::json sticking_check_json(const LoadedTask& task, const StickingCheckResult& r) {
  const double may_fraction = r.may > 0 ? static_cast<double>(r.may_stuck) / r.may : 0.0;
  nlohmann::json records = nlohmann::json::array();
  for (const StickingTrialRecord& t : r.records)
    records.push_back({{"atom", t.atom},
                       {"kind", atom_kind_name(t.kind)},
                       {"class", stick_class_name(t.cls)},
                       {"command_angle", t.command_angle},
                       {"phi", t.phi},
                       {"stuck", t.stuck},
                       {"speed", t.speed}});
  return {{"task", task.task.name},
          {"trials", r.trials},
          {"disagreements", r.disagreements},
          {"classes", {{"must", r.must}, {"may", r.may}, {"never", r.never}}},
          {"may_stick_fraction", may_fraction},
          {"disagreeing_trials", r.worst},
          {"unstable", r.unstable},
          {"unstable_trials", r.unstable_trials},
          {"records", records},
          {"seconds", r.seconds}};
}

}  // namespace cmt
