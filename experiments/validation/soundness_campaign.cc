#include "experiments/validation/soundness_campaign.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "controllers/random.h"
#include "experiments/common/json_text.h"
#include "experiments/common/verifier_budget.h"
#include "experiments/validation/validation.h"
#include "models/task_error.h"

namespace cmt {
namespace {

// Generation ranges (docs/validation.md "Random-task soundness campaign"), lengths in physical inches before
// the task's scale and unit factors.
constexpr double kMinFriction = 0.1, kMaxFriction = 0.8;
// The wide generator (CampaignGenerator::kWide): friction up to kWideMaxFriction; each box lifted off the
// floor with probability kLiftedBoxChance (its bottom at 15-40 % of the room's height, 10-30 % tall); a start
// near a rim with probability kNearRimChance (the start region's edge within kRimBand room units of the
// face's rim).
constexpr double kWideMaxFriction = 1.5;
constexpr double kLiftedBoxChance = 0.3;
constexpr double kNearRimChance = 0.5;
constexpr double kRimBand = 0.05;
// The slanted generator (CampaignGenerator::kSlanted): each obstacle a ramp with probability kRampChance: the
// obstacle's footprint with its top sloping along x or y from the drawn height down to kRampLowMin-Max of it
// (never to the floor: the part keeps a thickness the rollouts' scene can erode). A start on a ramp lies on
// its slope at kSlopeInset-(1 - kSlopeInset) of the way across each side.
constexpr double kRampChance = 0.5;
constexpr double kRampLowMin = 0.2, kRampLowMax = 0.9;
constexpr double kSlopeInset = 0.15;
// How far a ramp flush with a wall reaches through it, as a fraction of the room's diagonal: above twice the
// rollouts' cube half size (at most 0.05 x scale, the scale being the diagonal of the C-space's faces).
constexpr double kRampReach = 0.12;
constexpr double kFlushRelative = 1e-12;
constexpr double kMinThetaV = 0.02, kMaxThetaV = 0.3;
constexpr double kMinEps = 0.01, kMaxEps = 0.2;
constexpr double kFarOffsetMin = 50, kFarOffsetMax = 3000;
// Draws per task before giving up on one whose start or goal does not lie on the contact surface.
constexpr int kGenerationAttempts = 20;

// A generated scene in task units: the data the YAML is written from (and that minimization edits).
struct Scene {
  std::string units = "in";
  double mu = 0.5;
  Uncertainty u;
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();  // bounds; the floor is z = lo.z
  std::vector<AxisBox> boxes;                 // C-space obstacles standing on the floor
  std::vector<std::vector<Vec3>> ramps;       // convex C-space obstacles (their vertices)
  std::string start_kind = "point";           // point | segment | polygon
  std::vector<Vec3> start;
  std::vector<std::vector<Vec3>> goal;  // regions: 1 point, or a polygon
  bool spring = false;
  Vec3 command = Vec3::Zero();  // spring target or damper direction
};

std::string num(double x) {
  std::ostringstream os;
  os << std::setprecision(12) << x;
  return os.str();
}

std::string vec(const Vec3& v) { return "[" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "]"; }

std::string points(const std::vector<Vec3>& pts) {
  std::string s = "[";
  for (std::size_t i = 0; i < pts.size(); ++i) s += (i ? ", " : "") + vec(pts[i]);
  return s + "]";
}

std::string region(const std::string& kind, const std::vector<Vec3>& pts) {
  return "{" + kind + ": " + (kind == "point" ? vec(pts[0]) : points(pts)) + "}";
}

std::string to_yaml(const Scene& s, int index, const std::string& description) {
  std::ostringstream y;
  y << "name: campaign-" << index << "\n";
  y << "description: \"" << description << "\"\n";
  y << "units: " << s.units << "\nfriction: " << num(s.mu) << "\n";
  y << "uncertainty: {eps_s: " << num(s.u.eps_s) << ", eps_p: " << num(s.u.eps_p)
    << ", theta_v: " << num(s.u.theta_v) << ", theta_f: " << num(s.u.theta_f) << "}\n";
  y << "cspace:";
  if (s.boxes.empty() && s.ramps.empty()) y << " []";
  y << "\n";
  for (const AxisBox& b : s.boxes) y << "  - box: {min: " << vec(b.min) << ", max: " << vec(b.max) << "}\n";
  for (const auto& r : s.ramps) y << "  - convex: {vertices: " << points(r) << "}\n";
  y << "bounds: {min: " << vec(s.lo) << ", max: " << vec(s.hi) << "}\n";
  y << "start: " << region(s.start_kind, s.start) << "\n";
  y << "goal:\n";
  for (const auto& g : s.goal) y << "  - " << region(g.size() == 1 ? "point" : "polygon", g) << "\n";
  y << "motions: {m: {" << (s.spring ? "spring" : "damper") << ": " << vec(s.command) << "}}\n";
  y << "strategies: {s: [m]}\n";
  return y.str();
}

bool loads(const std::string& yaml) {
  try {
    load_task_from_string(yaml, "campaign");
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

// The top rectangle (counter-clockwise from above) of the floor or of a box.
std::vector<Vec3> top_rectangle(const Vec3& lo, const Vec3& hi, double z) {
  return {Vec3(lo.x(), lo.y(), z), Vec3(hi.x(), lo.y(), z), Vec3(hi.x(), hi.y(), z), Vec3(lo.x(), hi.y(), z)};
}

// A start centre on the face [flo, fhi] at height z, at least r inside it. With `near_rim`, on one side of
// one axis the start's extent toward the rim is `reach` (0 for a point, r for a square) and the gap between
// the start and the rim is at most kRimBand * L.
Vec3 start_centre(Rng& rng, const Vec3& flo, const Vec3& fhi, double z, double r, double L, bool near_rim,
                  double reach) {
  Vec3 c(uniform(rng, flo.x() + r, fhi.x() - r), uniform(rng, flo.y() + r, fhi.y() - r), z);
  if (near_rim) {
    const int k = uniform_index(rng, 2);
    const double band = std::min(kRimBand * L, std::max(0.0, fhi[k] - flo[k] - 2 * reach));
    const double gap = uniform(rng, 0, band);
    c[k] = uniform01(rng) < 0.5 ? flo[k] + reach + gap : fhi[k] - reach - gap;
  }
  return c;
}

// A ramp: a convex C-space part whose top slopes (the slanted generator).
struct Ramp {
  std::vector<Vec3> vertices;  // the floor rectangle, then the top (counter-clockwise)
  std::vector<Vec3> slope;  // the top over the drawn footprint, inside the bounds: starts and goals lie on it
};

// Whether a box side at `side` lies on the wall at `wall` (within the rounding of the draws, which place a
// flush box at lo + (extent - w) + w; the task text keeps 12 digits, so the two are then equal there).
bool flush(double side, double wall, const Vec3& room_lo, const Vec3& room_hi) {
  return std::abs(side - wall) <= kFlushRelative * (room_hi - room_lo).norm();
}

// A ramp over the box's footprint: its top slopes along `axis` from the box's top at the side `high_at_max`
// names down to `low` above the floor. A side flush with the bounds [room_lo, room_hi] reaches through the
// wall by kRampReach of the room's diagonal (the top plane continued): the C-space inside the bounds is the
// same, and the rollouts' scene, which does not grow convex parts into their neighbours and erodes them by
// its cube of half size h <= 0.05 x scale, keeps the eroded slope under a cube that touches the wall (a ramp
// that ended at the wall would leave the cube's far half over its eroded end, and the cube would sink).
// The low end is never flush with a wall (the caller turns such a ramp around), so the top rises through it.
Ramp make_ramp(const AxisBox& box, int axis, bool high_at_max, double low, const Vec3& room_lo,
               const Vec3& room_hi) {
  const double t_high = high_at_max ? box.max[axis] : box.min[axis];
  const double t_low = high_at_max ? box.min[axis] : box.max[axis];
  const double drop = (box.max.z() - low) / (t_low - t_high);  // dz per unit along the axis (signed)
  const auto top = [&](double x, double y) {
    return Vec3(x, y, box.max.z() - drop * ((axis == 0 ? x : y) - t_high));
  };
  const auto rectangle = [&](const Vec3& lo, const Vec3& hi, bool at_top) {
    if (!at_top)
      return std::vector<Vec3>{Vec3(lo.x(), lo.y(), lo.z()), Vec3(hi.x(), lo.y(), lo.z()),
                               Vec3(hi.x(), hi.y(), lo.z()), Vec3(lo.x(), hi.y(), lo.z())};
    return std::vector<Vec3>{top(lo.x(), lo.y()), top(hi.x(), lo.y()), top(hi.x(), hi.y()),
                             top(lo.x(), hi.y())};
  };
  const double reach = kRampReach * (room_hi - room_lo).norm();
  Vec3 lo = box.min, hi = box.max;
  for (int k = 0; k < 2; ++k) {
    if (flush(box.min[k], room_lo[k], room_lo, room_hi)) lo[k] -= reach;
    if (flush(box.max[k], room_hi[k], room_lo, room_hi)) hi[k] += reach;
  }
  Ramp r;
  r.vertices = rectangle(lo, hi, false);
  for (const Vec3& v : rectangle(lo, hi, true)) r.vertices.push_back(v);
  r.slope = rectangle(box.min, box.max, true);
  return r;
}

// A point of a ramp's slope at fractions (u, v) across it (bilinear in its planar quadrilateral).
Vec3 on_slope(const std::vector<Vec3>& q, double u, double v) {
  return (1 - v) * ((1 - u) * q[0] + u * q[1]) + v * ((1 - u) * q[3] + u * q[2]);
}

// A start on a ramp's slope (point, segment or small parallelogram, by `kind` as for flat faces), its
// fractions within [kSlopeInset, 1 - kSlopeInset]; the goal is then the whole slope.
void start_on_slope(Rng& rng, Scene& s, const std::vector<Vec3>& r, int kind) {  // r: the slope
  const double u = uniform(rng, kSlopeInset, 1 - kSlopeInset), v = uniform(rng, kSlopeInset, 1 - kSlopeInset);
  const double du = std::min({0.1, u - kSlopeInset, 1 - kSlopeInset - u});
  const double dv = std::min({0.1, v - kSlopeInset, 1 - kSlopeInset - v});
  if (kind <= 2) {
    s.start_kind = "point";
    s.start = {on_slope(r, u, v)};
  } else if (kind == 3) {
    s.start_kind = "segment";
    s.start = {on_slope(r, u - du, v - dv), on_slope(r, u + du, v + dv)};
  } else {
    s.start_kind = "polygon";
    s.start = {on_slope(r, u - du, v - dv), on_slope(r, u + du, v - dv), on_slope(r, u + du, v + dv),
               on_slope(r, u - du, v + dv)};
  }
  s.goal = {r};
}

Scene draw_scene(Rng& rng, CampaignGenerator generator, std::string* description) {
  const bool wide = generator == CampaignGenerator::kWide;
  const bool slanted = generator == CampaignGenerator::kSlanted;
  Scene s;
  const int unit = uniform_index(rng, 3);
  s.units = unit == 0 ? "in" : unit == 1 ? "mm" : "m";
  const double per_inch = unit == 0 ? 1 : unit == 1 ? 25.4 : 0.0254;
  const double size = std::exp(uniform(rng, std::log(0.25), std::log(2.0)));  // physical scale factor
  const double L = per_inch * size;
  const bool far = uniform01(rng) < 0.5;
  Vec3 offset;
  for (int k = 0; k < 3; ++k) {
    const double mag =
        far ? std::exp(uniform(rng, std::log(kFarOffsetMin), std::log(kFarOffsetMax))) * per_inch
            : uniform(rng, 0, 5) * L;
    offset[k] = uniform01(rng) < 0.5 ? -mag : mag;
  }
  const Vec3 extent(uniform(rng, 4, 10) * L, uniform(rng, 4, 10) * L, uniform(rng, 3, 6) * L);
  s.lo = offset;
  s.hi = offset + extent;
  s.mu = uniform(rng, kMinFriction, wide ? kWideMaxFriction : kMaxFriction);
  s.u.eps_s = uniform(rng, kMinEps, kMaxEps) * L;
  s.u.eps_p = uniform(rng, kMinEps, kMaxEps) * L;
  s.u.theta_v = uniform(rng, kMinThetaV, kMaxThetaV);
  s.u.theta_f = 0.05;
  const int nboxes = uniform_index(rng, 4);
  int lifted = 0;
  for (int b = 0; b < nboxes; ++b) {
    AxisBox box;
    for (int k = 0; k < 2; ++k) {
      const double w = uniform(rng, 0.15, 0.6) * extent[k];
      const double a = uniform(rng, 0, extent[k] - w);
      // Now and then flush against a bounds wall (walls and floor meet the box: concave edges and corners).
      const double at = uniform01(rng) < 0.25 ? (uniform01(rng) < 0.5 ? 0 : extent[k] - w) : a;
      box.min[k] = s.lo[k] + at;
      box.max[k] = s.lo[k] + at + w;
    }
    box.min.z() = s.lo.z();
    box.max.z() = s.lo.z() + uniform(rng, 0.1, 0.5) * extent.z();
    if (wide && uniform01(rng) < kLiftedBoxChance) {
      box.min.z() = s.lo.z() + uniform(rng, 0.15, 0.4) * extent.z();
      box.max.z() = box.min.z() + uniform(rng, 0.1, 0.3) * extent.z();
      ++lifted;
    }
    s.boxes.push_back(box);
  }
  // Slanted: some boxes become ramps (drawn after every box, so the boxes are those of the default draws).
  std::vector<int> ramp_of(s.boxes.size(), -1);  // per box: its ramp's index, -1 when it stays a box
  std::vector<std::vector<Vec3>> slopes;
  if (slanted)
    for (std::size_t b = 0; b < s.boxes.size(); ++b) {
      if (uniform01(rng) >= kRampChance) continue;
      const int axis = uniform_index(rng, 2);
      bool high_at_max = uniform01(rng) < 0.5;
      const AxisBox& box = s.boxes[b];
      // The low end away from the walls (make_ramp): turned around when it would be flush with one.
      if (high_at_max ? flush(box.min[axis], s.lo[axis], s.lo, s.hi)
                      : flush(box.max[axis], s.hi[axis], s.lo, s.hi))
        high_at_max = !high_at_max;
      const double low = box.min.z() + uniform(rng, kRampLowMin, kRampLowMax) * (box.max.z() - box.min.z());
      ramp_of[b] = static_cast<int>(s.ramps.size());
      Ramp r = make_ramp(box, axis, high_at_max, low, s.lo, s.hi);
      s.ramps.push_back(std::move(r.vertices));
      slopes.push_back(std::move(r.slope));
    }
  // The start face: the floor or a box top; a point, a short segment or a small square on it.
  const int face = uniform_index(rng, nboxes + 1);
  const Vec3 flo = face == 0 ? s.lo : s.boxes[face - 1].min;
  const Vec3 fhi = face == 0 ? s.hi : s.boxes[face - 1].max;
  const double z = face == 0 ? s.lo.z() : fhi.z();
  const double r = uniform(rng, 0.02, 0.4) * L;
  const bool near_rim = wide && uniform01(rng) < kNearRimChance;
  // Wide: the start's shape before its centre, so that a near-rim start is placed by its extent (the default
  // draws the shape after the centre).
  const int wide_kind = wide ? uniform_index(rng, 5) : -1;
  const Vec3 c = start_centre(rng, flo, fhi, z, r, L, near_rim, wide_kind >= 0 && wide_kind <= 2 ? 0.0 : r);
  const int kind = wide ? wide_kind : uniform_index(rng, 5);
  if (kind <= 2) {
    s.start_kind = "point";
    s.start = {c};
  } else if (kind == 3) {
    s.start_kind = "segment";
    const double a = uniform(rng, 0, 2 * M_PI);
    const Vec3 d(r * std::cos(a), r * std::sin(a), 0);
    s.start = {c - d, c + d};
  } else {
    s.start_kind = "polygon";
    s.start = top_rectangle(c - Vec3(r, r, 0), c + Vec3(r, r, 0), z);
  }
  // Goal: the start face's whole top (a box top, or the floor when nothing stands on it), else the start's
  // first point; the verdict is what a "reliable" claim is then checked against.
  if (face > 0 || nboxes == 0)
    s.goal = {top_rectangle(flo, fhi, z)};
  else
    s.goal = {{s.start[0]}};
  if (slanted && face > 0 && ramp_of[static_cast<std::size_t>(face - 1)] >= 0)
    start_on_slope(rng, s, slopes[static_cast<std::size_t>(ramp_of[static_cast<std::size_t>(face - 1)])],
                   kind);
  if (slanted) {  // the ramps replace their boxes
    std::vector<AxisBox> kept;
    for (std::size_t b = 0; b < s.boxes.size(); ++b)
      if (ramp_of[b] < 0) kept.push_back(s.boxes[b]);
    s.boxes = kept;
  }
  s.spring = uniform01(rng) < 0.5;
  if (s.spring) {
    s.command = c + Vec3(uniform(rng, -3, 3) * L, uniform(rng, -3, 3) * L, uniform(rng, -2, 0.3) * L);
  } else {
    const double polar = uniform(rng, 0.05, 1.5), az = uniform(rng, 0, 2 * M_PI);
    s.command = Vec3(std::sin(polar) * std::cos(az), std::sin(polar) * std::sin(az), -std::cos(polar));
  }
  std::ostringstream d;
  d << (s.spring ? "spring" : "damper") << ", " << nboxes << " boxes, " << s.units << ", "
    << (far ? "far" : "near") << ", start " << s.start_kind << " on " << (face == 0 ? "floor" : "box top")
    << ", mu " << num(std::round(s.mu * 100) / 100) << ", theta_v "
    << num(std::round(s.u.theta_v * 100) / 100);
  if (wide) d << ", wide: " << lifted << " lifted, " << (near_rim ? "start near a rim" : "start inside");
  if (slanted) {
    const bool on_ramp = face > 0 && ramp_of[static_cast<std::size_t>(face - 1)] >= 0;
    d << ", slanted: " << s.ramps.size() << " ramps" << (on_ramp ? ", start on a slope" : "");
  }
  *description = d.str();
  return s;
}

struct Generated {
  Scene scene;
  CampaignTask task;
  bool valid = false;
};

Generated generate(std::uint64_t seed, int index, CampaignGenerator generator) {
  Rng rng = rollout_stream(splitmix64(seed) ^ 0x5eedca3a16e5ULL, static_cast<std::uint64_t>(index));
  Generated g;
  g.task.index = index;
  for (int attempt = 0; attempt < kGenerationAttempts; ++attempt) {
    g.scene = draw_scene(rng, generator, &g.task.description);
    g.task.yaml = to_yaml(g.scene, index, g.task.description);
    if (loads(g.task.yaml)) {
      g.valid = true;
      return g;
    }
    // A goal over a top that another box covers in part: fall back to the start's first point.
    g.scene.goal = {{g.scene.start[0]}};
    g.task.yaml = to_yaml(g.scene, index, g.task.description);
    if (loads(g.task.yaml)) {
      g.valid = true;
      return g;
    }
  }
  return g;
}

// Validation of one task text in a forked child under the verifier budget; the child sends back the summary.
// The validation's seed of task `index` (validate_text), which the false-alarm search uses too.
std::uint64_t task_seed(const CampaignOptions& options, int index) {
  return splitmix64(options.seed) ^ static_cast<std::uint64_t>(index);
}

// Saves a false-alarm candidate and, with the check set, searches it for a failing rollout.
void check_false_alarm(const std::string& yaml, const CampaignOptions& options, int index,
                       CampaignRecord* rec) {
  rec->candidate = true;
  std::filesystem::create_directories(options.out / "unreliable");
  const std::filesystem::path file = options.out / "unreliable" / ("task-" + std::to_string(index) + ".yaml");
  std::ofstream(file) << yaml;
  rec->saved = file.string();
  if (!options.false_alarm_check) return;
  rec->check = options.false_alarm_check(file, task_seed(options, index));
  rec->false_alarm = !rec->check.failure_found;
}

CampaignRecord validate_text(const std::string& yaml, const CampaignOptions& options, int index) {
  CampaignRecord rec;
  rec.index = index;
  std::shared_ptr<const LoadedTask> task;
  try {
    task = load_task_from_string(yaml, "campaign-" + std::to_string(index));
  } catch (const std::exception& e) {
    rec.status = "invalid";
    rec.detail = e.what();
    return rec;
  }
  const ForkedRun run =
      run_forked_with_budget(options.verifier_budget, [&](const std::function<void()>& done) {
        ValidateOptions o;
        o.n = options.rollouts;
        o.seed = task_seed(options, index);
        o.threads = options.threads;
        o.mode = SampleMode::kExtreme;
        o.counterexample_budget = 0;  // soundness is the question here, not the search for failures
        o.spring_coast = options.spring_coast;
        o.after_verify = done;
        const ValidationResult r = run_validation(task, "s", o);
        nlohmann::json j;
        j["reliable"] = r.prediction.reliable;
        j["failure"] = r.prediction.failure;
        j["rollouts"] = static_cast<int>(r.rollouts.size());
        j["successes"] = r.successes;
        j["unstable"] = r.unstable;
        j["ends"] = static_cast<int>(r.ends.size());
        j["outside"] = r.outside;
        j["soundness"] = r.soundness;
        j["soundness_bug"] = r.soundness_bug;
        j["max_distance_outside"] = r.worst.empty() ? 0.0 : r.worst.front().distance;
        j["verify_seconds"] = r.verify_seconds;
        j["seed"] = o.seed;
        return json_text(j);
      });
  if (run.timed_out) {
    rec.status = "timed-out";
    rec.detail = "verifier over " + num(options.verifier_budget) + " s";
    return rec;
  }
  const nlohmann::json j = nlohmann::json::parse(run.payload);
  rec.reliable = j["reliable"];
  rec.detail = j["failure"];
  rec.rollouts = j["rollouts"];
  rec.successes = j["successes"];
  rec.unstable = j["unstable"];
  rec.ends = j["ends"];
  rec.outside = j["outside"];
  rec.soundness = j["soundness"];
  rec.soundness_bug = j["soundness_bug"];
  rec.max_distance_outside = j["max_distance_outside"];
  rec.verify_seconds = j["verify_seconds"];
  rec.status = campaign_status(rec.rollouts, rec.unstable, rec.outside, rec.soundness_bug);
  rec.replay = "cmt validate TASK --strategy s -n " + std::to_string(options.rollouts) + " --seed " +
               std::to_string(j["seed"].get<std::uint64_t>()) + " --mode extreme" +
               (options.spring_coast ? "" : " --no-spring-coast");
  return rec;
}

// Smaller variants of a scene: each box dropped, the start reduced to its first point.
std::vector<Scene> shrink_candidates(const Scene& s) {
  std::vector<Scene> out;
  for (std::size_t b = 0; b < s.boxes.size(); ++b) {
    Scene t = s;
    t.boxes.erase(t.boxes.begin() + static_cast<long>(b));
    out.push_back(t);
  }
  for (std::size_t r = 0; r < s.ramps.size(); ++r) {
    Scene t = s;
    t.ramps.erase(t.ramps.begin() + static_cast<long>(r));
    out.push_back(t);
  }
  if (s.start_kind != "point") {
    Scene t = s;
    t.start_kind = "point";
    t.start = {s.start[0]};
    out.push_back(t);
  }
  return out;
}

// Greedy minimization: keep any smaller variant that still shows a bug, until none does.
Scene minimize(Scene s, const std::string& description, const CampaignOptions& options, int index,
               CampaignRecord* rec) {
  for (bool shrunk = true; shrunk;) {
    shrunk = false;
    for (const Scene& t : shrink_candidates(s)) {
      const std::string yaml = to_yaml(t, index, description);
      const CampaignRecord r = validate_text(yaml, options, index);
      if (r.status == "bug") {
        s = t;
        *rec = r;
        shrunk = true;
        break;
      }
    }
  }
  return s;
}

std::map<int, nlohmann::json> recorded(const std::filesystem::path& file, const CampaignOptions& options) {
  std::map<int, nlohmann::json> out;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    try {
      const nlohmann::json j = nlohmann::json::parse(line);
      if (j.value("seed", std::uint64_t{0}) == options.seed && j.value("n", 0) == options.rollouts &&
          j.value("generator", "default") == campaign_generator_name(options.generator) &&
          j.value("spring_coast", false) == options.spring_coast)  // lines without it: first order
        out[j["index"].get<int>()] = j;
    } catch (const std::exception&) {  // a line cut by a kill: that task runs again
    }
  }
  return out;
}

CampaignRecord record_from_json(const nlohmann::json& j) {
  CampaignRecord r;
  r.index = j["index"];
  r.status = j["status"];
  r.description = j.value("description", "");
  r.reliable = j.value("reliable", false);
  r.saved = j.value("saved", "");
  r.replay = j.value("replay", "");
  r.rollouts = j.value("rollouts", 0);
  r.unstable = j.value("unstable", 0);
  r.outside = j.value("outside", 0);
  r.max_distance_outside = j.value("max_distance_outside", 0.0);
  r.candidate = j.value("false_alarm_candidate", false);
  if (j.contains("false_alarm") && j["false_alarm"].is_boolean())
    r.false_alarm = j["false_alarm"].get<bool>();
  return r;
}

}  // namespace

std::string campaign_status(int rollouts, int unstable, int outside, bool soundness_bug) {
  if (outside > 0 || soundness_bug) return "bug";
  if (unstable > kInconclusiveUnstableShare * rollouts) return "inconclusive";
  return "sound";
}

const char* campaign_generator_name(CampaignGenerator g) {
  return g == CampaignGenerator::kWide ? "wide" : g == CampaignGenerator::kSlanted ? "slanted" : "default";
}

CampaignTask generate_campaign_task(std::uint64_t seed, int index, CampaignGenerator generator) {
  return generate(seed, index, generator).task;
}

nlohmann::json campaign_record_json(const CampaignRecord& r) {
  return {{"index", r.index},
          {"status", r.status},
          {"description", r.description},
          {"detail", r.detail},
          {"reliable", r.reliable},
          {"rollouts", r.rollouts},
          {"successes", r.successes},
          {"unstable", r.unstable},
          {"ends", r.ends},
          {"outside", r.outside},
          {"soundness", r.soundness},
          {"max_distance_outside", r.max_distance_outside},
          {"soundness_bug", r.soundness_bug},
          {"verify_seconds", r.verify_seconds},
          {"saved", r.saved},
          {"replay", r.replay},
          {"false_alarm_candidate", r.candidate},
          {"false_alarm", r.false_alarm ? nlohmann::json(*r.false_alarm) : nlohmann::json()},
          {"failure_rollouts", r.check.rollouts},
          {"failure_closest",
           std::isfinite(r.check.closest) ? nlohmann::json(r.check.closest) : nlohmann::json()},
          {"failure_replay", r.check.replay}};
}

CampaignSummary run_soundness_campaign(const CampaignOptions& options,
                                       const std::function<void(const CampaignRecord&)>& progress) {
  std::filesystem::create_directories(options.out / "bugs");
  const std::filesystem::path results = options.out / "results.jsonl";
  const std::map<int, nlohmann::json> done = recorded(results, options);
  std::ofstream log(results, std::ios::app);
  CampaignSummary sum;
  for (int i = options.first; i < options.tasks; ++i) {
    CampaignRecord rec;
    if (const auto it = done.find(i); it != done.end()) {
      rec = record_from_json(it->second);
      ++sum.resumed;
    } else {
      const Generated g = generate(options.seed, i, options.generator);
      if (!g.valid) {
        rec.index = i;
        rec.status = "invalid";
        rec.detail = "no draw put the start and goal on the contact surface";
      } else {
        rec = validate_text(g.task.yaml, options, i);
        Scene scene = g.scene;
        if (rec.status == "bug" && options.minimize)
          scene = minimize(scene, g.task.description, options, i, &rec);
        if (rec.status == "sound" && !rec.reliable && rec.rollouts > rec.unstable &&
            rec.successes == rec.rollouts - rec.unstable)
          check_false_alarm(g.task.yaml, options, i, &rec);
        if (rec.status == "bug" || rec.status == "inconclusive") {
          const std::filesystem::path folder = options.out / (rec.status == "bug" ? "bugs" : "inconclusive");
          std::filesystem::create_directories(folder);
          const std::filesystem::path file = folder / ("task-" + std::to_string(i) + ".yaml");
          std::ofstream(file) << to_yaml(scene, i, g.task.description);
          rec.saved = file.string();
          const std::size_t at = rec.replay.find("TASK");
          if (at != std::string::npos) rec.replay.replace(at, 4, file.string());
        }
      }
      rec.description = g.task.description;
      nlohmann::json line = campaign_record_json(rec);
      line["seed"] = options.seed;
      line["n"] = options.rollouts;
      if (options.generator != CampaignGenerator::kDefault)
        line["generator"] = campaign_generator_name(options.generator);
      line["spring_coast"] = options.spring_coast;
      log << json_text(line) << "\n" << std::flush;
    }
    ++sum.run;
    if (rec.status == "sound") ++sum.sound;
    if (rec.status == "invalid") ++sum.invalid;
    if (rec.status == "timed-out") ++sum.timed_out;
    if (rec.status == "bug") {
      ++sum.bugs;
      sum.bug_records.push_back(rec);
    }
    if (rec.status == "inconclusive") {
      ++sum.inconclusive;
      sum.inconclusive_records.push_back(rec);
    }
    if (rec.status == "sound" || rec.status == "bug" || rec.status == "inconclusive") {
      sum.rollouts += rec.rollouts;
      sum.unstable += rec.unstable;
    }
    if (rec.reliable) ++sum.reliable;
    sum.candidates += rec.candidate;
    if (rec.false_alarm) ++(*rec.false_alarm ? sum.false_alarms : sum.failures_found);
    if (progress) progress(rec);
  }
  return sum;
}

}  // namespace cmt
