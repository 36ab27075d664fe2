// The predicted termination sets of a strategy, read back from the verifier's JSON (verify_json in
// experiments/cli/verify_command.cc) for drawing: per motion the pieces it may terminate on. Points come back
// in 3-D configuration coordinates (a planar task's [x, z] becomes (x, 0, z), as the C-space lifts it).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "models/task.h"

namespace cmt::report {

struct PredictedPiece {
  int atom = -1;
  std::string name, kind;  // kind: face, edge, vertex or free
  // face: polygon (a planar task's face is a segment), edge: its two ends, vertex: one point.
  std::vector<Vec3> polygon;
  std::vector<std::vector<Vec3>> holes;
  // free (a spring's free-space rest ball): centre and radius.
  Vec3 center = Vec3::Zero();
  double radius = 0;
};

struct PredictedStep {
  std::string motion;
  std::vector<PredictedPiece> termination;
};

struct PredictedSets {
  bool reliable = false;
  std::vector<PredictedStep> steps;
  int failed_step = -1;
};

// A point of a command's JSON ([x, y, z], or [x, z] for a planar task) in 3-D configuration coordinates;
// null coordinates become NaN. Throws std::invalid_argument naming `where` for another shape.
Vec3 json_point(const nlohmann::json& j, int dimension, const std::string& where);
std::vector<Vec3> json_points(const nlohmann::json& j, int dimension, const std::string& where);

// Throws std::invalid_argument naming the JSON path (e.g. "steps[0].termination[2].polygon[1]") when the
// object does not have the verify_json shape. Points with null (non-finite) coordinates are kept as NaN; the
// figures skip them.
PredictedSets parse_predicted_sets(const nlohmann::json& verify_json, int dimension);

}  // namespace cmt::report
