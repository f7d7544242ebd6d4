// Car's parallel loop: a persistent pool of worker threads that never holds the caller back for a thread the OS
// has not run yet. OpenMP's fork-join waits for every thread of the team at the end of each region, so on a busy
// machine (rviz, robot_state_publisher, a compiler beside the simulator) a region that needs a millisecond waits
// for a time slice of the second core; here items are claimed one at a time from a shared counter, the calling
// thread claims too, and the call waits only for items a worker has actually taken. No ROS headers.
#pragma once

#include <functional>

namespace car_sim {

// Runs fn(i) once for every i in [0, n), on the calling thread and up to parallel_threads() - 1 workers, and
// returns when all are done. fn's result must not depend on which thread runs it (then the outcome is the same
// for any thread count). Nested calls, and calls while another thread's loop runs, run serially on the caller.
// The first exception an item throws is rethrown here after the loop has finished.
void parallel_for(int n, const std::function<void(int)>& fn);

// The same, with the index of the thread running the item: 0 for the caller, 1 .. threads - 1 for workers, where
// threads = min(max_threads, parallel_threads()) (max_threads <= 0: no cap); for per-thread scratch. A loop that
// runs serially runs on thread 0.
void parallel_for_threads(int n, const std::function<void(int item, int thread)>& fn, int max_threads = 0);

// Threads a loop may use, the caller included: omp_get_max_threads() (OMP_NUM_THREADS, or the CPUs).
int parallel_threads();

}  // namespace car_sim
