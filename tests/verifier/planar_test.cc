// Planar tasks (dimension 2; docs/verifier.md "Planar tasks"): the [x, z] scene extruded across the phantom y
// slab |y| <= .5, regions extruded with it, and the forward projection of models/tasks/planar_blocks.yaml
// (the two blocks of Buckley Fig 4.1 in the plane), derived by hand in the task file's comments.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "models/loaded_task.h"
#include "models/task_loader.h"
#include "tests/verifier/test_geometry.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

std::shared_ptr<const LoadedTask> planar_blocks() {
  return load_task(std::filesystem::path(CMT_SOURCE_DIR) / "models/tasks/planar_blocks.yaml");
}

// The 3-D edge over a 2-D vertex (x, z): the line across the slab.
int edge_over(const CSpace& c, double x, double z) {
  for (const Edge& e : c.edges())
    if (std::abs(e.a.x() - x) < 1e-9 && std::abs(e.a.z() - z) < 1e-9 && std::abs(e.b.x() - x) < 1e-9 &&
        std::abs(e.b.z() - z) < 1e-9)
      return e.id;
  return -1;
}

TEST(Planar, RegionsAreExtrudedAcrossTheSlab) {
  const auto task = planar_blocks();
  const CSpace& c = task->cspace;
  EXPECT_TRUE(c.planar());
  EXPECT_EQ(c.faces().size(), 12u);
  EXPECT_EQ(c.edges().size(), 12u);
  EXPECT_TRUE(c.vertices().empty());
  // The start point (3, 3) stands for the segment over it on B's top: every y in the slab, nothing beyond.
  const ReachedSet start = ReachedSet::from_region(*task, task->task.start);
  for (double y : {-kPlanarClipHalfDepth, -0.2, 0.0, 0.3, kPlanarClipHalfDepth})
    EXPECT_NEAR(start.distance(Vec3(3, y, 3)), 0, 1e-12) << y;
  EXPECT_NEAR(start.distance(Vec3(3.5, 0, 3)), 0.5, 1e-12);
  // The goal segment is the band over the gap floor (area = length 3 x slab width 1), with the corner lines.
  const ReachedSet goal = ReachedSet::from_regions(*task, task->task.goal);
  const int gap = test::face_at(c, Vec3::UnitZ(), Vec3(0, 0, 0));
  ASSERT_GE(gap, 0);
  EXPECT_NEAR(goal.face_area(gap), 3.0, 1e-12);
  const int corner = edge_over(c, -1.5, 0);
  ASSERT_GE(corner, 0);
  const auto iv = goal.edge_intervals(corner);
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_EQ(iv[0].t0, 0.0);
  EXPECT_EQ(iv[0].t1, 1.0);
}

TEST(Planar, SlideIsReliableAndEndsInTheCornerDownIsNot) {
  const auto task = planar_blocks();
  const CSpace& c = task->cspace;
  const VerifyResult slide = verify_strategy(*task, *task->task.find_strategy("slide"));
  EXPECT_TRUE(slide.reliable) << slide.failure;
  ASSERT_EQ(slide.steps.size(), 1u);
  // v2 never sticks on a face; the only place it sticks is the concave corner (-1.5, 0), the whole line.
  EXPECT_EQ(slide.steps[0].termination.atoms(), std::vector<int>{edge_over(c, -1.5, 0)});
  EXPECT_EQ(slide.steps[0].termination.area(), 0.0);

  const Strategy& down_strategy = *task->task.find_strategy("down");
  const VerifyResult down =
      verify_strategy(*task, down_strategy, {SpringModel::kViaPoint, test::kRolloutStopRelativeSpeed});
  EXPECT_FALSE(down.reliable);
  // theta_v > phi: v1 may stick on B's top (the start is there) and, sliding off either side, on the floor
  // of the gap and right of B, never on A's top (z = 2 is out of reach from x >= 1.5 - 3 tan(.25) > -1.5).
  const ReachedSet& t = down.steps.at(0).termination;
  const int top_b = test::face_at(c, Vec3::UnitZ(), Vec3(3, 0, 3)),
            top_a = test::face_at(c, Vec3::UnitZ(), Vec3(-3, 0, 2));
  const int right = test::face_at(c, Vec3::UnitZ(), Vec3(5, 0, 0));
  EXPECT_GT(t.face_area(top_b), 0.0);
  EXPECT_GT(t.face_area(right), 0.0);
  EXPECT_EQ(t.face_area(top_a), 0.0);
  bool right_floor_outside = false;
  for (const ReachedPiece& p : down.outside_goal) right_floor_outside |= p.atom == right;
  EXPECT_TRUE(right_floor_outside);
  // With Coulomb sticking only, v1 (theta_v .25 > phi .245 about B's top normal) may slide forever at up to
  // .005 V on B's top; slide's v2 holds in the corner (A's right wall +x, floor +z: every N_i > 0 and
  // friction wins), so slide stays reliable.
  const VerifyResult coulomb = verify_strategy(*task, down_strategy);
  EXPECT_FALSE(coulomb.reliable);
  EXPECT_NE(coulomb.failure.find("may slide forever on"), std::string::npos) << coulomb.failure;
  ASSERT_FALSE(coulomb.steps.empty());
  EXPECT_NE(std::find(coulomb.steps[0].slide_forever.begin(), coulomb.steps[0].slide_forever.end(), top_b),
            coulomb.steps[0].slide_forever.end());
}

}  // namespace
}  // namespace cmt
