// Goals that are a vertex (a point at a concave corner) or an edge segment: the termination set of a damper
// that slides into them carries edge and face slivers of rounding size (edge parameters are rounded outward
// by kEdgeParamSlack) beside the goal atom, which must not decide the verdict (the goal check contains what
// lies within kGoalRelativeTolerance x scale of the goal, verifier/reached_set.cc pieces_outside).
#include <gtest/gtest.h>

#include <string>

#include "models/task_loader.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

// A room [0,4] x [0,4] x [0,3] (its walls are the bounds), a damper from the floor's middle.
std::shared_ptr<const LoadedTask> room_task(double mu, const std::string& goal, const std::string& command) {
  return load_task_from_string("name: goal-atoms\nunits: in\nfriction: " + std::to_string(mu) +
                                   "\nuncertainty: {eps_s: 0.05, eps_p: 0.05, theta_v: 0.1, theta_f: 0.05}\n"
                                   "cspace: []\nbounds: {min: [0, 0, 0], max: [4, 4, 3]}\n"
                                   "start: {point: [2, 2, 0]}\ngoal: " +
                                   goal + "\nmotions: {m: {damper: " + command + "}}\nstrategies: {s: [m]}\n",
                               "goal-atoms");
}

// First-order contact (contact_lift 0): the robot slides along the floor into the corner (0,0,0), where the
// three walls hold it. The termination set is the corner plus an interval of the upright edge about 3e-12
// long (the edge parameters' outward rounding): within the goal's tolerance of the corner.
TEST(GoalAtoms, ACornerGoalIsVerifiable) {
  for (const double mu : {0.05, 0.2}) {
    const auto task = room_task(mu, "{point: [0, 0, 0]}", "[-1, -1, -0.5]");
    const VerifyResult r = verify_motions(*task, {"m"});
    EXPECT_TRUE(r.reliable) << "mu " << mu << ": " << r.failure;
  }
}

// The robot slides into the floor's front edge y = 0 and along it (mu .2) toward the corner (4,0,0): the
// termination set holds the edge, the corner, segments of the wall y = 0 on the edge's line and an interval
// of the upright edge x = 4, y = 0 about 3e-12 long.
TEST(GoalAtoms, AnEdgeGoalIsVerifiable) {
  const auto task = room_task(0.2, "{segment: [[0, 0, 0], [4, 0, 0]]}", "[0.2, -1, -0.2]");
  const VerifyResult r = verify_motions(*task, {"m"});
  EXPECT_TRUE(r.reliable) << r.failure;
}

// The tolerance does not hide a real miss: the goal is the other end of the front edge, (4,0,0), which the
// slide toward (0,0,0) never reaches.
TEST(GoalAtoms, AMissedCornerIsStillUnreliable) {
  const auto task = room_task(0.2, "{point: [4, 0, 0]}", "[-1, -1, -0.5]");
  const VerifyResult r = verify_motions(*task, {"m"});
  EXPECT_FALSE(r.reliable);
}

// A goal point or segment inside a face is stored beside the face's regions (as its points and segments),
// and a termination piece there is contained when it lies within the tolerance of them. A damper straight
// down onto the floor (mu .3 > theta_v .1) must stick where it starts: the termination set is the start
// point, which is the goal point (the random-task campaign's task 1142 of seed 3: a point goal on a box top,
// verified unreliable while it must stick). A segment goal through the start holds it too; a goal point
// .01 away does not.
TEST(GoalAtoms, APointOrSegmentGoalInsideAFaceHoldsAStopThere) {
  for (const std::string goal :
       {"{point: [2, 2, 0]}", "{segment: [[1, 2, 0], [3, 2, 0]]}", "{segment: [[2, 2, 0], [2, 3, 0]]}"}) {
    const VerifyResult r = verify_motions(*room_task(0.3, goal, "[0, 0, -1]"), {"m"});
    EXPECT_TRUE(r.reliable) << goal << ": " << r.failure;
  }
  EXPECT_FALSE(verify_motions(*room_task(0.3, "{point: [2.01, 2, 0]}", "[0, 0, -1]"), {"m"}).reliable);
  EXPECT_FALSE(verify_motions(*room_task(0.3, "{segment: [[1, 2.01, 0], [3, 2.01, 0]]}", "[0, 0, -1]"), {"m"})
                   .reliable);
}

}  // namespace
}  // namespace cmt
