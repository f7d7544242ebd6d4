// The pool behind car_sim::parallel_for (include/car_sim/parallel.hpp).
#include "car_sim/parallel.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace car_sim {

namespace {

// One loop: items claimed from `next`; `refs` counts workers inside it (the caller waits for them to leave).
struct Job {
  const std::function<void(int, int)>* fn = nullptr;
  int n = 0;
  std::atomic<int> next{0};
  int refs = 0;                    // guarded by Pool::m
  std::exception_ptr error;        // guarded by Pool::m
};

thread_local bool in_loop = false;  // this thread runs an item of a loop (nested loops run serially)

class Pool {
 public:
  static Pool& get() {
    // never destroyed: workers may outlive static destruction order at exit
    static Pool* p = new Pool();
    return *p;
  }

  // Runs the job with up to `threads` threads, or false when another loop holds the pool.
  bool run(Job& j, int threads) {
    if (busy_.exchange(true)) return false;
    grow(threads - 1);
    bool sleepers;
    {
      std::lock_guard<std::mutex> l(m_);
      job_ = &j;
      wanted_ = threads - 1;
      gen_.fetch_add(1, std::memory_order_release);
      sleepers = sleeping_ > 0;
    }
    if (sleepers) wake_.notify_all();
    work(j, 0);
    {
      std::unique_lock<std::mutex> l(m_);
      job_ = nullptr;  // a worker that wakes from now on finds nothing to join
      left_.wait(l, [&] { return j.refs == 0; });
    }
    busy_.store(false);
    return true;
  }

  // Claims and runs items until none are left; the first exception is kept in the job.
  static void work(Job& j, int thread) {
    in_loop = true;
    for (int i = j.next.fetch_add(1); i < j.n; i = j.next.fetch_add(1)) {
      try {
        (*j.fn)(i, thread);
      } catch (...) {
        std::lock_guard<std::mutex> l(get().m_);
        if (!j.error) j.error = std::current_exception();
      }
    }
    in_loop = false;
  }

 private:
  void grow(int workers) {
    while (static_cast<int>(threads_.size()) < workers) {
      const int index = static_cast<int>(threads_.size());
      threads_.emplace_back([this, index] { loop(index); });
      threads_.back().detach();
    }
  }

  void loop(int index) {
    unsigned long seen = 0;
    for (;;) {
      // A while (about 100 us) the next loop is looked for without sleeping: a step's loops come a few
      // microseconds apart, and waking a sleeping thread costs more than that. Then sleep until one comes.
      const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(100);
      for (int k = 0; gen_.load(std::memory_order_acquire) == seen; ++k) {
        if ((k & 63) == 63 && std::chrono::steady_clock::now() > until) break;
        std::this_thread::yield();
      }
      std::unique_lock<std::mutex> l(m_);
      ++sleeping_;
      wake_.wait(l, [&] { return gen_.load(std::memory_order_relaxed) != seen; });
      --sleeping_;
      seen = gen_.load(std::memory_order_relaxed);
      Job* j = job_;
      // the loop is gone, or wants fewer workers than there are
      if (!j || index >= wanted_) continue;
      ++j->refs;
      l.unlock();
      work(*j, index + 1);
      l.lock();
      if (--j->refs == 0) left_.notify_all();
    }
  }

  std::mutex m_;
  std::condition_variable wake_, left_;
  std::atomic<unsigned long> gen_{0};  // written under m_
  int sleeping_ = 0;                   // workers waiting on wake_, guarded by m_
  Job* job_ = nullptr;     // guarded by m_
  int wanted_ = 0;         // guarded by m_
  std::atomic<bool> busy_{false};
  std::vector<std::thread> threads_;  // only the thread holding busy_ grows it
};

}  // namespace

int parallel_threads() { return std::max(1, omp_get_max_threads()); }

void parallel_for_threads(int n, const std::function<void(int, int)>& fn, int max_threads) {
  if (n <= 0) return;
  Job j;
  j.fn = &fn;
  j.n = n;
  const int cap = max_threads > 0 ? std::min(max_threads, parallel_threads()) : parallel_threads();
  const int threads = std::min(cap, n);
  if (threads <= 1 || in_loop || !Pool::get().run(j, threads)) {
    // serially on the caller; an exception propagates as it is
    for (int i = 0; i < n; ++i) fn(i, 0);
    return;
  }
  if (j.error) std::rethrow_exception(j.error);
}

void parallel_for(int n, const std::function<void(int)>& fn) {
  parallel_for_threads(n, [&fn](int i, int) { fn(i); });
}

}  // namespace car_sim
