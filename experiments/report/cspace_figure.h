// Orthographic views of a configuration's C-space in the manner of Buckley's figures: the C-space faces
// (models/cspace.h) in painter's order, the goal and start regions, the predicted termination set of every
// motion (verifier), and the observed motion ends of the rollouts (MuJoCo) on top.
#pragma once

#include <string>
#include <vector>

#include "experiments/report/plot_canvas.h"
#include "experiments/report/predicted_sets.h"
#include "experiments/report/results_db.h"
#include "models/loaded_task.h"

namespace cmt::report {

// front: x right, z up, seen from -y; top: x right, y up, seen from +z; side: y right, z up, seen from +x.
enum class View { kFront, kTop, kSide };
const char* view_name(View view);  // "front", "top", "side"

// The views worth drawing: all three for a 3-D task; the front only for a planar task, whose y extent is the
// artificial extrusion of the C-space (docs/cspace.md "Planar tasks").
std::vector<View> views_for(const Task& task);

// A planned motion's commanded positions (`cmt plan`, docs/planner.md): the convex pieces of its cell (their
// vertices), drawn as the outlines of their projections, the commanded position chosen in it, and its
// sensed-position set P_s (type 2 termination, Buckley Fig 6.9), drawn as box outlines.
struct PlannedMotionLayer {
  std::string motion;
  Vec3 commanded = Vec3::Zero();
  std::vector<std::vector<Vec3>> pieces;       // empty: the motion claims its commanded position alone
  std::vector<AxisBox> sensed_positions = {};  // empty: sticking termination only
};

// The adversarial search's layer of one motion's figure (`cmt falsify`, docs/falsify.md "In sweeps and the
// report"): its rollouts' ends of that motion by phase, the predicted pieces no rollout ended in, and the
// coverage gaps no search covered, each drawn with its motion's coverage radius around it.
struct SearchLayer {
  struct End {
    std::string how;  // "falsify", "coverage", "failure" or "gap"
    Vec3 end = Vec3::Zero();
    bool inside = false;
  };
  struct Gap {
    Vec3 point = Vec3::Zero();
    double radius = 0;
  };
  std::vector<End> ends;
  std::vector<std::vector<Vec3>> unreached_pieces;  // polygon, segment ends or the vertex
  std::vector<Gap> unreached_gaps;
};

struct CSpaceFigureData {
  const LoadedTask* task = nullptr;
  std::vector<std::string> motions;           // the strategy's motion names, in order
  const PredictedSets* prediction = nullptr;  // null: nothing predicted yet
  const std::vector<RolloutRow>* rollouts = nullptr;
  std::string title;  // what the figure is of, e.g. "cube / stick {"friction":0.3}"
  const std::vector<PlannedMotionLayer>* planned = nullptr;  // a plan's motions, in order (colors as motions)
  const SearchLayer* search = nullptr;                       // a one-motion figure's adversarial search
};

// Color of motion i of n: the last motion (whose set is judged against the goal) is highlighted.
cv::Scalar motion_color(int i, int n);

// The view in which the pieces' projections cover the most area, then (without faces, or at equal area)
// the most edge length (the front view of a planar task; ties go to the earlier of front, top, side): a
// one-motion figure shows its set where it is widest.
View widest_view(const Task& task, const std::vector<PredictedPiece>& pieces);

// Draws one view, finished (axes, legend), ready to save.
PlotCanvas draw_cspace_view(const CSpaceFigureData& data, View view, const FigureSize& size = {});

}  // namespace cmt::report
