#include "experiments/report/cspace_figure.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "experiments/report/plot_style.h"

namespace cmt::report {
namespace {

// A face counts as seen edge-on when its normal is this close to perpendicular to the viewing direction
// (C-space normals are unit vectors rounded from exact values; 1e-9 is far above that rounding).
constexpr double kEdgeOnCosine = 1e-9;
// A projected polygon with less area than this many square pixels is drawn as a thick line instead.
constexpr double kDegeneratePixelArea = 1.0;
constexpr double kMarginFraction = 0.06;  // empty border around the scene, of its extent
constexpr int kEdgePieceThickness = 5;    // px: predicted edges and planar faces (segments)
constexpr int kVertexPieceRadius = 6;     // px: predicted vertices
constexpr double kPieceLineShade = 0.75;  // predicted edges and vertices: this fraction of the face color
constexpr int kInsideDotRadius = 3;       // px: observed ends inside the prediction
constexpr int kOutsideCrossHalf = 6;      // px: observed ends outside it
constexpr int kOutsideCrossThickness = 2;
constexpr int kPlannedCellThickness = 2;   // px: outlines of a planned motion's cell
constexpr int kPlannedMarkerRadius = 7;    // px: a planned motion's commanded position
constexpr int kSearchEndRadius = 4;        // px: the adversarial search's ends
constexpr int kUnreachedThickness = 3;     // px: outlines of predicted pieces no rollout reached
constexpr int kUnreachedVertexRadius = 9;  // px: the same for a vertex

struct ViewSpec {
  int u, v;            // coordinate indices shown right and up
  Vec3 toward_viewer;  // unit vector from the scene to the viewer
  const char* axes;    // for the title
};

ViewSpec spec(View view) {
  switch (view) {
    case View::kFront:
      return {0, 2, Vec3(0, -1, 0), "x-z"};
    case View::kTop:
      return {0, 1, Vec3(0, 0, 1), "x-y"};
    case View::kSide:
      return {1, 2, Vec3(1, 0, 0), "y-z"};
  }
  return {0, 2, Vec3(0, -1, 0), "x-z"};
}

const char* axis_name(int i) { return i == 0 ? "x" : i == 1 ? "y" : "z"; }

DataPoint project(const Vec3& p, const ViewSpec& s) { return {p[s.u], p[s.v]}; }

std::vector<DataPoint> project(const std::vector<Vec3>& pts, const ViewSpec& s) {
  std::vector<DataPoint> out;
  out.reserve(pts.size());
  for (const Vec3& p : pts) out.push_back(project(p, s));
  return out;
}

Vec3 centroid(const std::vector<Vec3>& pts) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : pts) c += p;
  return pts.empty() ? c : Vec3(c / static_cast<double>(pts.size()));
}

// Area of the projection in square pixels (shoelace), to tell a polygon from a sliver seen edge-on.
double pixel_area(const PlotCanvas& canvas, const std::vector<DataPoint>& pts) {
  double twice = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const DataPoint a = canvas.to_image(pts[i]), b = canvas.to_image(pts[(i + 1) % pts.size()]);
    twice += a.x * b.y - b.x * a.y;
  }
  return std::isfinite(twice) ? 0.5 * std::abs(twice) : 0.0;
}

// Bounding box of everything drawn, in view coordinates.
struct Box {
  double umin = std::numeric_limits<double>::infinity(), umax = -umin, vmin = umin, vmax = -umin;
  void add(const DataPoint& p) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
    umin = std::min(umin, p.x), umax = std::max(umax, p.x);
    vmin = std::min(vmin, p.y), vmax = std::max(vmax, p.y);
  }
};

