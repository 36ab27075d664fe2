#include "experiments/report/report.h"

#include <algorithm>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>

#include "experiments/common/json_text.h"
#include "experiments/report/cspace_figure.h"
#include "experiments/report/edr_figure.h"
#include "experiments/report/extremes_figure.h"
#include "experiments/report/falsify_figure.h"
#include "experiments/report/plan_graph_figure.h"
#include "experiments/report/predicted_sets.h"
#include "experiments/report/report_documents.h"
#include "experiments/report/report_table.h"
#include "experiments/report/results_db.h"
#include "experiments/report/sticking_figure.h"
#include "experiments/report/view_data.h"
#include "experiments/report/view_page.h"
#include "models/input_error.h"
#include "models/loaded_task.h"

namespace cmt::report {
namespace {

constexpr const char* kFigureDir = "figures";
constexpr const char* kFigurePrefix = "config_";  // every figure and 3-D page this command writes starts so
constexpr const char* kViewDir = "view";          // 3-D pages (view_page.h) and their shared assets
constexpr const char* kEdrFigurePrefix = "edr_";  // the EDR outcome figures (write_edr_figures)
constexpr const char* kExtremesFigurePrefix = "extremes_";  // §6.3.4's experiment (write_extremes_figures)
constexpr const char* kPlanFigurePrefix = "plan_";          // planned motions' cells (write_plan_figures)

std::string key(const ConfigRow& c, const std::string& column) {
  return column + " (config_id " + std::to_string(c.config_id) + ")";
}

// Figures of an earlier report of another database would be listed nowhere; only ours are removed.
void prepare_output(const std::filesystem::path& out_dir) {
  std::error_code ec;
  if (std::filesystem::exists(out_dir, ec) && !std::filesystem::is_directory(out_dir, ec))
    throw InputError(out_dir.string(), "-o", "exists and is not a directory");
  std::filesystem::create_directories(out_dir / kFigureDir, ec);
  if (!ec) std::filesystem::create_directories(out_dir / kViewDir, ec);
  if (ec)
    throw std::runtime_error(out_dir.string() + ": cannot create the report directory: " + ec.message());
  for (const auto& [dir, extension] : {std::pair{kFigureDir, ".png"}, std::pair{kViewDir, ".html"}})
    for (const auto& entry : std::filesystem::directory_iterator(out_dir / dir)) {
      const std::string name = entry.path().filename().string();
      if (entry.is_regular_file() &&
          (name.rfind(kFigurePrefix, 0) == 0 || name.rfind(kEdrFigurePrefix, 0) == 0 ||
           name.rfind(kExtremesFigurePrefix, 0) == 0 || name.rfind(kPlanFigurePrefix, 0) == 0) &&
          entry.path().extension() == extension)
        std::filesystem::remove(entry.path());
    }
}

class ReportBuilder {
 public:
  ReportBuilder(const ResultsDb& db, const std::filesystem::path& out_dir, StickClassOf stick_class,
                CounterexampleReplay replay)
      : db_(db), out_dir_(out_dir), stick_class_(std::move(stick_class)), replay_(std::move(replay)) {}

  ConfigSection section(const ConfigRow& c) {
    ConfigSection s;
    s.row = &c;
    s.label = config_label(c);
    const auto task = loaded(c);
    std::vector<std::string> motions;
    if (const Strategy* strategy = task->task.find_strategy(c.strategy))
      motions = strategy->motions;
    else
      s.notes.push_back("the task has no strategy '" + c.strategy + "'");

    std::optional<PredictedSets> prediction;
    if (c.prediction && !c.prediction->verify_json.is_null()) {
      try {
        prediction = parse_predicted_sets(c.prediction->verify_json, task->task.dimension);
      } catch (const std::exception& e) {  // std::invalid_argument, nlohmann::json type errors
        throw InputError(db_.path.string(), key(c, "predictions.verify_json"), e.what());
      }
    }
    add_notes(c, prediction, s.notes);

    CSpaceFigureData data{task.get(), motions, prediction ? &*prediction : nullptr, &c.rollouts, s.label};
    for (View view : views_for(task->task)) {
      const PlotCanvas canvas = draw_cspace_view(data, view);
      save(canvas, c, view_name(view), std::string(view_name(view)) + " view", s);
    }
    write_view(data, c, s);
    if (prediction) save_falsify_figures(c, *task, *prediction, s);
    if (c.metrics && !c.metrics->sticking.is_null()) {
      std::optional<PlotCanvas> canvas;
      try {
        canvas = draw_sticking_figure(c.metrics->sticking, s.label);
      } catch (const std::exception& e) {
        throw InputError(db_.path.string(), key(c, "metrics.sticking"), e.what());
      }
      if (canvas)
        save(*canvas, c, "sticking", "stick fraction", s);
      else
        s.notes.push_back("sticking check: no records to plot");
    }
    return s;
  }

