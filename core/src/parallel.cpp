// parallel.cpp -- parallel_for (see parallel.hpp).
#include "uniparam/core/parallel.hpp"

#include <flint/flint.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "uniparam/core/budget.hpp"

namespace uniparam {

std::size_t worker_count() {
  if (const char* e = std::getenv("UNIPARAM_THREADS")) {
    char* end = nullptr;
    const long v = std::strtol(e, &end, 10);
    if (end != e && *end == '\0' && v >= 1) return static_cast<std::size_t>(std::min(v, 64L));
  }
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : std::min<std::size_t>(hw, 8);
}

namespace {

/// One parallel_for call: the items, the task and the first error.
struct Job {
  Job(std::size_t n_, std::size_t workers_, const std::function<void(std::size_t, std::size_t)>& task_)
      : n(n_), workers(workers_), task(task_), deadline(current_deadline()) {}
  const std::size_t n, workers;
  const std::function<void(std::size_t, std::size_t)>& task;
  const Deadline deadline;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;

  /// Worker `worker` takes items until none is left or one failed.
  void work(std::size_t worker) {
    for (;;) {
      const std::size_t i = next.fetch_add(1);
      if (i >= n || failed.load()) return;
      try {
        task(worker, i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        failed.store(true);
        return;
      }
    }
  }
};

/// The number of pools: a parallel_for made inside a task of another (an
/// operation's steps side by side, each with its own parallel loops) takes
/// the next pool, whose threads are as persistent as the first's. Deeper
/// nesting gets threads of its own.
constexpr int kPools = 4;
thread_local int t_pool = -1;  // the pool this thread belongs to (-1: none)

/// How long a pool thread that finished its items, and a caller waiting for
/// the pool threads, poll before they block on a condition variable. A
/// blocked thread takes a futex wake-up and a reschedule to start (tens of
/// microseconds on a VM), which is the whole run time of a low-degree job;
/// the jobs of one operation follow each other within far less than this.
/// The poll yields the processor every 64 rounds, so an oversubscribed
/// machine loses little to it.
constexpr std::chrono::microseconds kSpin{500};

/// Polls ready() for at most kSpin; true as soon as it holds.
template <class Ready>
bool spin_until(Ready ready) {
  const auto until = std::chrono::steady_clock::now() + kSpin;
  for (unsigned round = 0;; ++round) {
    if (ready()) return true;
    if ((round & 63) == 63) {
      if (std::chrono::steady_clock::now() >= until) return false;
      std::this_thread::yield();
    }
  }
}

/// Persistent worker threads, started on first use and kept until the
/// process exits. Their FLINT/Arb thread-local caches (Gauss-Legendre nodes
/// above all: computing them costs more than a low-degree quadrature) then
/// live from one parallel_for to the next, as the calling thread's do,
/// instead of being rebuilt by fresh threads at every call. Pool thread k
/// (k >= 1) is worker k of every job that uses at least k + 1 workers.
/// One job at a time: a call that finds the pool in use (from another
/// thread, or from inside a task) takes the next pool (parallel_for), and
/// threads of its own when all kPools are.
class Pool {
 public:
  /// Pool k (0 <= k < kPools); pool k's threads know they belong to it.
  static Pool& instance(int k) {
    static Pool pools[kPools] = {Pool(0), Pool(1), Pool(2), Pool(3)};
    return pools[k];
  }

  /// Runs job on the calling thread (worker 0) and pool threads 1..workers-1;
  /// false (nothing run) when the pool is in use.
  bool run(Job& job) {
    bool expected = false;
    if (!in_use_.compare_exchange_strong(expected, true)) return false;
    struct Release {
      std::atomic<bool>& flag;
      ~Release() { flag.store(false); }
    } release{in_use_};
    {
      std::lock_guard<std::mutex> lock(m_);
      while (threads_.size() + 1 < job.workers) {
        const std::size_t k = threads_.size() + 1;
        threads_.emplace_back([this, k] { loop(k); });
      }
      job_ = &job;
      pending_ = job.workers - 1;
      pending_count_.store(pending_, std::memory_order_release);
      generation_.fetch_add(1, std::memory_order_release);
    }
    wake_.notify_all();
    job.work(0);
    spin_until([this] { return pending_count_.load(std::memory_order_acquire) == 0; });
    std::unique_lock<std::mutex> lock(m_);
    done_.wait(lock, [this] { return pending_ == 0; });
    job_ = nullptr;
    return true;
  }

  ~Pool() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
      stop_flag_.store(true);
    }
    wake_.notify_all();
    for (auto& t : threads_) t.join();
  }

 private:
  explicit Pool(int level) : level_(level) {}

  void loop(std::size_t k) {
    t_pool = level_;
    std::uint64_t seen = 0;
    for (;;) {
      Job* job = nullptr;
      spin_until([&] { return generation_.load(std::memory_order_acquire) != seen || stop_flag_.load(); });
      {
        std::unique_lock<std::mutex> lock(m_);
        wake_.wait(lock, [&] { return stop_ || generation_.load() != seen; });
        if (stop_) break;
        seen = generation_.load();
        if (job_ && k < job_->workers) job = job_;  // null: a job this thread sat out ended
      }
      if (!job) continue;
      {
        const ScopedDeadline inherit(job->deadline);
        job->work(k);
      }
      bool last;
      {
        std::lock_guard<std::mutex> lock(m_);
        last = --pending_ == 0;
        pending_count_.store(pending_, std::memory_order_release);
      }
      if (last) done_.notify_one();
    }
    flint_cleanup();  // this thread's FLINT/Arb caches
  }

  int level_;                        // this pool's index (Pool::instance)
  std::atomic<bool> in_use_{false};  // a parallel_for is using the pool
  std::mutex m_;    // guards everything below
  std::condition_variable wake_, done_;
  std::vector<std::thread> threads_;
  Job* job_ = nullptr;
  std::size_t pending_ = 0;  // pool threads of the current job still working
  std::atomic<std::uint64_t> generation_{0};  // written under m_; read by the spinning threads
  bool stop_ = false;
  // Copies of pending_ and stop_ for the spinning threads (written under m_).
  std::atomic<std::size_t> pending_count_{0};
  std::atomic<bool> stop_flag_{false};
};

/// The pool is busy: threads of this call's own, released when it returns.
void run_on_fresh_threads(Job& job) {
  std::vector<std::thread> threads;
  threads.reserve(job.workers - 1);
  for (std::size_t w = 1; w < job.workers; ++w)
    threads.emplace_back([&job, w] {
      {
        const ScopedDeadline inherit(job.deadline);
        job.work(w);
      }
      flint_cleanup();  // this thread's FLINT/Arb caches (Gauss-Legendre nodes, ...)
    });
  job.work(0);
  for (auto& t : threads) t.join();
}

}  // namespace

void parallel_for(std::size_t n, std::size_t max_workers, const std::function<void(std::size_t, std::size_t)>& task) {
  const std::size_t workers = std::min(std::max<std::size_t>(max_workers, 1), n);
  if (workers <= 1) {
    for (std::size_t i = 0; i < n; ++i) task(0, i);
    return;
  }
  Job job(n, workers, task);
  // A free pool after the calling thread's own (the caller is worker 0 of
  // whatever job it is running; the pools before its own may be busy with
  // the job it belongs to).
  bool ran = false;
  for (int k = t_pool + 1; k < kPools && !ran; ++k) ran = Pool::instance(k).run(job);
  if (!ran) run_on_fresh_threads(job);
  if (job.error) std::rethrow_exception(job.error);
}

}  // namespace uniparam