void set_view_ranges(PlotCanvas& canvas, const CSpaceFigureData& d, const ViewSpec& s) {
  Box box;
  for (const Face& f : d.task->cspace.faces())
    for (const Vec3& p : f.polygon) box.add(project(p, s));
  for (const Vec3& p : d.task->task.start.points) box.add(project(p, s));
  for (const Region& g : d.task->task.goal)
    for (const Vec3& p : g.points) box.add(project(p, s));
  if (d.prediction)
    for (const PredictedStep& step : d.prediction->steps)
      for (const PredictedPiece& piece : step.termination) {
        for (const Vec3& p : piece.polygon) box.add(project(p, s));
        if (piece.kind == "free" && std::isfinite(piece.radius)) {
          const DataPoint c = project(piece.center, s);
          box.add(c - DataPoint(piece.radius, piece.radius));
          box.add(c + DataPoint(piece.radius, piece.radius));
        }
      }
  if (d.planned)  // the commanded positions, not the cells (which reach the planner's domain box)
    for (const PlannedMotionLayer& m : *d.planned) box.add(project(m.commanded, s));
  // Rollout ends are not included: one that flew off would shrink the scene to a dot; it is clipped instead.
  if (!(box.umin <= box.umax)) box = Box{-1, 1, -1, 1};
  const double margin = kMarginFraction * std::max({box.umax - box.umin, box.vmax - box.vmin, 1e-9});
  canvas.set_ranges({box.umin - margin, box.umax + margin}, {box.vmin - margin, box.vmax + margin}, true);
}

void draw_faces(PlotCanvas& canvas, const CSpace& cspace, const ViewSpec& s) {
  // Painter's order: farthest from the viewer first, so nearer faces cover them.
  std::vector<const Face*> faces;
  for (const Face& f : cspace.faces()) faces.push_back(&f);
  std::stable_sort(faces.begin(), faces.end(), [&](const Face* a, const Face* b) {
    return centroid(a->polygon).dot(s.toward_viewer) < centroid(b->polygon).dot(s.toward_viewer);
  });
  for (const Face* f : faces) {
    const std::vector<DataPoint> poly = project(f->polygon, s);
    const double facing = f->normal.dot(s.toward_viewer);
    if (facing > kEdgeOnCosine) {
      canvas.fill_polygon(poly, {}, kFaceFill);
      canvas.polyline(poly, true, kFaceOutline, 1);
    } else if (facing >= -kEdgeOnCosine) {
      canvas.polyline(poly, true, kFaceOutline, 1);  // edge-on: its projection is a segment
    } else {
      canvas.polyline(poly, true, kBackFaceLine, 1);  // seen from the obstacle side: outline only
    }
  }
}

// A region (start/goal) or predicted piece given by points: polygon, segment or point. Segments and points
// are drawn in `line` (a darker shade for predicted edges and vertices, so they stand out on the faces they
// bound).
void draw_points_shape(PlotCanvas& canvas, const std::vector<DataPoint>& pts,
                       const std::vector<std::vector<DataPoint>>& holes, const cv::Scalar& fill,
                       const cv::Scalar& outline, int outline_thickness, const cv::Scalar& line) {
  if (pts.size() >= 3 && pixel_area(canvas, pts) >= kDegeneratePixelArea) {
    canvas.fill_polygon(pts, holes, fill);
    canvas.polyline(pts, true, outline, outline_thickness);
    for (const auto& h : holes) canvas.polyline(h, true, outline, 1);
  } else if (pts.size() >= 3) {
    canvas.polyline(pts, false, fill, kEdgePieceThickness);  // a face seen edge-on keeps its face color
  } else if (pts.size() == 2) {
    canvas.polyline(pts, false, line, kEdgePieceThickness);
  } else if (pts.size() == 1) {
    canvas.dot(pts[0], kVertexPieceRadius, line);
  }
}

// Lower-dimensional pieces last (faces, then edges, then vertices), each group farthest first, so that
// nearer faces cover farther ones and no edge or vertex is hidden under a face.
std::vector<const PredictedPiece*> drawing_order(const std::vector<PredictedPiece>& pieces,
                                                 const ViewSpec& s) {
  std::vector<const PredictedPiece*> order;
  for (const PredictedPiece& p : pieces) order.push_back(&p);
  auto rank = [](const PredictedPiece* p) {
    return p->kind == "free" ? 0 : p->polygon.size() >= 3 ? 1 : p->polygon.size() == 2 ? 2 : 3;
  };
  auto depth = [&](const PredictedPiece* p) {
    return (p->kind == "free" ? p->center : centroid(p->polygon)).dot(s.toward_viewer);
  };
  std::stable_sort(order.begin(), order.end(), [&](const PredictedPiece* a, const PredictedPiece* b) {
    if (rank(a) != rank(b)) return rank(a) < rank(b);
    return depth(a) < depth(b);
  });
  return order;
}

