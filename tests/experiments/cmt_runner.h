// Runs the built cmt program for end-to-end tests: its exit status and stdout (stderr is discarded), or its
// stderr.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace cmt::test {

struct Result {
  int status = -1;
  std::string out;
};

// Runs a shell command line and collects what it writes to the pipe.
inline Result run_shell(const std::string& cmd) {
  Result r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), pipe)) r.out += buf.data();
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

inline Result run(const std::string& args) {
  return run_shell(std::string(CMT_BINARY) + " " + args + " 2>/dev/null");
}

// Its exit status and stderr (stdout is discarded).
inline Result run_stderr(const std::string& args) {
  return run_shell(std::string(CMT_BINARY) + " " + args + " 2>&1 >/dev/null");
}

// A built-in task file.
inline std::string task(const std::string& name) {
  return std::string(CMT_SOURCE_DIR) + "/models/tasks/" + name + ".yaml";
}

}  // namespace cmt::test
