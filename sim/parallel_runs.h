// The one thread pool of the rollouts (TBB): body(state, i) for every index i in [0, n) on at most `threads`
// threads, each thread with its own state (a RolloutRunner: one mjData, which threads must not share). The
// caller stores results by index, so they do not depend on the thread count or the schedule (every random
// draw of index i comes from its own stream, controllers/random.h). The first exception thrown by a body
// cancels the remaining indices and is rethrown here.
#pragma once

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <memory>
#include <type_traits>

namespace cmt {

// make_state() returns a std::unique_ptr<State>; it is called once per thread that takes part, on that
// thread.
template <class MakeState, class Body>
void parallel_runs(int n, int threads, MakeState make_state, Body body) {
  if (n <= 0) return;
  using StatePtr = std::invoke_result_t<MakeState>;
  tbb::enumerable_thread_specific<StatePtr> states;
  tbb::task_arena arena(std::clamp(threads, 1, n));
  arena.execute([&] {
    // Grain 1: a rollout is milliseconds to seconds of work, and indices differ widely in cost.
    tbb::parallel_for(
        tbb::blocked_range<int>(0, n, 1),
        [&](const tbb::blocked_range<int>& range) {
          StatePtr& state = states.local();
          if (!state) state = make_state();
          for (int i = range.begin(); i != range.end(); ++i) body(*state, i);
        },
        tbb::simple_partitioner());
  });
}

}  // namespace cmt