void draw_prediction(PlotCanvas& canvas, const PredictedSets& prediction, const ViewSpec& s) {
  const int n = static_cast<int>(prediction.steps.size());
  for (int i = 0; i < n; ++i) {
    const cv::Scalar color = motion_color(i, n);
    const int outline = i == n - 1 ? 2 : 1;  // the last motion's set stands out
    for (const PredictedPiece* piece : drawing_order(prediction.steps[i].termination, s)) {
      if (piece->kind == "free") {
        canvas.circle(project(piece->center, s), piece->radius, color, true);
        canvas.circle(project(piece->center, s), piece->radius, darker(color), false, outline);
        continue;
      }
      std::vector<std::vector<DataPoint>> holes;
      for (const auto& h : piece->holes) holes.push_back(project(h, s));
      draw_points_shape(canvas, project(piece->polygon, s), holes, color, darker(color), outline,
                        darker(color, kPieceLineShade));
    }
  }
}

void draw_region_outline(PlotCanvas& canvas, const Region& r, const ViewSpec& s, const cv::Scalar& color) {
  const std::vector<DataPoint> pts = project(r.points, s);
  if (pts.size() == 1)
    canvas.dot(pts[0], kVertexPieceRadius - 2, color);
  else
    canvas.polyline(pts, r.kind == Region::Kind::kPolygon, color, 2);
}

}  // namespace

const char* view_name(View view) {
  switch (view) {
    case View::kFront:
      return "front";
    case View::kTop:
      return "top";
    case View::kSide:
      return "side";
  }
  return "front";
}

std::vector<View> views_for(const Task& task) {
  if (task.dimension == 2) return {View::kFront};
  return {View::kFront, View::kTop, View::kSide};
}

cv::Scalar motion_color(int i, int n) {
  if (i == n - 1) return kLastMotionColor;
  constexpr int kCycle = sizeof(kMotionColors) / sizeof(kMotionColors[0]);
  return kMotionColors[i % kCycle];
}

