// Runs one program with its output captured in files, in its own process group, killed (the whole group, with
// SIGKILL) when it outlives a hard time limit. Safe to call from several threads at once.
#pragma once

#include <string>
#include <vector>

namespace cmt::fuzz {

struct ChildLimits {
  double seconds = 10;    // wall-clock limit; then SIGKILL to the process group
  long memory_mb = 4096;  // address-space limit (RLIMIT_AS), so hostile input cannot exhaust the machine
};

struct ChildResult {
  bool killed_on_time = false;  // the hard time limit was reached
  bool exited = false;          // normal exit (exit_code valid)
  int exit_code = -1;
  int signal = 0;  // the terminating signal when not exited
  double seconds = 0;
  std::string out;  // stdout, whole
  std::string err;  // stderr, whole
};

// Runs argv[0] with the arguments; stdout and stderr go to out_path and err_path and are read back.
// Throws std::runtime_error when the process cannot be started.
ChildResult run_child(const std::vector<std::string>& argv, const ChildLimits& limits,
                      const std::string& out_path, const std::string& err_path);

}  // namespace cmt::fuzz
