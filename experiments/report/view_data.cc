#include "experiments/report/view_data.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>

#include "models/task.h"

namespace cmt::report {
namespace {

using nlohmann::json;

// Motion colours (the last motion of a strategy is judged against the goal; the colours only tell motions
// apart).
constexpr const char* kMotionColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                         "#ff7f0e", "#17becf", "#8c564b", "#e377c2"};
constexpr const char* kFaceColor = "#9aa5b1";
constexpr const char* kEdgeColor = "#52606d";
constexpr const char* kStartColor = "#f0b400";
constexpr const char* kGoalColor = "#00a36c";
constexpr const char* kOutsideColor = "#000000";

const char* motion_color(int i) { return kMotionColors[i % std::size(kMotionColors)]; }

// "#rrggbb" scaled toward black by `factor` (observed ends are drawn darker than their predicted set).
std::string darker(const std::string& hex, double factor) {
  char out[8];
  const long rgb = std::strtol(hex.c_str() + 1, nullptr, 16);
  const auto scale = [&](int shift) { return static_cast<int>(((rgb >> shift) & 0xff) * factor); };
  std::snprintf(out, sizeof out, "#%02x%02x%02x", scale(16), scale(8), scale(0));
  return out;
}

// Non-finite coordinates (a piece the verifier could not place) become null in JSON; the page skips
// nothing, so such points are left out of the layers.
bool finite(const Vec3& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()); }

json cspace_layers(const CSpace& c) {
  json faces = make_layer("cspace-faces", "C-space faces", "scene", kFaceColor, 0.18);
  for (const Face& f : c.faces())
    faces["polygons"].push_back(
        {{"points", view_points(f.polygon)},
         {"info",
          {{"atom", f.id}, {"name", c.atom_name(f.id)}, {"kind", "face"}, {"friction", f.friction}}}});
  json edges = make_layer("cspace-edges", "C-space edges", "scene", kEdgeColor, 1);
  for (const Edge& e : c.edges())
    edges["segments"].push_back({{"points", view_points({e.a, e.b})},
                                 {"info", {{"atom", e.id}, {"name", c.atom_name(e.id)}, {"kind", "edge"}}}});
  return json::array({faces, edges});
}

void add_region(json& layer, const Region& r, const std::string& what) {
  const json info = {{"region", what}, {"key", r.key}};
  if (r.kind == Region::Kind::kPoint)
    layer["points"].push_back({{"point", view_point(r.points[0])}, {"info", info}});
  else if (r.kind == Region::Kind::kSegment)
    layer["segments"].push_back({{"points", view_points(r.points)}, {"info", info}});
  else
    layer["polygons"].push_back({{"points", view_points(r.points)}, {"info", info}});
}

json region_layers(const Task& t) {
  json start = make_layer("start", "start region", "scene", kStartColor, 0.8);
  start["style"]["size"] = 1.6;
  add_region(start, t.start, "start");
  json goal = make_layer("goal", "goal", "scene", kGoalColor, 0.6);
  goal["style"]["size"] = 1.6;
  for (const Region& g : t.goal) add_region(goal, g, "goal");
  return json::array({start, goal});
}

// Area of a planar loop in 3-D (half the norm of Newell's vector).
double loop_area(const std::vector<Vec3>& loop) {
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 0; i < loop.size(); ++i) n += loop[i].cross(loop[(i + 1) % loop.size()]);
  return 0.5 * n.norm();
}

double piece_area(const PredictedPiece& p) {
  double a = loop_area(p.polygon);
  for (const std::vector<Vec3>& h : p.holes) a -= loop_area(h);
  return a;
}

// Ends of motion `step` per atom (the atom the rollout's end lies on), for the pieces' info.
std::map<int, int> ends_per_atom(const std::vector<RolloutRow>* ends, int step) {
  std::map<int, int> out;
  if (ends)
    for (const RolloutRow& r : *ends)
      if (r.motion == step) ++out[r.atom];
  return out;
}