  const nlohmann::json& figures() const { return figures_; }

 private:
  // The configuration's 3-D page (view_page.h) in DIR/view/, beside the assets written once for all. Without
  // three.js the report is still written, with a note saying what to install.
  void write_view(const CSpaceFigureData& figure, const ConfigRow& c, ConfigSection& s) {
    try {
      if (!view_assets_written_) write_view_assets(out_dir_ / kViewDir);
      view_assets_written_ = true;
      ViewInput input;
      input.task = figure.task;
      input.title = figure.title;
      input.motions = figure.motions;
      input.prediction = figure.prediction;
      input.ends = figure.rollouts;
      input.stick_class = stick_class_;
      if (replay_) {
        try {
          input.counterexample = replay_(loaded(c), c);
        } catch (const std::exception& e) {  // a MuJoCo error: the page is still written, without it
          s.notes.push_back(std::string("counterexample not replayed: ") + e.what());
        }
      }
      const std::string page =
          std::string(kViewDir) + "/" + kFigurePrefix + std::to_string(c.config_id) + ".html";
      write_view_page(view_data(input), out_dir_ / page, ".");
      s.view_page = page;
    } catch (const std::runtime_error& e) {
      s.notes.push_back(std::string("no 3-D page: ") + e.what());
    }
  }

  // Per motion of an adversarial search (falsify_figure.h): its figure in the view where its set is widest.
  void save_falsify_figures(const ConfigRow& c, const LoadedTask& task, const PredictedSets& prediction,
                            ConfigSection& s) {
    if (!c.metrics || !c.metrics->falsify.is_object()) return;
    std::vector<FalsifyMotionFigure> figures;
    try {
      figures = falsify_motion_figures(c.metrics->falsify, prediction, c.rollouts, task.task);
    } catch (const std::exception& e) {  // std::invalid_argument, nlohmann::json type errors
      throw InputError(db_.path.string(), key(c, "metrics.falsify"), e.what());
    }
    for (const FalsifyMotionFigure& f : figures) {
      const CSpaceFigureData data{
          &task,   {f.motion}, &f.prediction, &f.random, s.label + ", search of " + f.motion,
          nullptr, &f.search};
      const PlotCanvas canvas = draw_cspace_view(data, f.view);
      save(canvas, c, "falsify_" + std::to_string(f.step),
           "adversarial search, " + f.motion + " (" + view_name(f.view) + " view)", s);
    }
  }

  // Configurations of one task share its YAML text, and building a C-space is the slow part.
  std::shared_ptr<const LoadedTask> loaded(const ConfigRow& c) {
    auto it = tasks_.find(c.task_yaml);
    if (it != tasks_.end()) return it->second;
    const std::string label = db_.path.string() + " " + key(c, "configs.task_yaml");
    auto task = load_task_from_string(c.task_yaml, label);
    tasks_.emplace(c.task_yaml, task);
    return task;
  }

  void add_notes(const ConfigRow& c, const std::optional<PredictedSets>& prediction,
                 std::vector<std::string>& notes) const {
    if (!c.done()) {
      std::set<int> rollouts;
      for (const RolloutRow& r : c.rollouts) rollouts.insert(r.rollout);
      notes.push_back("pending: " + std::to_string(rollouts.size()) + " of " + std::to_string(c.n) +
                      " rollouts recorded so far");
    }
    if (!c.prediction) notes.push_back("no prediction yet");
    if (c.prediction && !c.prediction->reliable && !c.prediction->failure.empty())
      notes.push_back("verifier: " + c.prediction->failure);
    if (prediction) {
      bool any = false;
      for (const PredictedStep& step : prediction->steps) any = any || !step.termination.empty();
      if (!any) notes.push_back("the predicted termination sets are empty");
    }
    if (c.metrics) {
      const MetricsRow& m = *c.metrics;
      if (m.soundness_bug) notes.push_back("SOUNDNESS BUG: the verifier says reliable but a rollout failed");
      if (const std::string replay = counterexample_command(m.counterexample); !replay.empty())
        notes.push_back("counterexample, replay with: " + replay);
      if (const std::string note = falsify_note(c); !note.empty()) notes.push_back(note);
      if (m.sticking.is_object())
        notes.push_back("sticking check: " + std::to_string(m.sticking.value("trials", 0)) + " trials, " +
                        std::to_string(m.sticking.value("disagreements", 0)) + " disagreements");
    }
  }

