// Verifier work in forked child processes: a wall-clock budget for the verifier of a sweep unit
// (docs/sweeps.md "Verifier time budget"), and works run ahead for the planner (ForkedWork). The verifier
// cannot be interrupted from outside (no cancellation points in verifier/), and a thread that is given up on
// keeps a core busy until it finishes and cannot be stopped before the process exits. So the unit runs in a
// forked child process, which the parent kills (SIGKILL) when the verification has not finished within the
// budget; the rollouts then run without a prediction and the unit records "verifier: timed out after B s" as
// its result instead of hanging the sweep.
#pragma once

#include <functional>
#include <string>

namespace cmt {

// Prefix of VerifyResult::failure (and predictions.failure) of a unit whose verifier ran out of budget.
inline constexpr const char* kVerifierTimedOut = "verifier: timed out";

struct ForkedRun {
  bool timed_out = false;  // the child was killed before it reported the end of its budgeted phase
  std::string payload;     // what the child returned (empty when timed out)
};

// Forks. The child runs `work(phase_done)`, calling phase_done() once its budgeted phase (the verification)
// is over, and its return value is sent back through a pipe; it then ends with _exit (no destructors, no
// atexit handlers: it never touches the parent's SQLite connection or stdio buffers). The parent waits at
// most `budget_seconds` for phase_done, then kills the child; after phase_done it waits without limit.
// Requirements: the calling process is single-threaded (the rollout threads are joined after every batch);
// an exception in the child is rethrown in the parent as std::runtime_error with its message, and a child
// that dies otherwise is reported the same way.
ForkedRun run_forked_with_budget(
    double budget_seconds, const std::function<std::string(const std::function<void()>& phase_done)>& work);

// One work running in a forked child (the verifier's checks the planner announces ahead, collected when asked
// for), with the same requirements as above. Destroying a work whose child has not ended kills it (SIGKILL)
// and reaps it.
class ForkedWork {
 public:
  explicit ForkedWork(const std::function<std::string()>& work);
  ~ForkedWork();
  ForkedWork(const ForkedWork&) = delete;
  ForkedWork& operator=(const ForkedWork&) = delete;

  // Reads what the child has written; `block`: until it ends. True once it has ended (and been reaped); a
  // pipe that cannot be read ends it too (the child is killed: its result is lost).
  bool poll(bool block);
  // The child's result once poll() returned true; its exception, its death or a lost result as
  // std::runtime_error.
  std::string result() const;
  int pid() const { return pid_; }

 private:
  void end(bool kill);  // closes the pipe, kills the child if asked, reaps it

  int pid_ = -1, fd_ = -1, status_ = 0;
  bool ended_ = false;
  std::string data_, error_;
};

}  // namespace cmt
