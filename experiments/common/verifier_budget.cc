#include "experiments/common/verifier_budget.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <stdexcept>

namespace cmt {

namespace {

// The child's messages: one tag byte, then for kResult/kError the rest of the stream.
constexpr char kPhaseDone = 'V';
constexpr char kResult = 'R';
constexpr char kError = 'E';
constexpr std::size_t kReadChunk = 1 << 16;

void write_all(int fd, const std::string& data) {
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) ::_exit(4);  // the parent is gone: nobody wants the result
    done += static_cast<std::size_t>(n);
  }
}

[[noreturn]] void run_child(int fd, const std::function<std::string(const std::function<void()>&)>& work) {
  int status = 0;
  try {
    const std::string result = work([fd] { write_all(fd, std::string(1, kPhaseDone)); });
    write_all(fd, std::string(1, kResult) + result);
  } catch (const std::exception& e) {
    write_all(fd, std::string(1, kError) + e.what());
    status = 3;
  } catch (...) {
    write_all(fd, std::string(1, kError) + "unknown exception");
    status = 3;
  }
  ::close(fd);
  ::_exit(status);  // no destructors or atexit handlers: the parent's state stays the parent's
}

std::string describe_status(int status) {
  if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
  if (WIFEXITED(status)) return "exit status " + std::to_string(WEXITSTATUS(status));
  return "status " + std::to_string(status);
}

// A forked child running `work`, with the read end of its pipe.
struct Child {
  pid_t pid = -1;
  int fd = -1;
};

Child fork_child(const std::function<std::string(const std::function<void()>&)>& work) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("verifier budget: pipe failed");
  // Buffered output would otherwise be written twice, once by each process.
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error("verifier budget: fork failed");
  }
  if (pid == 0) {
    ::close(fds[0]);
    run_child(fds[1], work);
  }
  ::close(fds[1]);
  return {pid, fds[0]};
}

// The child's result from everything it wrote, once it has been reaped with `status`; throws its error.
std::string child_result(const std::string& data, int status) {
  std::size_t at = 0;
  if (at < data.size() && data[at] == kPhaseDone) ++at;
  if (at < data.size() && data[at] == kResult && WIFEXITED(status) && WEXITSTATUS(status) == 0)
    return data.substr(at + 1);
  if (at < data.size() && data[at] == kError) throw std::runtime_error(data.substr(at + 1));
  throw std::runtime_error("the unit's worker process ended without a result (" + describe_status(status) +
                           ")");
}

}  // namespace

ForkedRun run_forked_with_budget(double budget_seconds,
                                 const std::function<std::string(const std::function<void()>&)>& work) {
  const auto [pid, read_fd] = fork_child(work);
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(std::max(0.0, budget_seconds));
  std::string data;
  bool timed_out = false;
  char buffer[kReadChunk];
  for (;;) {
    if (data.empty()) {  // still in the budgeted phase: wait for the first byte until the deadline
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0) {
        timed_out = true;
        break;
      }
      pollfd p{read_fd, POLLIN, 0};
      const int r = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
      if (r == 0 || (r < 0 && errno == EINTR)) continue;
    }
    const ssize_t n = ::read(read_fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // EOF: the child is done (or died)
    data.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(read_fd);
  if (timed_out) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (timed_out) return ForkedRun{true, ""};
  return ForkedRun{false, child_result(data, status)};
}

std::vector<std::string> run_forked_batch(const std::vector<std::function<std::string()>>& works,
                                          int parallel) {
  std::vector<std::string> out(works.size());
  if (parallel <= 1 || works.size() <= 1) {
    for (std::size_t i = 0; i < works.size(); ++i) out[i] = works[i]();
    return out;
  }
  struct Running {
    Child child;
    std::size_t index = 0;
    std::string data;
  };
  std::vector<Running> running;
  std::size_t next = 0;
  std::string first_error;
  char buffer[kReadChunk];
  while (next < works.size() || !running.empty()) {
    while (static_cast<int>(running.size()) < parallel && next < works.size()) {
      const std::size_t i = next++;
      running.push_back(
          {fork_child([&works, i](const std::function<void()>&) { return works[i](); }), i, ""});
    }
    std::vector<pollfd> polls;
    for (const Running& r : running) polls.push_back({r.child.fd, POLLIN, 0});
    if (::poll(polls.data(), polls.size(), -1) < 0) continue;  // EINTR: poll again
    for (std::size_t k = running.size(); k-- > 0;) {
      if (polls[k].revents == 0) continue;
      const ssize_t n = ::read(running[k].child.fd, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n > 0) {
        running[k].data.append(buffer, static_cast<std::size_t>(n));
        continue;
      }
      ::close(running[k].child.fd);  // EOF: the child is done (or died)
      int status = 0;
      while (::waitpid(running[k].child.pid, &status, 0) < 0 && errno == EINTR) {
      }
      try {
        out[running[k].index] = child_result(running[k].data, status);
      } catch (const std::exception& e) {
        if (first_error.empty()) first_error = e.what();
      }
      running.erase(running.begin() + static_cast<std::ptrdiff_t>(k));
    }
  }
  if (!first_error.empty()) throw std::runtime_error(first_error);
  return out;
}

}  // namespace cmt