  void save(const PlotCanvas& canvas, const ConfigRow& c, const std::string& kind, const std::string& caption,
            ConfigSection& s) {
    const std::string file =
        std::string(kFigureDir) + "/" + kFigurePrefix + std::to_string(c.config_id) + "_" + kind + ".png";
    canvas.save(out_dir_ / file);
    s.figures.push_back({file, caption});
    nlohmann::json entry = canvas.layout();
    entry["file"] = file;
    entry["config_id"] = c.config_id;
    entry["kind"] = kind;
    figures_.push_back(entry);
  }

  const ResultsDb& db_;
  std::filesystem::path out_dir_;
  std::map<std::string, std::shared_ptr<const LoadedTask>> tasks_;
  nlohmann::json figures_ = nlohmann::json::array();
  bool view_assets_written_ = false;
  StickClassOf stick_class_;
  CounterexampleReplay replay_;
};

}  // namespace

namespace {

// The runs and, for a result with a 3-D page (`cmt teach --view`), the page relative to the report directory.
std::vector<TeachingRun> read_teaching_runs(const std::vector<std::filesystem::path>& files,
                                            const std::filesystem::path& out_dir) {
  std::vector<TeachingRun> runs;
  for (const std::filesystem::path& f : files) {
    std::ifstream in(f);
    if (!in) throw InputError(f.string(), "", "cannot open the teaching result");
    nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    const bool teach = j.is_object() && j.contains("solved") && j.contains("steps");
    const bool backproject = j.is_object() && j.contains("start_inside") && j.contains("steps");
    if (j.is_discarded() || !(teach || backproject))
      throw InputError(
          f.string(), "",
          "not a `cmt teach --json` or `cmt backproject --json` result (an object with solved or "
          "start_inside, and steps)");
    std::string link;
    if (j.contains("view") && j["view"].is_string())
      link = std::filesystem::relative(std::filesystem::absolute(j["view"].get<std::string>()),
                                       std::filesystem::absolute(out_dir))
                 .generic_string();
    runs.push_back({f.filename().string(), std::move(j), link});
  }
  return runs;
}

// Each file as one JSON object, after `adapt` (may be null), that holds `keys`; otherwise a InputError naming
// the file and the result: `noun` when it cannot be opened, `what` when it is not such a result.
std::vector<nlohmann::json> read_json_results(const std::vector<std::filesystem::path>& files,
                                              const std::vector<const char*>& keys, const std::string& noun,
                                              const std::string& what,
                                              const std::function<void(nlohmann::json&)>& adapt = nullptr) {
  std::vector<nlohmann::json> runs;
  for (const std::filesystem::path& f : files) {
    std::ifstream in(f);
    if (!in) throw InputError(f.string(), "", "cannot open the " + noun);
    nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    if (adapt && j.is_object()) adapt(j);
    const bool has_keys = std::all_of(keys.begin(), keys.end(), [&](const char* k) { return j.contains(k); });
    if (j.is_discarded() || !j.is_object() || !has_keys) {
      std::string list;
      for (std::size_t i = 0; i < keys.size(); ++i) list += (i ? " and " : "") + std::string(keys[i]);
      throw InputError(f.string(), "", "not a " + what + " (an object with " + list + ")");
    }
    runs.push_back(std::move(j));
  }
  return runs;
}

// `cmt edr --json` objects (an object with edr_reliable and slices).
std::vector<nlohmann::json> read_edr_runs(const std::vector<std::filesystem::path>& files) {
  // `cmt validate --edr --json`: the verdict with the check beside it, as `cmt edr --check` writes them.
  const auto unwrap_validate = [](nlohmann::json& j) {
    if (!j.contains("verdict") || !j["verdict"].is_object() || !j.contains("outcomes")) return;
    nlohmann::json verdict = j["verdict"];
    j.erase("verdict");
    if (j.contains("seconds")) verdict["seconds"] = j["seconds"];
    verdict["check"] = std::move(j);
    j = std::move(verdict);
  };
  return read_json_results(files, {"edr_reliable", "slices"}, "EDR result",
                           "`cmt edr --json` or `cmt validate --edr --json` result", unwrap_validate);
}

// `cmt plan --json` objects (an object with found and termination).
std::vector<nlohmann::json> read_plan_runs(const std::vector<std::filesystem::path>& files) {
  return read_json_results(files, {"found", "termination"}, "planner result", "`cmt plan --json` result");
}

// Saves a figure that belongs to no configuration (`file` relative to out_dir), lists it in `refs` with its
// caption and adds its layout to `figures` (figures.json) with `kind`.
void save_report_figure(const PlotCanvas& canvas, const std::filesystem::path& out_dir,
                        const std::string& file, const std::string& caption, const char* kind,
                        std::vector<FigureRef>& refs, nlohmann::json* figures) {
  canvas.save(out_dir / file);
  refs.push_back({file, caption});
  nlohmann::json entry = canvas.layout();
  entry["file"] = file;
  entry["config_id"] = nullptr;  // not a configuration's
  entry["kind"] = kind;
  figures->push_back(entry);
}

// Per EDR result with a physics check, its outcomes against the first model parameter (edr_figure.h) in
// figures/edr_<i>.png; each figure's layout is added to `figures` (figures.json) with kind "edr".
std::vector<FigureRef> write_edr_figures(const std::vector<nlohmann::json>& runs,
                                         const std::filesystem::path& out_dir, nlohmann::json* figures) {
  std::vector<FigureRef> refs;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    auto text = [&](const char* key) {
      return runs[i].contains(key) && runs[i][key].is_string() ? runs[i][key].get<std::string>() : "?";
    };
    const std::string label = text("task") + " / " + text("strategy") + ": EDR outcomes per world";
    const std::optional<PlotCanvas> canvas = draw_edr_figure(runs[i], label);
    if (!canvas) continue;
    const std::string file = std::string(kFigureDir) + "/" + kEdrFigurePrefix + std::to_string(i) + ".png";
    save_report_figure(*canvas, out_dir, file, label, "edr", refs, figures);
  }
  return refs;
}

// Per plan result with §6.3.4's experiment, its success rates (extremes_figure.h) in
// figures/extremes_<i>.png, added to `figures` with kind "extremes".
std::vector<FigureRef> write_extremes_figures(const std::vector<nlohmann::json>& runs,
                                              const std::filesystem::path& out_dir, nlohmann::json* figures) {
  std::vector<FigureRef> refs;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::string task =
        runs[i].contains("task") && runs[i]["task"].is_string() ? runs[i]["task"].get<std::string>() : "?";
    const std::string label = task + ": planned motions commanded at and outside their cpositions (6.3.4)";
    const std::optional<PlotCanvas> canvas = draw_extremes_figure(runs[i], label);
    if (!canvas) continue;
    const std::string file =
        std::string(kFigureDir) + "/" + kExtremesFigurePrefix + std::to_string(i) + ".png";
    save_report_figure(*canvas, out_dir, file, label, "extremes", refs, figures);
  }
  return refs;
}