namespace {

// A planned motion's cell as the outline of each piece's projection (the convex hull of its projected
// vertices; cells are clipped to the plot, they may reach far beyond the scene), and its commanded position.
void draw_planned(PlotCanvas& canvas, const std::vector<PlannedMotionLayer>& planned, const ViewSpec& s) {
  const int n = static_cast<int>(planned.size());
  for (int i = 0; i < n; ++i) {
    const cv::Scalar color = darker(motion_color(i, n), kPieceLineShade);
    for (const std::vector<Vec3>& piece : planned[static_cast<std::size_t>(i)].pieces) {
      std::vector<cv::Point2f> projected, hull;
      for (const Vec3& v : piece) {
        const DataPoint p = project(v, s);
        projected.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
      }
      if (projected.size() < 2) continue;
      cv::convexHull(projected, hull);
      std::vector<DataPoint> outline(hull.begin(), hull.end());
      canvas.polyline(outline, true, color, kPlannedCellThickness);
    }
    canvas.marker(project(planned[static_cast<std::size_t>(i)].commanded, s), LegendMarker::kDiamond,
                  kPlannedMarkerRadius, color);
    for (const AxisBox& b : planned[static_cast<std::size_t>(i)].sensed_positions) {
      const DataPoint lo = project(b.min, s), hi = project(b.max, s);
      canvas.polyline({lo, {hi.x, lo.y}, hi, {lo.x, hi.y}}, true, kSensedPositionsLine,
                      kPlannedCellThickness);
    }
  }
}

// The search phases in drawing order, with their markers (docs/falsify.md): the random ends are the
// figure's rollouts.
struct SearchPhase {
  const char* how;
  const char* label;
  LegendMarker marker;
  cv::Scalar color;
};
const SearchPhase kSearchPhases[] = {
    {"falsify", "falsification search end", LegendMarker::kTriangle, rgb(0x0072b2)},
    {"coverage", "coverage search end", LegendMarker::kDiamond, rgb(0xcc79a7)},
    {"failure", "failure search end", LegendMarker::kTriangle, rgb(0xd55e00)},
    {"gap", "gap search end", LegendMarker::kSquare, rgb(0x56b4e9)},
};

// Unreached pieces and gaps first (outlines under the ends), then the ends inside by phase, then the ends
// outside as red crosses. Returns which legend rows apply: per phase, any outside, any unreached.
struct SearchDrawn {
  bool phase[std::size(kSearchPhases)] = {};
  bool outside = false, pieces = false, gaps = false;
};
SearchDrawn draw_search(PlotCanvas& canvas, const SearchLayer& search, const ViewSpec& s) {
  SearchDrawn drawn;
  for (const std::vector<Vec3>& piece : search.unreached_pieces) {
    const std::vector<DataPoint> pts = project(piece, s);
    if (pts.size() == 1)
      canvas.ring(pts[0], kUnreachedVertexRadius, kInk, kUnreachedThickness);
    else if (!pts.empty())
      canvas.polyline(pts, pts.size() >= 3, kInk, kUnreachedThickness);
    drawn.pieces = drawn.pieces || !pts.empty();
  }
  for (const SearchLayer::Gap& g : search.unreached_gaps) {
    canvas.circle(project(g.point, s), g.radius, kInk, false, 1);
    canvas.dot(project(g.point, s), 2, kInk);
    drawn.gaps = true;
  }
  for (std::size_t k = 0; k < std::size(kSearchPhases); ++k)
    for (const SearchLayer::End& e : search.ends)
      if (e.inside && e.how == kSearchPhases[k].how) {
        canvas.marker(project(e.end, s), kSearchPhases[k].marker, kSearchEndRadius, kSearchPhases[k].color);
        drawn.phase[k] = true;
      }
  for (const SearchLayer::End& e : search.ends)
    if (!e.inside) {
      canvas.cross(project(e.end, s), kOutsideCrossHalf, kOutsideRed, kOutsideCrossThickness);
      drawn.outside = true;
    }
  return drawn;
}

void add_search_legend(PlotCanvas& canvas, const SearchDrawn& drawn) {
  for (std::size_t k = 0; k < std::size(kSearchPhases); ++k)
    if (drawn.phase[k])
      canvas.add_legend({kSearchPhases[k].label, kSearchPhases[k].color, kSearchPhases[k].marker});
  if (drawn.pieces) canvas.add_legend({"piece no rollout reached", kInk, LegendMarker::kLine});
  if (drawn.gaps) canvas.add_legend({"gap not covered (ring)", kInk, LegendMarker::kOutline});
}

double projected_area(const std::vector<Vec3>& polygon, const ViewSpec& s) {
  double twice = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const DataPoint a = project(polygon[i], s), b = project(polygon[(i + 1) % polygon.size()], s);
    twice += a.x * b.y - b.x * a.y;
  }
  return std::isfinite(twice) ? 0.5 * std::abs(twice) : 0.0;
}

double projected_length(const Vec3& a, const Vec3& b, const ViewSpec& s) {
  const double length = cv::norm(project(b, s) - project(a, s));
  return std::isfinite(length) ? length : 0.0;
}

}  // namespace

View widest_view(const Task& task, const std::vector<PredictedPiece>& pieces) {
  View best = View::kFront;
  std::pair<double, double> best_size(-1, -1);
  for (View view : views_for(task)) {
    std::pair<double, double> size(0, 0);  // faces' area, then edges' length
    for (const PredictedPiece& p : pieces)
      if (p.polygon.size() >= 3)
        size.first += projected_area(p.polygon, spec(view));
      else if (p.polygon.size() == 2)
        size.second += projected_length(p.polygon[0], p.polygon[1], spec(view));
    if (size > best_size) best = view, best_size = size;
  }
  return best;
}

