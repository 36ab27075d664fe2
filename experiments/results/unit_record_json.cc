#include "experiments/results/unit_record_json.h"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "experiments/common/json_text.h"

namespace cmt {

namespace {

using nlohmann::json;

// JSON has no infinities or NaN (nlohmann writes them as null); a distance to an empty prediction is +inf.
json real(double v) {
  if (std::isfinite(v)) return v;
  if (std::isnan(v)) return "nan";
  return v > 0 ? "inf" : "-inf";
}

double real(const json& j) {
  if (j.is_number()) return j.get<double>();
  const std::string s = j.get<std::string>();
  if (s == "inf") return std::numeric_limits<double>::infinity();
  if (s == "-inf") return -std::numeric_limits<double>::infinity();
  if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
  throw std::runtime_error("unit record: bad number '" + s + "'");
}

template <class T>
json optional_json(const std::optional<T>& v) {
  if (!v) return nullptr;
  if constexpr (std::is_same_v<T, double>)
    return real(*v);
  else
    return *v;
}

}  // namespace

std::string unit_record_to_text(const UnitRecord& r) {
  json rows = json::array();
  for (const RolloutRow& row : r.rollouts)
    rows.push_back({row.rollout, row.motion, real(row.start[0]), real(row.start[1]), real(row.start[2]),
                    real(row.end[0]), real(row.end[1]), real(row.end[2]), row.atom, row.termination,
                    optional_json(row.inside), optional_json(row.distance), row.success, row.unstable});
  const json j = {{"reliable", r.reliable},
                  {"failure", r.failure},
                  {"verify_seconds", real(r.verify_seconds)},
                  {"verify_json", r.verify_json},
                  {"verifier_theta_v", real(r.verifier_theta_v)},
                  {"verifier_model", r.verifier_model},
                  {"rollouts", rows},
                  {"counts", {r.rollout_count, r.successes, r.unstable, r.ends, r.outside}},
                  {"soundness", real(r.soundness)},
                  {"coverage", real(r.coverage)},
                  {"coverage_radius", real(r.coverage_radius)},
                  {"contact_tolerance", real(r.contact_tolerance)},
                  {"soundness_bug", r.soundness_bug},
                  {"counterexample", optional_json(r.counterexample)},
                  {"sticking", optional_json(r.sticking)},
                  {"rollout_seconds", real(r.rollout_seconds)},
                  {"falsify", optional_json(r.falsify)}};
  return json_text(j);
}

UnitRecord unit_record_from_text(const std::string& text) {
  try {
    const json j = json::parse(text);
    UnitRecord r;
    r.reliable = j.at("reliable").get<bool>();
    r.failure = j.at("failure").get<std::string>();
    r.verify_seconds = real(j.at("verify_seconds"));
    r.verify_json = j.at("verify_json").get<std::string>();
    r.verifier_theta_v = real(j.at("verifier_theta_v"));
    r.verifier_model = j.at("verifier_model").get<std::string>();
    for (const json& a : j.at("rollouts")) {
      RolloutRow row;
      row.rollout = a.at(0).get<int>();
      row.motion = a.at(1).get<int>();
      for (int k = 0; k < 3; ++k) {
        row.start[k] = real(a.at(2 + k));
        row.end[k] = real(a.at(5 + k));
      }
      row.atom = a.at(8).get<int>();
      row.termination = a.at(9).get<std::string>();
      if (!a.at(10).is_null()) row.inside = a.at(10).get<bool>();
      if (!a.at(11).is_null()) row.distance = real(a.at(11));
      row.success = a.at(12).get<bool>();
      row.unstable = a.at(13).get<bool>();
      r.rollouts.push_back(std::move(row));
    }
    const json& c = j.at("counts");
    r.rollout_count = c.at(0).get<int>();
    r.successes = c.at(1).get<int>();
    r.unstable = c.at(2).get<int>();
    r.ends = c.at(3).get<int>();
    r.outside = c.at(4).get<int>();
    r.soundness = real(j.at("soundness"));
    r.coverage = real(j.at("coverage"));
    r.coverage_radius = real(j.at("coverage_radius"));
    r.contact_tolerance = real(j.at("contact_tolerance"));
    r.soundness_bug = j.at("soundness_bug").get<bool>();
    if (!j.at("counterexample").is_null()) r.counterexample = j.at("counterexample").get<std::string>();
    if (!j.at("sticking").is_null()) r.sticking = j.at("sticking").get<std::string>();
    r.rollout_seconds = real(j.at("rollout_seconds"));
    if (!j.at("falsify").is_null()) r.falsify = j.at("falsify").get<std::string>();
    return r;
  } catch (const json::exception& e) {
    throw std::runtime_error(std::string("unit record: ") + e.what());
  }
}

}  // namespace cmt