// A plan's motions as figure layers: each motion's commanded position, its cell's pieces (vertices) and its
// sensed-position boxes.
std::vector<PlannedMotionLayer> planned_layers(const nlohmann::json& run, int dimension) {
  std::vector<PlannedMotionLayer> layers;
  const auto point = [&](const nlohmann::json& p) {
    if (!p.is_array() || p.size() < 2 || p.size() > 3) throw std::invalid_argument("a point is [x, y, z]");
    if (dimension == 2 || p.size() == 2) return Vec3(p[0].get<double>(), 0, p.back().get<double>());
    return Vec3(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
  };
  for (const nlohmann::json& m : run.at("motions")) {
    PlannedMotionLayer layer;
    layer.motion = m.at("name").get<std::string>();
    layer.commanded = point(m.at("commanded"));
    for (const nlohmann::json& piece : m.value("cpositions", nlohmann::json::array())) {
      std::vector<Vec3> vertices;
      for (const nlohmann::json& v : piece.at("vertices")) vertices.push_back(point(v));
      layer.pieces.push_back(std::move(vertices));
    }
    for (const nlohmann::json& box : m.value("spositions", nlohmann::json::array()))
      layer.sensed_positions.push_back({point(box.at("min")), point(box.at("max"))});
    layers.push_back(std::move(layer));
  }
  return layers;
}

// Per plan result with motions and a `task_file` that loads, one figure per view
// (figures/plan_<i>_<view>.png): the task's C-space with each motion's cell outlined, its commanded
// position and its sensed-position set (Buckley's Figs 6.6, 6.8-6.11), and the plan as a graph
// (figures/plan_<i>_graph.png), added to `figures` with kind "plan". A
// plan whose task file does not load gets no figures.
std::vector<FigureRef> write_plan_figures(const std::vector<nlohmann::json>& runs,
                                          const std::filesystem::path& out_dir, nlohmann::json* figures) {
  std::vector<FigureRef> refs;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const nlohmann::json& run = runs[i];
    if (!run.contains("task_file") || !run["task_file"].is_string() || !run.contains("motions") ||
        !run["motions"].is_array() || run["motions"].empty())
      continue;
    std::shared_ptr<const LoadedTask> task;
    std::vector<PlannedMotionLayer> layers;
    try {
      task = load_task(run["task_file"].get<std::string>());
      layers = planned_layers(run, task->task.dimension);
    } catch (const std::exception&) {  // InputError, JSON errors: the table still shows the plan
      continue;
    }
    std::vector<std::string> names;
    for (const PlannedMotionLayer& layer : layers) names.push_back(layer.motion);
    CSpaceFigureData data{task.get(), names, nullptr, nullptr, task->task.name + " planned", &layers};
    for (View view : views_for(task->task)) {
      const PlotCanvas canvas = draw_cspace_view(data, view);
      const std::string file = std::string(kFigureDir) + "/" + kPlanFigurePrefix + std::to_string(i) + "_" +
                               view_name(view) + ".png";
      save_report_figure(
          canvas, out_dir, file,
          task->task.name + ": planned motions' cpositions and commands, " + view_name(view) + " view",
          "plan", refs, figures);
    }
    if (const auto graph = draw_plan_graph(run, task->task.name + " plan: states and motions")) {
      const std::string file =
          std::string(kFigureDir) + "/" + kPlanFigurePrefix + std::to_string(i) + "_graph.png";
      save_report_figure(*graph, out_dir, file,
                         task->task.name + ": the plan as a graph of states and motions", "plan", refs,
                         figures);
    }
  }
  return refs;
}

}  // namespace