// Opacity of a predicted piece by its atom's stick class: must-stick atoms solid, may-stick lighter, and the
// pieces on never-stick atoms (there by the slow-stop rule, sensing or the contact lift) faint.
double class_opacity(const std::string& stick) {
  return stick == "must" ? 0.85 : stick == "may" ? 0.5 : 0.22;
}

json prediction_layer(const ViewInput& in, const PredictedStep& step, int i) {
  json layer = make_layer("predicted-" + std::to_string(i), "predicted ends: " + step.motion,
                          "motion " + std::to_string(i + 1) + ": " + step.motion, motion_color(i), 0.55);
  layer["style"]["offset"] = -1;  // drawn in front of the C-space face it lies on
  const std::map<int, int> counts = ends_per_atom(in.ends, i);
  for (const PredictedPiece& p : step.termination) {
    const auto it = counts.find(p.atom);
    json info = {{"atom", p.atom},
                 {"name", p.name},
                 {"kind", p.kind},
                 {"motion", step.motion},
                 {"ends on this atom", it == counts.end() ? 0 : it->second}};
    json style = json::object();
    if (in.stick_class && p.atom >= 0) {
      const std::string stick = in.stick_class(*in.task, step.motion, p.atom);
      info["stick"] = stick;
      style["opacity"] = class_opacity(stick);
    }
    if (p.kind == "free") {
      info["radius"] = p.radius;
      layer["spheres"].push_back({{"center", view_point(p.center)}, {"radius", p.radius}, {"info", info}});
    } else if (p.kind == "vertex" || p.polygon.size() == 1) {
      layer["points"].push_back({{"point", view_point(p.polygon.at(0))}, {"style", style}, {"info", info}});
    } else if (p.kind == "edge" || p.polygon.size() == 2) {
      layer["segments"].push_back({{"points", view_points(p.polygon)}, {"style", style}, {"info", info}});
    } else {
      json holes = json::array();
      for (const std::vector<Vec3>& h : p.holes) holes.push_back(view_points(h));
      info["area"] = piece_area(p);
      layer["polygons"].push_back(
          {{"points", view_points(p.polygon)}, {"holes", holes}, {"style", style}, {"info", info}});
    }
  }
  return layer;
}

json ends_layers(const std::vector<RolloutRow>& ends, const std::vector<std::string>& motions) {
  json out = json::array();
  for (int i = 0; i < static_cast<int>(motions.size()); ++i) {
    const std::string group = "motion " + std::to_string(i + 1) + ": " + motions[i];
    json inside = make_layer("ends-inside-" + std::to_string(i), "observed ends in the prediction", group,
                             darker(motion_color(i), 0.55), 1);
    json outside = make_layer("ends-outside-" + std::to_string(i), "observed ends outside the prediction",
                              group, kOutsideColor, 1);
    outside["style"]["size"] = 1.5;
    for (const RolloutRow& r : ends) {
      if (r.motion != i || !finite(r.end)) continue;
      const json info = {{"rollout", r.rollout},         {"motion", motions[i]},   {"atom", r.atom},
                         {"termination", r.termination}, {"distance", r.distance}, {"success", r.success}};
      (r.inside ? inside : outside)["points"].push_back({{"point", view_point(r.end)}, {"info", info}});
    }
    out.push_back(inside);
    out.push_back(outside);
  }
  return out;
}

json trajectory_layer(const std::vector<ViewTrajectory>& trajectories, const std::string& id,
                      const std::string& name, const std::string& color) {
  json layer = make_layer(id, name, "rollouts", color, 0.9);
  for (const ViewTrajectory& t : trajectories)
    layer["polylines"].push_back(
        {{"points", view_points(t.points)}, {"info", {{"rollout", t.rollout}, {"success", t.success}}}});
  return layer;
}

