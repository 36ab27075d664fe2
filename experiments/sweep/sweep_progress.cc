#include "experiments/sweep/sweep_progress.h"

#include <cmath>
#include <cstdio>

namespace cmt {

namespace {

constexpr int kBarWidth = 30;

double since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

std::string format_duration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[64];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ld h %02ld min", s / 3600, (s / 60) % 60);
  else if (s >= 60)
    std::snprintf(buf, sizeof buf, "%ld min %02ld s", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld s", s);
  return buf;
}

SweepProgress::SweepProgress(int total, bool terminal, std::string prefix)
    : total_(total),
      terminal_(terminal),
      prefix_(std::move(prefix)),
      start_(std::chrono::steady_clock::now()) {
  if (terminal_ && total_ > 0) draw();
}

void SweepProgress::draw() const {
  const int filled = total_ > 0 ? kBarWidth * done_ / total_ : kBarWidth;
  const double elapsed = since(start_);
  // ETA from the mean time per unit so far (units of a sweep are alike; unknown before the first one).
  const std::string eta = done_ > 0 ? format_duration(elapsed / done_ * (total_ - done_)) : "?";
  std::fprintf(stderr, "\r%s[%s%s] %d/%d units, %s elapsed, ETA %s   ", prefix_.c_str(),
               std::string(filled, '#').c_str(), std::string(kBarWidth - filled, ' ').c_str(), done_, total_,
               format_duration(elapsed).c_str(), eta.c_str());
  std::fflush(stderr);
}

void SweepProgress::unit_done(const std::string& what, double seconds) {
  ++done_;
  if (terminal_) {
    draw();
    return;
  }
  std::fprintf(stderr, "%sunit %d/%d done in %.1f s: %s\n", prefix_.c_str(), done_, total_, seconds,
               what.c_str());
  std::fflush(stderr);
}

void SweepProgress::finish() {
  if (terminal_ && total_ > 0) std::fprintf(stderr, "\n");
}

}  // namespace cmt