ReportSummary write_report(const std::filesystem::path& database, const std::filesystem::path& out_dir,
                           const StickClassOf& stick_class, const CounterexampleReplay& replay,
                           const std::vector<std::filesystem::path>& teach_results,
                           const std::vector<std::filesystem::path>& edr_results,
                           const std::vector<std::filesystem::path>& plan_results) {
  const std::vector<TeachingRun> teaching = read_teaching_runs(teach_results, out_dir);
  const std::vector<nlohmann::json> edr = read_edr_runs(edr_results);
  const std::vector<nlohmann::json> plans = read_plan_runs(plan_results);
  const ResultsDb db = read_results_db(database);
  prepare_output(out_dir);
  ReportBuilder builder(db, out_dir, stick_class, replay);
  std::vector<ConfigSection> sections;
  ReportSummary summary;
  for (const ConfigRow& c : db.configs) {
    sections.push_back(builder.section(c));
    ++(c.done() ? summary.done : summary.pending);
  }
  ReportContent content = build_report_content(db, std::move(sections));
  content.teaching = teaching_table(teaching);
  content.edr = edr_table(edr);
  content.planner = planner_table(plans);
  content.extremes = extremes_table(plans);
  nlohmann::json figures = builder.figures();
  content.edr_figures = write_edr_figures(edr, out_dir, &figures);
  content.extremes_figures = write_extremes_figures(plans, out_dir, &figures);
  content.plan_figures = write_plan_figures(plans, out_dir, &figures);
  summary.configs = static_cast<int>(db.configs.size());
  summary.figures = static_cast<int>(figures.size());
  summary.index = out_dir / "index.html";
  summary.markdown = out_dir / "report.md";
  summary.figures_json = out_dir / "figures.json";
  write_text_file(summary.markdown, render_markdown(content));
  write_text_file(summary.index, render_html(content));
  write_text_file(
      summary.figures_json,
      json_text(nlohmann::json({{"database", database.string()}, {"figures", figures}}), 2) + "\n");
  return summary;
}

}  // namespace cmt::report
