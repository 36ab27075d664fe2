// Layers of a teaching session's 3-D page (teach_view.h).
#include "experiments/cli/teach_view.h"

#include <tuple>

#include "experiments/report/view_data.h"

namespace cmt {
namespace {

using nlohmann::json;

void add_pieces(json& layer, const LoadedTask& task, const std::vector<ReachedPiece>& pieces,
                const std::string& what) {
  for (const ReachedPiece& p : pieces)
    report::add_view_piece(layer, p.polygon, p.holes,
                           {{"atom", p.atom}, {"name", task.cspace.atom_name(p.atom)}, {"what", what}});
}

std::vector<ReachedPiece> cell_pieces(const LoadedTask& task, const std::vector<teaching::StartCell>& cells) {
  std::vector<ReachedPiece> out;
  for (const teaching::StartCell& c : cells)
    for (ReachedPiece& p : ReachedSet::from_region(task, c.region).pieces()) out.push_back(std::move(p));
  return out;
}

}  // namespace

json teach_view_data(const teaching::Session& session, const std::string& title) {
  const LoadedTask& task = session.task();
  report::ViewInput input;
  input.task = &task;
  input.title = title;
  json data = report::view_data(input);
  const std::vector<teaching::TeachStep>& steps = session.steps();
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const teaching::TeachStep& s = steps[k];
    const std::string id = "step" + std::to_string(k + 1);
    const std::string group = "step " + std::to_string(k + 1) + ": " + s.motion;
    struct LayerSpec {
      std::string suffix, name, color;
      double opacity;
      std::vector<ReachedPiece> pieces;
    };
    const std::vector<LayerSpec> specs = {
        {"solved", "solved start cells", "#00a36c", 0.9, cell_pieces(task, s.solved)},
        {"remaining", "start remaining", "#f0b400", 0.9, cell_pieces(task, s.remaining)},
        {"stops-solved", s.motion + " may stop here (from the solved cells)", "#1f77b4", 0.5,
         s.stops_from_solved},
        {"stops-remaining", s.motion + " may stop here (from the remaining start)", "#ff7f0e", 0.5,
         s.stops_from_remaining},
        {"avoid", "stops from which the earlier motions fail (points to avoid)", "#d62728", 0.8, s.blocking}};
    for (const LayerSpec& spec : specs) {
      if (spec.pieces.empty()) continue;
      json layer = report::make_layer(id + "-" + spec.suffix, spec.name, group, spec.color, spec.opacity);
      add_pieces(layer, task, spec.pieces, spec.name);
      layer["visible"] = k + 1 == steps.size();  // the last step shown first; the others a click away
      data["layers"].push_back(std::move(layer));
    }
  }
  return data;
}

json backprojection_view_data(const LoadedTask& task, const std::vector<BackprojectionLayers>& steps,
                              const std::string& title) {
  report::ViewInput input;
  input.task = &task;
  input.title = title;
  json data = report::view_data(input);
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const BackprojectionLayers& s = steps[k];
    const std::string id = "motion" + std::to_string(k + 1);
    const std::string group = s.motion + " (backprojection " + std::to_string(k + 1) + " from the goal)";
    const std::vector<
        std::tuple<std::string, std::string, std::string, double, const std::vector<ReachedPiece>*>>
        specs = {{"strong", "strong backprojection S: surely stops in the target", "#00a36c", 0.6, &s.strong},
                 {"weak", "weak backprojection W(B): may reach a stop outside the target", "#ff7f0e", 0.35,
                  &s.weak},
                 {"base", "B: may stop outside the target (points to avoid)", "#d62728", 0.9, &s.base}};
    for (const auto& [suffix, name, color, opacity, pieces] : specs) {
      if (pieces->empty()) continue;
      json layer = report::make_layer(id + "-" + suffix, name, group, color, opacity);
      add_pieces(layer, task, *pieces, name);
      layer["visible"] = k + 1 == steps.size() && suffix != "weak";  // the chain's first motion shown first
      data["layers"].push_back(std::move(layer));
    }
  }
  return data;
}

}  // namespace cmt
