// Regression guard for the verifier's termination sets on the built-in 3-D strategies: each stored reference
// (tests/experiments/data/reference_verify/, `cmt verify --json` of the verifier as validated by the main
// job, soundness 1 on every unit) must lie inside the termination set the verifier computes now, step by
// step, up to the goal check's rounding tolerance (kGoalRelativeTolerance x the C-space scale); and the
// verdict must be the same. A faster or restructured verifier may find tighter sets only with a reason: the
// reference then changes in the same commit, with that reason in its message. Planar tasks are left out:
// their JSON points are [x, z] and do not give back the y slab.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/validation/verifier_model.h"
#include "models/loaded_task.h"
#include "verifier/reached_set.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

const std::filesystem::path kReferenceDir =
    std::filesystem::path(CMT_SOURCE_DIR) / "tests/experiments/data/reference_verify";

Vec3 json_point(const nlohmann::json& p) {
  return Vec3(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
}

std::vector<Vec3> json_ring(const nlohmann::json& ring) {
  std::vector<Vec3> out;
  for (const auto& p : ring) out.push_back(json_point(p));
  return out;
}

// The atom pieces of one JSON termination list (the free rest ball is compared apart).
std::vector<ReachedPiece> json_pieces(const nlohmann::json& list) {
  std::vector<ReachedPiece> out;
  for (const auto& j : list) {
    if (j["kind"] == "free") continue;
    ReachedPiece p;
    p.atom = j["atom"].get<int>();
    p.polygon = json_ring(j["polygon"]);
    if (j.contains("holes"))
      for (const auto& h : j["holes"]) p.holes.push_back(json_ring(h));
    out.push_back(std::move(p));
  }
  return out;
}

const nlohmann::json* free_piece(const nlohmann::json& list) {
  for (const auto& j : list)
    if (j["kind"] == "free") return &j;
  return nullptr;
}

std::vector<std::string> reference_files() {
  std::vector<std::string> out;
  for (const auto& entry : std::filesystem::directory_iterator(kReferenceDir))
    if (entry.path().extension() == ".json") out.push_back(entry.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

class ReferenceTermination : public ::testing::TestWithParam<std::string> {};

TEST_P(ReferenceTermination, StoredSetsLieInsideTodaysAndTheVerdictHolds) {
  std::ifstream in(kReferenceDir / GetParam());
  const nlohmann::json ref = nlohmann::json::parse(in);
  const auto task =
      load_task((std::filesystem::path(CMT_SOURCE_DIR) / ref["task_file"].get<std::string>()).string());
  ASSERT_EQ(task->task.dimension, 3);
  const Strategy strategy = task->task.strategy_named(ref["strategy"].get<std::string>());
  const VerifyOptions options = rollout_verify_options(*task);
  const VerifyResult now = verify_strategy(*task, strategy, options);

  const nlohmann::json& old = ref["verify"];
  EXPECT_EQ(now.reliable, old["reliable"].get<bool>());
  ASSERT_EQ(now.steps.size(), old["steps"].size());
  const double tolerance = kGoalRelativeTolerance * task->cspace.scale();
  for (std::size_t i = 0; i < now.steps.size(); ++i) {
    const VerifyStep& step = now.steps[i];
    const nlohmann::json& old_step = old["steps"][i];
    ASSERT_EQ(step.node, old_step["node"].get<int>());
    const ReachedSet stored = ReachedSet::from_pieces(task->cspace, json_pieces(old_step["termination"]));
    for (const ReachedPiece& p : stored.pieces_outside(step.termination, tolerance)) {
      double farthest = 0;
      for (const Vec3& v : p.polygon) farthest = std::max(farthest, step.termination.distance(v));
      ADD_FAILURE() << "step " << i << " (" << step.motion << "): the stored termination on "
                    << task->cspace.atom_name(p.atom) << " (" << p.polygon.size() << " points, area "
                    << p.area << ") is no longer inside: a corner lies " << farthest
                    << " from today's (tolerance " << tolerance << ")";
    }
    if (const nlohmann::json* free = free_piece(old_step["termination"])) {
      ASSERT_TRUE(step.free_termination) << "step " << i << ": the stored rest ball is gone";
      const double reach =
          (json_point((*free)["center"]) - step.free_center).norm() + (*free)["radius"].get<double>();
      EXPECT_LE(reach, step.free_radius + tolerance) << "step " << i << ": the rest ball shrank";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(BuiltIn, ReferenceTermination, ::testing::ValuesIn(reference_files()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return std::filesystem::path(info.param).stem().string();
                         });

// Stored pieces read back to the stored area, and the comparison can fail: a termination set with one face
// piece removed does not contain the stored one.
TEST(ReferenceTerminationCheck, ReadBackAndASmallerSetIsCaught) {
  std::ifstream in(kReferenceDir / "hole_teach.json");
  const nlohmann::json ref = nlohmann::json::parse(in);
  const auto task =
      load_task((std::filesystem::path(CMT_SOURCE_DIR) / ref["task_file"].get<std::string>()).string());
  std::vector<ReachedPiece> pieces = json_pieces(ref["verify"]["steps"][0]["termination"]);
  const ReachedSet whole = ReachedSet::from_pieces(task->cspace, pieces);
  double stored_area = 0;
  for (const auto& j : ref["verify"]["steps"][0]["termination"])
    if (j["kind"] == "face") stored_area += j["area"].get<double>();
  ASSERT_GT(stored_area, 0);
  // Read back whole, rounded onto the region grid: by at most 1.5 cells along every stored boundary in the
  // chart (outer boundaries outward, holes, subtracted, by as much inward), sqrt 3 times that on the face.
  const auto ring_length = [](const std::vector<Vec3>& ring) {
    double length = 0;
    for (std::size_t k = 0; k < ring.size(); ++k) length += (ring[(k + 1) % ring.size()] - ring[k]).norm();
    return length;
  };
  double boundary = 0;
  for (const ReachedPiece& p : pieces) {
    if (task->cspace.atom_kind(p.atom) != AtomKind::kFace) continue;
    boundary += ring_length(p.polygon);
    for (const std::vector<Vec3>& hole : p.holes) boundary += ring_length(hole);
  }
  EXPECT_NEAR(whole.area(), stored_area, 1.5 * std::sqrt(3.0) * region_cell(task->cspace.scale()) * boundary);
  const auto face = std::find_if(pieces.begin(), pieces.end(), [&](const ReachedPiece& p) {
    return task->cspace.atom_kind(p.atom) == AtomKind::kFace;
  });
  ASSERT_NE(face, pieces.end());
  const int atom = face->atom;
  pieces.erase(face);
  const ReachedSet smaller = ReachedSet::from_pieces(task->cspace, pieces);
  const auto outside = whole.pieces_outside(smaller, kGoalRelativeTolerance * task->cspace.scale());
  ASSERT_FALSE(outside.empty());
  EXPECT_EQ(outside.front().atom, atom);
}

}  // namespace
}  // namespace cmt
