// Progress of a sweep on stderr: a bar redrawn in place with the ETA when stderr is a terminal, else one
// line per finished unit (batch logs, Slurm output files).
#pragma once

#include <chrono>
#include <string>

namespace cmt {

class SweepProgress {
 public:
  // total: units this process will run (the skipped ones excluded); prefix: e.g. "[rank 1] ".
  SweepProgress(int total, bool terminal, std::string prefix);
  // A unit finished after `seconds`; `what` describes it for the log line.
  void unit_done(const std::string& what, double seconds);
  void finish();  // ends the bar's line

 private:
  void draw() const;
  int total_, done_ = 0;
  bool terminal_;
  std::string prefix_;
  std::chrono::steady_clock::time_point start_;
};

// "1 h 02 min", "3 min 05 s", "12 s": a duration for people.
std::string format_duration(double seconds);

}  // namespace cmt