PlotCanvas draw_cspace_view(const CSpaceFigureData& d, View view, const FigureSize& size) {
  const ViewSpec s = spec(view);
  const std::string unit = unit_name(d.task->task.units);
  PlotCanvas canvas(size, d.title + ": " + view_name(view) + " view (" + s.axes + ")",
                    std::string(axis_name(s.u)) + " (" + unit + ")",
                    std::string(axis_name(s.v)) + " (" + unit + ")");
  set_view_ranges(canvas, d, s);  // no grid: the faces' outlines are the reference lines, as in the thesis
  draw_faces(canvas, d.task->cspace, s);

  for (const Region& g : d.task->task.goal)
    draw_points_shape(canvas, project(g.points, s), {}, kGoalFill, kGoalLine, 1, kGoalLine);
  if (d.prediction) draw_prediction(canvas, *d.prediction, s);
  for (const Region& g : d.task->task.goal) draw_region_outline(canvas, g, s, kGoalLine);
  draw_region_outline(canvas, d.task->task.start, s, kStartColor);
  if (d.planned) draw_planned(canvas, *d.planned, s);

  // The motions: the prediction's steps when there is one, else the strategy's.
  std::vector<std::string> motions = d.motions;
  if (d.prediction && !d.prediction->steps.empty()) {
    motions.clear();
    for (const PredictedStep& step : d.prediction->steps) motions.push_back(step.motion);
  }
  const int n = static_cast<int>(motions.size());

  bool any_inside = false, any_outside = false;
  if (d.rollouts) {
    // Unstable rollouts are left out: soundness is judged on stable ones only (docs/validation.md).
    for (const RolloutRow& r : *d.rollouts)
      if (!r.unstable && r.inside) {
        canvas.dot(project(r.end, s), kInsideDotRadius, darker(motion_color(r.motion, n)));
        any_inside = true;
      }
  }
  SearchDrawn search_drawn;
  if (d.search) search_drawn = draw_search(canvas, *d.search, s);
  if (d.rollouts)
    for (const RolloutRow& r : *d.rollouts)  // crosses last: the outliers must not be hidden
      if (!r.unstable && !r.inside) {
        canvas.cross(project(r.end, s), kOutsideCrossHalf, kOutsideRed, kOutsideCrossThickness);
        any_outside = true;
      }

  canvas.add_legend({"C-space face", kFaceFill, LegendMarker::kFill});
  canvas.add_legend({"C-space face, back side", kBackFaceLine, LegendMarker::kOutline});
  canvas.add_legend({"goal region", kGoalFill, LegendMarker::kFill});
  canvas.add_legend({"start region", kStartColor, LegendMarker::kLine});
  if (d.prediction)  // n is its number of steps when it has any
    for (int i = 0; i < static_cast<int>(d.prediction->steps.size()); ++i) {
      // A one-motion figure of a search shows one step of the strategy, not necessarily its last.
      canvas.add_legend({"predicted end, " + motions[i] + (i == n - 1 && !d.search ? " (last)" : ""),
                         motion_color(i, n), LegendMarker::kFill});
      const auto& pieces = d.prediction->steps[i].termination;
      if (std::any_of(pieces.begin(), pieces.end(),
                      [](const PredictedPiece& p) { return p.kind != "free" && p.polygon.size() <= 2; }))
        canvas.add_legend({"predicted edge/vertex, " + motions[i],
                           darker(motion_color(i, n), kPieceLineShade), LegendMarker::kLine});
    }
  if (d.search && any_inside)
    canvas.add_legend({"random end in set", darker(motion_color(0, n)), LegendMarker::kDot});
  else if (any_inside)
    for (int i = 0; i < n; ++i)
      canvas.add_legend(
          {"observed end in set, " + motions[i], darker(motion_color(i, n)), LegendMarker::kDot});
  if (d.search) add_search_legend(canvas, search_drawn);
  if (any_outside || search_drawn.outside)
    canvas.add_legend({"observed end outside set", kOutsideRed, LegendMarker::kCross});
  if (d.planned)
    for (std::size_t i = 0; i < d.planned->size(); ++i) {
      const PlannedMotionLayer& m = (*d.planned)[i];
      const cv::Scalar color =
          darker(motion_color(static_cast<int>(i), static_cast<int>(d.planned->size())), kPieceLineShade);
      if (!m.pieces.empty()) canvas.add_legend({"cell of " + m.motion, color, LegendMarker::kLine});
      canvas.add_legend(
          {"command, " + m.motion + (m.pieces.empty() ? " (no cell)" : ""), color, LegendMarker::kDiamond});
      if (!m.sensed_positions.empty())
        canvas.add_legend({"sensed positions P_s, " + m.motion, kSensedPositionsLine, LegendMarker::kLine});
    }
  canvas.finish();
  return canvas;
}

}  // namespace cmt::report