// An axis box grown point by point; empty until the first finite point.
struct Box {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  void grow(const Vec3& p) {
    if (!finite(p)) return;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void grow(const std::vector<Vec3>& ps) {
    for (const Vec3& p : ps) grow(p);
  }
  json to_json() const {
    const bool empty = !finite(lo);
    return {{"min", view_point(empty ? Vec3::Zero() : lo)}, {"max", view_point(empty ? Vec3::Zero() : hi)}};
  }
};

json bounds_of(const CSpace& c, const Task& t) {
  Box box;
  for (const Vertex& v : c.vertices()) box.grow(v.point);
  box.grow(t.start.points);
  for (const Region& g : t.goal) box.grow(g.points);
  return box.to_json();
}

// Where the camera looks first: the start, the goals, the predicted pieces, the ends and the trajectories.
json focus_of(const ViewInput& in) {
  Box box;
  box.grow(in.task->task.start.points);
  for (const Region& g : in.task->task.goal) box.grow(g.points);
  if (in.prediction)
    for (const PredictedStep& s : in.prediction->steps)
      for (const PredictedPiece& p : s.termination) {
        box.grow(p.polygon);
        if (p.kind == "free") {
          box.grow(p.center + Vec3::Constant(p.radius));
          box.grow(p.center - Vec3::Constant(p.radius));
        }
      }
  if (in.ends)
    for (const RolloutRow& r : *in.ends) box.grow(r.end);
  for (const ViewTrajectory& t : in.trajectories) box.grow(t.points);
  for (const ViewTrajectory& t : in.counterexample) box.grow(t.points);
  return box.to_json();
}

}  // namespace

json view_point(const Vec3& p) { return json::array({p.x(), p.y(), p.z()}); }

json view_points(const std::vector<Vec3>& ps) {
  json out = json::array();
  for (const Vec3& p : ps)
    if (finite(p)) out.push_back(view_point(p));
  return out;
}

void add_view_piece(json& layer, const std::vector<Vec3>& polygon,
                    const std::vector<std::vector<Vec3>>& holes, const json& info) {
  if (polygon.size() == 1) {
    layer["points"].push_back({{"point", view_point(polygon.front())}, {"info", info}});
  } else if (polygon.size() == 2) {
    layer["segments"].push_back({{"points", view_points(polygon)}, {"info", info}});
  } else if (polygon.size() > 2) {
    json hole_points = json::array();
    for (const std::vector<Vec3>& h : holes) hole_points.push_back(view_points(h));
    layer["polygons"].push_back({{"points", view_points(polygon)}, {"holes", hole_points}, {"info", info}});
  }
}

nlohmann::json make_layer(const std::string& id, const std::string& name, const std::string& group,
                          const std::string& color, double opacity) {
  return {{"id", id},
          {"name", name},
          {"group", group},
          {"style", {{"color", color}, {"opacity", opacity}}},
          {"visible", true},
          {"polygons", json::array()},
          {"segments", json::array()},
          {"points", json::array()},
          {"polylines", json::array()},
          {"spheres", json::array()}};
}

nlohmann::json view_data(const ViewInput& in) {
  const LoadedTask& task = *in.task;
  json layers = cspace_layers(task.cspace);
  for (json& l : region_layers(task.task)) layers.push_back(std::move(l));
  std::vector<std::string> motions = in.motions;
  if (in.prediction) {
    motions.clear();
    for (const PredictedStep& s : in.prediction->steps) motions.push_back(s.motion);
    for (int i = 0; i < static_cast<int>(in.prediction->steps.size()); ++i)
      layers.push_back(prediction_layer(in, in.prediction->steps[i], i));
  }
  if (in.ends)
    for (json& l : ends_layers(*in.ends, motions)) layers.push_back(std::move(l));
  if (!in.trajectories.empty())
    layers.push_back(trajectory_layer(in.trajectories, "trajectories", "rollout trajectories", "#555555"));
  if (!in.counterexample.empty())
    layers.push_back(
        trajectory_layer(in.counterexample, "counterexample", "counterexample (replayed)", "#e00000"));
  return {{"format", "cmt-view-1"},
          {"title", in.title},
          {"units", unit_name(task.task.units)},
          {"bounds", bounds_of(task.cspace, task.task)},
          {"focus", focus_of(in)},
          {"layers", layers}};
}

}  // namespace cmt::report
