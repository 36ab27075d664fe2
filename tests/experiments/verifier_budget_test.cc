// The verifier time budget (experiments/common/verifier_budget.h): a forked child that reports the end of its
// budgeted phase in time returns its result, one that does not is killed at the deadline, a child's
// exception reaches the parent with its message; and a unit record survives the trip through the pipe bit
// for bit (experiments/results/unit_record_json.h), infinities and NULLs included.
#include "experiments/common/verifier_budget.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <limits>
#include <thread>

#include "experiments/results/unit_record_json.h"
#include "models/input_error.h"

namespace cmt {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

TEST(VerifierBudget, ChildThatFinishesItsPhaseInTimeReturnsItsResult) {
  // The phase ends at once; the work after it (0.5 s) is not limited by the 0.1 s budget.
  const ForkedRun run = run_forked_with_budget(0.1, [](const std::function<void()>& phase_done) {
    phase_done();
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    return std::string(100000, 'x') + "end";  // more than a pipe buffer
  });
  EXPECT_FALSE(run.timed_out);
  EXPECT_EQ(run.payload.size(), 100003u);
  EXPECT_EQ(run.payload.substr(100000), "end");
}

TEST(VerifierBudget, ChildThatOverrunsIsKilledAtTheDeadline) {
  const auto start = std::chrono::steady_clock::now();
  const ForkedRun run = run_forked_with_budget(0.2, [](const std::function<void()>& phase_done) {
    std::this_thread::sleep_for(std::chrono::seconds(30));  // a verifier that would hang the sweep
    phase_done();
    return std::string("never");
  });
  EXPECT_TRUE(run.timed_out);
  EXPECT_TRUE(run.payload.empty());
  EXPECT_LT(seconds_since(start), 5.0);  // 0.2 s and a kill, not 30 s
}

TEST(VerifierBudget, ChildExceptionsReachTheParentWithTheirMessage) {
  try {
    run_forked_with_budget(10, [](const std::function<void()>&) -> std::string {
      throw InputError("task.yaml", "strategies", "unknown strategy 'x'");
    });
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "task.yaml: strategies: unknown strategy 'x'");
  }
}

// A work in its own process: not ended at once (it sleeps), then its result, larger than a pipe buffer.
TEST(ForkedWork, RunsInAChildAndIsCollectedWhenAskedFor) {
  ForkedWork work([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    return std::to_string(::getpid()) + ":" + std::string(100000, 'x');
  });
  EXPECT_FALSE(work.poll(false));
  EXPECT_THROW(work.result(), std::logic_error);
  EXPECT_TRUE(work.poll(true));
  EXPECT_TRUE(work.poll(false));
  const std::string out = work.result();
  ASSERT_NE(out.find(':'), std::string::npos);
  EXPECT_NE(out.substr(0, out.find(':')), std::to_string(::getpid()));
  EXPECT_EQ(out.size(), out.find(':') + 1 + 100000);
}

TEST(ForkedWork, ErrorsReachTheParentAndAnUncollectedChildIsKilled) {
  ForkedWork failing([]() -> std::string { throw std::runtime_error("check failed"); });
  ASSERT_TRUE(failing.poll(true));
  try {
    failing.result();
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "check failed");
  }
  const auto start = std::chrono::steady_clock::now();
  int pid = -1;
  {
    ForkedWork hanging([] {
      std::this_thread::sleep_for(std::chrono::seconds(30));
      return std::string("never");
    });
    pid = hanging.pid();
    EXPECT_FALSE(hanging.poll(false));
  }
  EXPECT_LT(seconds_since(start), 5.0);  // killed, not waited for
  int status = 0;
  EXPECT_EQ(::waitpid(pid, &status, WNOHANG), -1);  // and reaped: no such child any more
  EXPECT_EQ(errno, ECHILD);
}

TEST(UnitRecordText, RoundTripKeepsEveryBit) {
  UnitRecord r;
  r.reliable = true;
  r.failure = "a \"quoted\"\nline";
  r.verify_seconds = 0.1;
  r.verify_json = R"({"reliable": true})";
  r.verifier_theta_v = 0.25 + 0.0997909628669423;
  r.verifier_model = R"({"controller": "admittance"})";
  RolloutRow a;
  a.rollout = 3;
  a.motion = 1;
  a.start = {1.0 / 3, -0.0, 1e-300};
  a.end = {-1.5, 2.0 / 7, 0};
  a.atom = 45;
  a.termination = "sticking";
  a.inside = false;
  a.distance = std::numeric_limits<double>::infinity();  // an end where nothing was predicted
  a.success = false;
  a.unstable = false;
  RolloutRow b = a;
  b.motion = -1;
  b.inside.reset();  // not scored: NULL
  b.distance.reset();
  b.termination = "none";
  b.unstable = true;
  r.rollouts = {a, b};
  r.rollout_count = 2;
  r.successes = 1;
  r.unstable = 1;
  r.ends = 1;
  r.outside = 1;
  r.soundness = 0;
  r.coverage = 0.1 + 0.2;
  r.coverage_radius = 1e-17;
  r.contact_tolerance = 3.4641016151377544e-4;
  r.soundness_bug = true;
  r.counterexample = R"({"index": 3})";
  r.rollout_seconds = 12.5;

  const UnitRecord s = unit_record_from_text(unit_record_to_text(r));
  EXPECT_EQ(s.reliable, r.reliable);
  EXPECT_EQ(s.failure, r.failure);
  EXPECT_EQ(s.verify_seconds, r.verify_seconds);
  EXPECT_EQ(s.verify_json, r.verify_json);
  EXPECT_EQ(s.verifier_theta_v, r.verifier_theta_v);
  EXPECT_EQ(s.verifier_model, r.verifier_model);
  ASSERT_EQ(s.rollouts.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const RolloutRow &x = r.rollouts[i], &y = s.rollouts[i];
    EXPECT_EQ(y.rollout, x.rollout);
    EXPECT_EQ(y.motion, x.motion);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(y.start[k], x.start[k]);
      EXPECT_EQ(std::signbit(y.start[k]), std::signbit(x.start[k]));
      EXPECT_EQ(y.end[k], x.end[k]);
    }
    EXPECT_EQ(y.atom, x.atom);
    EXPECT_EQ(y.termination, x.termination);
    EXPECT_EQ(y.inside, x.inside);
    EXPECT_EQ(y.distance, x.distance);
    EXPECT_EQ(y.success, x.success);
    EXPECT_EQ(y.unstable, x.unstable);
  }
  EXPECT_EQ(s.rollout_count, 2);
  EXPECT_EQ(s.successes, 1);
  EXPECT_EQ(s.unstable, 1);
  EXPECT_EQ(s.ends, 1);
  EXPECT_EQ(s.outside, 1);
  EXPECT_EQ(s.soundness, 0);
  EXPECT_EQ(s.coverage, 0.1 + 0.2);
  EXPECT_EQ(s.coverage_radius, 1e-17);
  EXPECT_EQ(s.contact_tolerance, r.contact_tolerance);
  EXPECT_TRUE(s.soundness_bug);
  EXPECT_EQ(s.counterexample, r.counterexample);
  EXPECT_FALSE(s.sticking.has_value());
  EXPECT_EQ(s.rollout_seconds, 12.5);
  EXPECT_THROW(unit_record_from_text("{\"reliable\": 1}"), std::runtime_error);
}

}  // namespace
}  // namespace cmt
