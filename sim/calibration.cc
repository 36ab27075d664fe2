#include "sim/calibration.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <string>

#include "sim/rollout.h"

namespace cmt {

namespace {

// A floor box and a wall box (C-space form, inches). The face case runs on the floor at (1, 0, 0), 3 in from
// the wall; the edge case in the concave edge x = -2, z = 0 (along y). Both slide along +y, away from every
// other feature for the whole case. `step` is the position form's via spacing: a tenth of the spring's
// distance to its commanded position.
std::string calibration_yaml(double mu, double step) {
  return "name: calibration\nunits: in\nfriction: " + std::to_string(mu) +
         "\nuncertainty: {eps_s: 0, eps_p: 0, theta_v: 0, theta_f: 0, step: " + std::to_string(step) +
         "}\n"
         "cspace:\n"
         "  - box: {min: [-2, -4, -2], max: [4, 4, 0]}\n"
         "  - box: {min: [-4, -4, -2], max: [-2, 4, 4]}\n"
         "bounds: {min: [-4, -4, -2], max: [4, 4, 4]}\n"
         "start: {point: [1, 0, 0]}\n"
         "goal: {point: [1, 0, 0]}\n";
}

struct Geometry {
  std::string name;
  Vec3 position;
  std::vector<Vec3> inward;  // inward normals of the faces in contact (into the obstacles)
  Vec3 normal() const {      // inward bisector
    Vec3 n = Vec3::Zero();
    for (const Vec3& v : inward) n += v;
    return n.normalized();
  }
};

// One pushing direction of a case: alpha from the inward normal (bisector), as a ratio of a reference angle.
struct Angle {
  double ratio, alpha;
  std::string reference;
};

// The edge's two Coulomb thresholds for a pull at alpha from its bisector (calibration.h): sticking below
// `kinetic`, sliding beyond `cone`, either between.
double edge_kinetic_angle(double mu) { return std::atan(std::sqrt(2.0) * mu); }
double edge_cone_angle(double mu) {
  return mu < 1 ? std::atan(std::sqrt(2.0) * mu / std::sqrt(1 - mu * mu)) : M_PI / 2;
}

// The angles: the grid of ratios of phi, and for the edge its two thresholds' neighbourhoods.
std::vector<Angle> calibration_angles(const Geometry& g, double mu) {
  const double phi = std::atan(mu);
  std::vector<Angle> angles;
  for (const double r : kCalibrationRatios) angles.push_back({r, r * phi, "phi"});
  if (g.name == "edge") {
    for (const double r : {0.9, 0.95}) angles.push_back({r, r * edge_kinetic_angle(mu), "edge_kinetic"});
    if (mu < 1)
      for (const double r : {1.05, 1.1}) angles.push_back({r, r * edge_cone_angle(mu), "edge_cone"});
  }
  return angles;
}

// Coulomb's prediction for a push at alpha.
std::string coulomb_expectation(const Geometry& g, double alpha, double mu) {
  if (g.name == "face") return alpha <= std::atan(mu) ? "stick" : "slide";
  return alpha <= edge_kinetic_angle(mu) ? "stick" : alpha > edge_cone_angle(mu) ? "slide" : "ambiguous";
}

// Coulomb's sliding speed: kinetic friction mu x (sum of the normal parts) opposes the slip. `x1` is the
// position at the start of the measuring window.
double analytic_slide_speed(const CalibrationCase& c, const Geometry& g, const Motion& m, const Vec3& dir,
                            const Vec3& x1, double lambda, double window) {
  const Vec3 tangent = Vec3::UnitY();
  double normal = 0;
  if (m.kind == Motion::Kind::kSpring) {
    const Vec3 d = m.target - x1;
    for (const Vec3& n : g.inward) normal += d.dot(n);
    const double excess = std::max(0.0, d.dot(tangent) - c.mu * normal);
    return excess * (1 - std::exp(-lambda * window)) / window;
  }
  for (const Vec3& n : g.inward) normal += dir.dot(n);
  return c.command_speed * (std::sin(c.alpha) - c.mu * normal);
}

// Runs one case on the runner's scene and fills its observations (speed, creep, penetration, the analytic
// speed of a slide) and its verdict.
void run_case(RolloutRunner& runner, const RolloutScene& scene, const Geometry& g, double distance,
              double lambda, CalibrationCase& c) {
  const Vec3 tangent = Vec3::UnitY();
  const bool spring = c.motion == "spring";
  const Vec3 dir = std::cos(c.alpha) * g.normal() + std::sin(c.alpha) * tangent;
  Motion m;
  m.name = "calibration";
  m.kind = spring ? Motion::Kind::kSpring : Motion::Kind::kDamper;
  m.target = spring ? Vec3(g.position + distance * dir) : dir;
  const bool position_form = c.form == ControllerForm::kPosition;
  const ControllerParams& params = scene.controller_params();
  // Velocity forms: creep and speed over kVelocityWindow after kVelocitySettle, stick/slide from that speed.
  // Position form (calibration.h): creep at constant load, over kPositionWindow once the via plan is
  // complete and kPositionSettleTimeConstants / g have passed; stick/slide from the travel along the tangent
  // over the whole motion; the slip while the load grows is reported (loading_creep) over
  // kPositionLoadingWindow after kPositionLoadingStart. The plan: ViaPointSpring::plan
  // (controllers/controller.cc) splits the distance to the target into ceil(distance / step) segments, one
  // via point every via_time, from time 0; the last one has run to completion (AML MOVE) after segments x
  // via_time.
  const int segments = std::max(1, static_cast<int>(std::ceil((m.target - g.position).norm() / params.step)));
  const double plan = segments * params.via_time;
  const double settle =
      position_form ? plan + kPositionSettleTimeConstants / params.position_gain : kVelocitySettle;
  const double window = position_form ? kPositionWindow : kVelocityWindow;
  const double duration = settle + window;
  const double loading_end = kPositionLoadingStart + kPositionLoadingWindow;
  const double s = scene.meters_per_unit();
  Vec3 x1 = Vec3::Zero(), x2 = Vec3::Zero(), l1 = Vec3::Zero(), l2 = Vec3::Zero();
  double penetration = 0;
  runner.drive(g.position, m, duration, [&](const StepState& st) {
    penetration = std::max(penetration, st.penetration * s);
    if (std::abs(st.time - settle) < 1e-9) x1 = st.position;
    if (std::abs(st.time - kPositionLoadingStart) < 1e-9) l1 = st.position;
    if (std::abs(st.time - loading_end) < 1e-9) l2 = st.position;
    x2 = st.position;
  });
  const double tangential = (x2 - x1).dot(tangent) / window;
  if (position_form) {
    c.command_speed = params.step / params.via_time;
  } else if (spring) {
    c.command_speed = lambda * (m.target - x1).norm();
  } else {
    c.command_speed = params.damper_speed;
  }
  // Position form: the mean tangential speed over the whole motion, so that a slide that ends while the plan
  // runs is still seen.
  c.speed = position_form ? (x2 - g.position).dot(tangent) / duration : tangential;
  c.observed = std::abs(c.speed) > kSlideThreshold * c.command_speed ? "slide" : "stick";
  c.max_penetration = penetration;
  if (!position_form && c.observed == "slide" && c.expected == "slide") {
    c.analytic_speed = analytic_slide_speed(c, g, m, dir, x1, lambda, window);
    c.speed_error = std::abs(c.speed / c.analytic_speed - 1);
  }
  if (c.observed == "stick") {
    c.creep = std::abs(tangential) / c.command_speed;
    if (position_form)
      c.loading_creep = std::abs((l2 - l1).dot(tangent)) / kPositionLoadingWindow / c.command_speed;
  }
  c.agree = c.expected == "ambiguous" || c.expected == c.observed;
  c.passed = c.agree && c.creep <= kMaxCreep && c.speed_error <= kMaxSpeedError &&
             c.max_penetration <= kMaxPenetration;
}

// The case into the totals. Ambiguous cases are reported but not scored: Coulomb allows either outcome there.
void add_case(const CalibrationCase& c, CalibrationResult& result) {
  if (c.expected == "ambiguous") {
    ++result.ambiguous;
  } else {
    result.max_creep = std::max(result.max_creep, c.creep);
    result.max_loading_creep = std::max(result.max_loading_creep, c.loading_creep);
    result.max_speed_error = std::max(result.max_speed_error, c.speed_error);
    double& speed_error = c.geometry == "face" ? result.max_face_speed_error : result.max_edge_speed_error;
    speed_error = std::max(speed_error, c.speed_error);
    double& creep = c.geometry == "face" ? result.max_face_creep : result.max_edge_creep;
    creep = std::max(creep, c.creep);
    result.agree = result.agree && c.agree;
    result.passed = result.passed && c.passed;
  }
  result.max_penetration = std::max(result.max_penetration, c.max_penetration);
  result.passed = result.passed && c.max_penetration <= kMaxPenetration;
  result.cases.push_back(c);
}

}  // namespace

CalibrationResult calibrate_friction(std::vector<ControllerForm> forms, const MjcfOptions& scene) {
  const auto wall_start = std::chrono::steady_clock::now();
  CalibrationResult result;
  const std::vector<Geometry> geometries = {
      {"face", Vec3(1, 0, 0), {-Vec3::UnitZ()}},
      {"edge", Vec3(-2, 0, 0), {-Vec3::UnitZ(), -Vec3::UnitX()}},
  };
  SimOptions base;
  base.scene = scene;
  const double lambda = base.spring_rate;
  const double distance = kCalibrationSpeed / lambda;  // spring: |x_c - x| giving the calibration speed
  for (const double mu : kCalibrationFrictions) {
    const auto task = load_task_from_string(calibration_yaml(mu, distance / 10), "calibration.yaml");
    for (const ControllerForm form : forms) {
      SimOptions options = base;
      options.form = form;
      options.damper_speed_per_scale = kCalibrationSpeed / task->cspace.scale();
      const auto rollout_scene = RolloutScene::build(task, options);
      RolloutRunner runner(rollout_scene);
      for (const Geometry& g : geometries)
        for (const char* motion_kind : {"damper", "spring"}) {
          if (form == ControllerForm::kPosition && std::string(motion_kind) != "spring") continue;
          for (const Angle& a : calibration_angles(g, mu)) {
            if (a.alpha >= M_PI / 2) continue;  // does not push into the contact
            CalibrationCase c;
            c.geometry = g.name;
            c.motion = motion_kind;
            c.form = form;
            c.mu = mu;
            c.ratio = a.ratio;
            c.reference = a.reference;
            c.alpha = a.alpha;
            c.expected = coulomb_expectation(g, a.alpha, mu);
            run_case(runner, *rollout_scene, g, distance, lambda, c);
            add_case(c, result);
          }
        }
    }
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace cmt
