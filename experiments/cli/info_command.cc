#include "experiments/cli/info_command.h"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <sstream>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"

namespace cmt {
namespace {

// Planar tasks report atoms in the plane: a face is the segment [x, z] it extrudes, an edge the corner point.
nlohmann::json atom_points(const LoadedTask& task, const std::vector<Vec3>& pts) {
  const int dim = task.task.dimension;
  nlohmann::json out = nlohmann::json::array();
  std::vector<Vec3> seen;
  for (const Vec3& p : pts) {
    Vec3 q = p;
    if (dim == 2) q.y() = 0;
    if (std::find(seen.begin(), seen.end(), q) != seen.end()) continue;
    seen.push_back(q);
    out.push_back(point_json(q, dim));
  }
  return out;
}

}  // namespace

nlohmann::json info_json(const LoadedTask& task, bool with_atoms, double build_seconds) {
  const CSpace& c = task.cspace;
  const Task& t = task.task;
  int concave = 0, convex = 0, flat = 0, non_manifold = 0;
  for (const Edge& e : c.edges()) {
    concave += e.shape == EdgeShape::kConcave;
    convex += e.shape == EdgeShape::kConvex;
    flat += e.shape == EdgeShape::kFlat;
    non_manifold += e.shape == EdgeShape::kNonManifold;
  }
  nlohmann::json j = {
      {"task", t.name},
      {"file", t.source_file},
      {"units", unit_name(t.units)},
      {"dimension", t.dimension},
      {"form", t.physical() ? "physical" : "cspace"},
      {"c_obstacles", c.obstacles().size()},
      {"faces", c.faces().size()},
      {"edges", c.edges().size()},
      {"vertices", c.vertices().size()},
      {"atoms", c.atom_count()},
      {"edge_shapes",
       {{"concave", concave}, {"convex", convex}, {"flat", flat}, {"non_manifold", non_manifold}}},
      {"motions", nlohmann::json::array()},
      {"strategies", nlohmann::json::array()},
      {"seconds", build_seconds},
  };
  for (const Motion& m : t.motions) j["motions"].push_back(m.name);
  for (const Strategy& s : t.strategies) j["strategies"].push_back(s.name);
  if (!with_atoms) return j;
  nlohmann::json list = nlohmann::json::array();
  for (const Face& f : c.faces()) {
    Vec3 n = f.normal;
    list.push_back({{"id", f.id},
                    {"name", c.atom_name(f.id)},
                    {"kind", "face"},
                    {"points", atom_points(task, f.polygon)},
                    {"normal", point_json(n, t.dimension)},
                    {"friction", f.friction},
                    {"edges", f.edges},
                    {"vertices", f.vertices}});
  }
  for (const Edge& e : c.edges()) {
    list.push_back({{"id", e.id},
                    {"name", c.atom_name(e.id)},
                    {"kind", "edge"},
                    {"points", atom_points(task, {e.a, e.b})},
                    {"shape", edge_shape_name(e.shape)},
                    {"faces", e.faces}});
  }
  for (const Vertex& v : c.vertices()) {
    list.push_back({{"id", v.id},
                    {"name", c.atom_name(v.id)},
                    {"kind", "vertex"},
                    {"points", atom_points(task, {v.point})},
                    {"faces", v.faces},
                    {"edges", v.edges}});
  }
  j["atom_list"] = list;
  return j;
}

std::string info_text(const LoadedTask& task) {
  const CSpace& c = task.cspace;
  std::ostringstream s;
  s << task.task.name << " (" << task.task.source_file << ", units " << unit_name(task.task.units) << ")\n"
    << "  C-obstacles: " << c.obstacles().size() << "\n"
    << "  atoms: " << c.atom_count() << " = " << c.faces().size() << " faces + " << c.edges().size()
    << " edges + " << c.vertices().size() << " vertices\n";
  return s.str();
}

void add_info_command(CLI::App& app, CommandState& state) {
  struct Options {
    std::string task;
    bool atoms = false;
  };
  auto options = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("info", "Configuration-space atoms of a task (faces, edges, vertices)");
  cmd->add_option("TASK", options->task, "task YAML file")->required();
  cmd->add_flag("--atoms", options->atoms, "also list every atom's geometry");
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([options, &state] {
    const auto start = std::chrono::steady_clock::now();
    const auto task = load_task(options->task);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (state.json)
      print_json(info_json(*task, options->atoms, seconds));
    else
      std::cout << info_text(*task);
    state.exit_status = kExitSuccess;
  });
}

}  // namespace cmt
