// The task loader and the C-space builder (what `cmt info` runs) in process, on the regression corpus and on
// seeded mutants of the small built-in tasks: every input either loads or is refused with a TaskError. In
// process, so that the ASan+UBSan build (-DCMT_SANITIZE=ON) checks this path without building the whole cmt
// program; the end-to-end checks (exit status, JSON, time) are cmt-fuzz's (fuzz_corpus_*, fuzz_run_*).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "experiments/fuzz/mutator.h"
#include "models/loaded_task.h"
#include "models/task_error.h"

namespace cmt {
namespace {

namespace fs = std::filesystem;

// 1 when the text loads, 0 when it is refused as bad input; anything else escapes and fails the test.
int load_or_refuse(const std::string& text, const std::string& label) {
  try {
    load_task_from_string(text, label);
    return 1;
  } catch (const TaskError& e) {
    EXPECT_FALSE(e.reason().empty()) << label;
    return 0;
  }
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(LoaderFuzz, CorpusLoadsOrIsRefused) {
  int files = 0, loaded = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(CMT_SOURCE_DIR) / "tests/fuzz/corpus")) {
    if (entry.path().extension() != ".yaml") continue;
    ++files;
    loaded += load_or_refuse(read(entry.path()), entry.path().filename().string());
  }
  EXPECT_GE(files, 14);
  EXPECT_GE(loaded, 1);  // hole with perfect sensing is a valid task
}

TEST(LoaderFuzz, MutantsOfTheSmallTasksLoadOrAreRefused) {
  const fs::path tasks = fs::path(CMT_SOURCE_DIR) / "models/tasks";
  std::vector<fuzz::SeedTask> seeds = {fuzz::load_seed((tasks / "two_blocks.yaml").string()),
                                       fuzz::load_seed((tasks / "planar_blocks.yaml").string())};
  for (const auto& entry : fs::directory_iterator(tasks / "soundness"))
    seeds.push_back(fuzz::load_seed(entry.path().string()));
  int loaded = 0;
  constexpr int kInputs = 2000;
  for (int i = 0; i < kInputs; ++i)
    loaded += load_or_refuse(fuzz::make_mutant(seeds, 11, i).text, "mutant " + std::to_string(i));
  RecordProperty("loaded", loaded);
  // Most mutants are bad input, some survive: both paths are exercised.
  EXPECT_GT(loaded, 20);
  EXPECT_LT(loaded, kInputs);
}

}  // namespace
}  // namespace cmt
