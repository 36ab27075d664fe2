#include "experiments/report/falsify_figure.h"

#include <set>
#include <stdexcept>

namespace cmt::report {
namespace {

const nlohmann::json& array_at(const nlohmann::json& j, const char* key) {
  static const nlohmann::json kEmpty = nlohmann::json::array();
  if (!j.contains(key) || j[key].is_null()) return kEmpty;
  if (!j[key].is_array()) throw std::invalid_argument(std::string(key) + ": expected a list");
  return j[key];
}

int step_of(const nlohmann::json& item, const std::string& where) {
  if (!item.is_object() || !item.contains("step") || !item["step"].is_number_integer())
    throw std::invalid_argument(where + ".step: expected an integer");
  return item["step"].get<int>();
}

const nlohmann::json& member(const nlohmann::json& item, const char* key, const std::string& where) {
  if (!item.contains(key)) throw std::invalid_argument(where + "." + key + ": missing");
  return item[key];
}

bool flag(const nlohmann::json& item, const char* key, const std::string& where) {
  if (!item.contains(key) || !item[key].is_boolean())
    throw std::invalid_argument(where + "." + key + ": expected true or false");
  return item[key].get<bool>();
}

}  // namespace

std::vector<FalsifyMotionFigure> falsify_motion_figures(const nlohmann::json& falsify,
                                                        const PredictedSets& prediction,
                                                        const std::vector<RolloutRow>& rollouts,
                                                        const Task& task) {
  const int dim = task.dimension;
  const int steps = static_cast<int>(prediction.steps.size());
  std::vector<FalsifyMotionFigure> figures(static_cast<std::size_t>(steps));
  std::set<int> measured;
  const auto figure_of = [&](const nlohmann::json& item, const std::string& where) -> FalsifyMotionFigure* {
    const int k = step_of(item, where);
    if (k < 0 || k >= steps) return nullptr;  // a step the prediction does not have
    measured.insert(k);
    return &figures[static_cast<std::size_t>(k)];
  };
  double radius = 0;  // a gap without its own radius (older results): the pooled one
  if (falsify.contains("coverage_radius") && !falsify["coverage_radius"].is_null()) {
    if (!falsify["coverage_radius"].is_number())
      throw std::invalid_argument("coverage_radius: expected a number");
    radius = falsify["coverage_radius"].get<double>();
  }
  const nlohmann::json& pieces = array_at(falsify, "pieces");
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const std::string where = "pieces[" + std::to_string(i) + "]";
    FalsifyMotionFigure* f = figure_of(pieces[i], where);
    if (f && !flag(pieces[i], "reached", where) && pieces[i].contains("points"))
      f->search.unreached_pieces.push_back(json_points(pieces[i]["points"], dim, where + ".points"));
  }
  const nlohmann::json& gaps = array_at(falsify, "gaps");
  for (std::size_t i = 0; i < gaps.size(); ++i) {
    const std::string where = "gaps[" + std::to_string(i) + "]";
    FalsifyMotionFigure* f = figure_of(gaps[i], where);
    if (!f || flag(gaps[i], "reached", where)) continue;
    double gap_radius = radius;
    if (gaps[i].contains("radius")) {
      if (!gaps[i]["radius"].is_number()) throw std::invalid_argument(where + ".radius: expected a number");
      gap_radius = gaps[i]["radius"].get<double>();
    }
    f->search.unreached_gaps.push_back(
        {json_point(member(gaps[i], "point", where), dim, where + ".point"), gap_radius});
  }
  const nlohmann::json& ends = array_at(falsify, "search_ends");
  for (std::size_t i = 0; i < ends.size(); ++i) {
    const std::string where = "search_ends[" + std::to_string(i) + "]";
    FalsifyMotionFigure* f = figure_of(ends[i], where);
    if (!f) continue;
    if (!ends[i].contains("how") || !ends[i]["how"].is_string())
      throw std::invalid_argument(where + ".how: expected a string");
    f->search.ends.push_back({ends[i]["how"].get<std::string>(),
                              json_point(member(ends[i], "end", where), dim, where + ".end"),
                              flag(ends[i], "inside", where)});
  }
  std::vector<FalsifyMotionFigure> out;
  for (int k : measured) {
    FalsifyMotionFigure f = std::move(figures[static_cast<std::size_t>(k)]);
    f.step = k;
    f.motion = prediction.steps[static_cast<std::size_t>(k)].motion;
    f.prediction.reliable = prediction.reliable;
    f.prediction.steps = {prediction.steps[static_cast<std::size_t>(k)]};
    for (const RolloutRow& r : rollouts)
      if (r.motion == k && r.termination != "none") {  // a time-out is no end (as the search's ends)
        f.random.push_back(r);
        f.random.back().motion = 0;
      }
    f.view = widest_view(task, f.prediction.steps[0].termination);
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace cmt::report
