// The taught task that `cmt teach -o` writes (experiments/teach/teach_json.h): a taught strategy with a
// sensed dispatch (Buckley Alg 5.1) reads back as the same tree, in 3-D and in a planar task, and its JSON
// form mirrors the task format.
#include "experiments/teach/teach_json.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "controllers/termination.h"
#include "models/task_loader.h"

namespace cmt {
namespace {

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The ridge session (models/sessions/ridge_dispatch.yaml) on `task_file`: right, then down.
Strategy teach_ridge(const std::string& task_file, std::string& written) {
  const std::string text = read(task_file);
  teaching::TeachOptions options;
  options.verify.spring_model = SpringModel::kVelocity;
  options.verify.stop_relative_speed = kStopRelativeSpeed;
  teaching::Session session(load_task_from_string(text, task_file), options);
  session.propose("right");
  session.propose("down");
  EXPECT_TRUE(session.solved());
  if (!session.strategy()) return {};
  written = taught_task_yaml(text, session, *session.strategy(), "taught");
  return *session.strategy();
}

void expect_round_trip(const std::string& task_file, int dimension) {
  std::string written;
  const Strategy taught = teach_ridge(task_file, written);
  ASSERT_TRUE(taught.conditional()) << teaching::strategy_text(taught);
  const Task reread = parse_task_string(written, "written");
  const Strategy* back = reread.find_strategy("taught");
  ASSERT_NE(back, nullptr) << written;
  EXPECT_TRUE(teaching::same_strategy(*back, taught)) << written;

  const nlohmann::json j = strategy_json(taught, dimension);
  ASSERT_EQ(j.size(), 2u) << j;
  EXPECT_EQ(j[0], "down");
  const nlohmann::json& branches = j[1]["branch"];
  ASSERT_EQ(branches.size(), 2u) << j;
  EXPECT_EQ(branches[0]["then"], nlohmann::json::array({"right"}));
  EXPECT_EQ(branches[0]["when"]["position"][0]["box"]["min"].size(), static_cast<std::size_t>(dimension));
  EXPECT_EQ(branches[1]["else"], nlohmann::json::array());
}

TEST(TaughtTaskFile, RidgeDispatchReadsBackAsTheSameTree) {
  expect_round_trip(std::string(CMT_SOURCE_DIR) + "/models/tasks/ridge.yaml", 3);
}

// In a planar task the tests' boxes are written as [x, z] and span the clip slab when read; the verifier
// takes every reading to pass the slab (the sensing error lies in the x-z plane), so the dispatch verifies.
TEST(TaughtTaskFile, PlanarRidgeDispatchReadsBackAsTheSameTree) {
  expect_round_trip(std::string(CMT_SOURCE_DIR) + "/tests/experiments/data/ridge_planar.yaml", 2);
}

TEST(TaughtTaskFile, ChainsStayFlowLists) {
  EXPECT_EQ(strategy_json(Strategy::sequence("s", {"a", "b"}), 3), nlohmann::json::array({"a", "b"}));
  EXPECT_EQ(strategy_json(Strategy{}, 3), nlohmann::json::array());
}

}  // namespace
}  // namespace cmt
