#include "experiments/report/predicted_sets.h"

#include <limits>
#include <stdexcept>

namespace cmt::report {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double coordinate(const nlohmann::json& v) { return v.is_number() ? v.get<double>() : kNaN; }

PredictedPiece piece(const nlohmann::json& j, int dimension, const std::string& where) {
  if (!j.is_object()) throw std::invalid_argument(where + ": expected an object");
  PredictedPiece p;
  p.atom = j.value("atom", -1);
  p.name = j.value("name", "");
  p.kind = j.value("kind", "");
  if (p.kind == "free") {
    if (!j.contains("center")) throw std::invalid_argument(where + ".center: missing");
    p.center = json_point(j["center"], dimension, where + ".center");
    p.radius = j.contains("radius") ? coordinate(j["radius"]) : kNaN;
    return p;
  }
  if (!j.contains("polygon")) throw std::invalid_argument(where + ".polygon: missing");
  p.polygon = json_points(j["polygon"], dimension, where + ".polygon");
  if (j.contains("holes")) {
    if (!j["holes"].is_array()) throw std::invalid_argument(where + ".holes: expected a list of polygons");
    for (std::size_t h = 0; h < j["holes"].size(); ++h)
      p.holes.push_back(json_points(j["holes"][h], dimension, where + ".holes[" + std::to_string(h) + "]"));
  }
  return p;
}

}  // namespace

Vec3 json_point(const nlohmann::json& j, int dimension, const std::string& where) {
  const std::size_t expected = dimension == 2 ? 2 : 3;
  if (!j.is_array() || j.size() != expected)
    throw std::invalid_argument(where + ": expected a point of " + std::to_string(expected) + " coordinates");
  if (dimension == 2) return {coordinate(j[0]), 0.0, coordinate(j[1])};
  return {coordinate(j[0]), coordinate(j[1]), coordinate(j[2])};
}

std::vector<Vec3> json_points(const nlohmann::json& j, int dimension, const std::string& where) {
  if (!j.is_array()) throw std::invalid_argument(where + ": expected a list of points");
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < j.size(); ++i)
    out.push_back(json_point(j[i], dimension, where + "[" + std::to_string(i) + "]"));
  return out;
}

PredictedSets parse_predicted_sets(const nlohmann::json& verify_json, int dimension) {
  if (!verify_json.is_object()) throw std::invalid_argument("expected a JSON object");
  PredictedSets out;
  out.reliable = verify_json.value("reliable", false);
  out.failed_step = verify_json.value("failed_step", -1);
  if (!verify_json.contains("steps")) return out;
  const nlohmann::json& steps = verify_json["steps"];
  if (!steps.is_array()) throw std::invalid_argument("steps: expected a list");
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const std::string where = "steps[" + std::to_string(i) + "]";
    if (!steps[i].is_object()) throw std::invalid_argument(where + ": expected an object");
    PredictedStep s;
    s.motion = steps[i].value("motion", "motion " + std::to_string(i + 1));
    const nlohmann::json& t =
        steps[i].contains("termination") ? steps[i]["termination"] : nlohmann::json::array();
    if (!t.is_array()) throw std::invalid_argument(where + ".termination: expected a list");
    for (std::size_t k = 0; k < t.size(); ++k)
      s.termination.push_back(piece(t[k], dimension, where + ".termination[" + std::to_string(k) + "]"));
    out.steps.push_back(std::move(s));
  }
  return out;
}

}  // namespace cmt::report
