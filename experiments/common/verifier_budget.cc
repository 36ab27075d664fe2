#include "experiments/common/verifier_budget.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
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
  throw std::runtime_error("the worker process ended without a result (" + describe_status(status) + ")");
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

ForkedWork::ForkedWork(const std::function<std::string()>& work) {
  const Child child = fork_child([&work](const std::function<void()>&) { return work(); });
  pid_ = child.pid;
  fd_ = child.fd;
}

ForkedWork::~ForkedWork() {
  if (!ended_) end(true);
}

void ForkedWork::end(bool kill) {
  ::close(fd_);
  if (kill) ::kill(pid_, SIGKILL);
  while (::waitpid(pid_, &status_, 0) < 0 && errno == EINTR) {
  }
  ended_ = true;
}

bool ForkedWork::poll(bool block) {
  char buffer[kReadChunk];
  while (!ended_) {
    pollfd p{fd_, POLLIN, 0};
    const int r = ::poll(&p, 1, block ? -1 : 0);
    if (r < 0 && errno == EINTR) continue;
    if (r == 0) return false;  // nothing to read yet (not blocking)
    const ssize_t n = r < 0 ? -1 : ::read(fd_, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n > 0) {
      data_.append(buffer, static_cast<std::size_t>(n));
      continue;
    }
    if (n < 0) {  // the pipe cannot be read: the result is lost, so the child is stopped
      error_ = std::string("cannot read the worker's pipe: ") + std::strerror(errno);
      end(true);
      break;
    }
    end(false);  // EOF: the child is done (or died)
  }
  return true;
}

std::string ForkedWork::result() const {
  if (!ended_) throw std::logic_error("ForkedWork::result before the child ended");
  if (!error_.empty()) throw std::runtime_error(error_);
  return child_result(data_, status_);
}

}  // namespace cmt
