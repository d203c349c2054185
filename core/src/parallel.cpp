// parallel.cpp -- parallel_for (see parallel.hpp).
#include "uniparam/core/parallel.hpp"

#include <flint/flint.h>
#include <pthread.h>
#include <time.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <string>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {

namespace {
/// The ScopedWorkerCount in force in this thread (0: none).
thread_local std::size_t g_worker_override = 0;
}  // namespace

ScopedWorkerCount::ScopedWorkerCount(std::size_t n) : prev_(g_worker_override) {
  if (n > 64) throw InvalidArgument("the number of threads must be from 1 to 64, got " + std::to_string(n));
  if (n > 0) g_worker_override = n;
}

ScopedWorkerCount::~ScopedWorkerCount() { g_worker_override = prev_; }

std::size_t worker_count() {
  if (g_worker_override > 0) return g_worker_override;
  if (const char* e = std::getenv("UNIPARAM_THREADS")) {
    char* end = nullptr;
    const long v = std::strtol(e, &end, 10);
    if (end != e && *end == '\0' && v >= 1) return static_cast<std::size_t>(std::min(v, 64L));
  }
  // Read once: hardware_concurrency() opens a file in /sys (~10 us), and
  // callers ask before every parallel loop.
  static const std::size_t hw = [] {
    const unsigned n = std::thread::hardware_concurrency();
    return n == 0 ? std::size_t{1} : std::min<std::size_t>(n, 8);
  }();
  return hw;
}

namespace {

std::atomic<std::uint64_t> g_dispatched{0};  // parallel_dispatches()

/// CPU time (ns) of the thread whose CPU clock is `clock`; 0 when unknown.
std::int64_t cpu_ns(clockid_t clock) {
  timespec ts{};
  if (clock_gettime(clock, &ts) != 0) return 0;
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

std::int64_t wall_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

/// One parallel_for call: the items, the task and the first error.
struct Job {
  Job(std::size_t n_, std::size_t workers_, const std::function<void(std::size_t, std::size_t)>& task_,
      const std::function<void(std::size_t)>& prepare_)
      : n(n_), workers(workers_), task(task_), prepare(prepare_), deadline(current_deadline()),
        worker_override(g_worker_override) {}
  const std::size_t n, workers;
  const std::function<void(std::size_t, std::size_t)>& task;
  const std::function<void(std::size_t)>& prepare;  // may be empty
  const Deadline deadline;
  const std::size_t worker_override;  // the caller's ScopedWorkerCount (0: none)
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  // The calling thread's CPU clock and the wall clock when the job was
  // published (set before publication, then only read).
  clockid_t caller_clock = CLOCK_THREAD_CPUTIME_ID;
  std::int64_t start_wall = 0;
  // Before the process's first thread, the CPU-time window
  // (window_cpu_ns): the wall and CPU clocks and the items started at its
  // start (window_wall 0: not started), and the earliest wall time of the
  // next CPU-clock reading; guarded by cpu_mutex.
  std::mutex cpu_mutex;
  std::int64_t window_wall = 0, window_cpu = 0, next_look = 0;
  std::size_t window_taken = 0;
  // In a process that has threads (g_threads_started when the job was
  // published), where the dispatcher judges jobs during their items, the
  // caller's CPU clock is read at the start instead (start_cpu), and at
  // each look once kInlineCpu of wall time has passed.
  bool whole_job = false;
  std::int64_t start_cpu = 0;
  std::atomic<bool> dispatched{false};  // pool threads may join (written under the pool's mutex)

  /// Worker `worker` takes items until none is left or one failed. Worker
  /// 0 calls between_items() after each of its items (may be empty).
  template <class F>
  void work(std::size_t worker, F between_items) {
    for (;;) {
      const std::size_t i = next.fetch_add(1);
      if (i >= n || failed.load()) return;
      try {
        task(worker, i);
        between_items();
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        failed.store(true);
        return;
      }
    }
  }
  void work(std::size_t worker) {
    work(worker, [] {});
  }

  /// Worth waking the pool threads for: what is left of the job is long
  /// enough to pay for them. The caller has spent kInlineCpu of CPU time on
  /// it, and the items the other workers could take, estimated at the
  /// caller's CPU time per item so far, add up to kInlineCpu more (a
  /// process with threads: whole_job); before the process's first thread,
  /// the same with kFirstThreadCpu, the first half of it counted in wall
  /// time and the second in CPU time, the time per item the second half's
  /// (window_cpu_ns); or the
  /// same with wall time and kInlineWall (a task that blocks, or a caller
  /// that is descheduled for long). The items the others could take: those
  /// not started, less the one the caller starts next when `between` (it
  /// is between two items, and takes the next one itself before a woken
  /// thread could). Items of one job cost about the same; where its tail
  /// costs more than its head, the estimate is low and the job may finish
  /// alone, which costs at most what one thread costs.
  bool due(std::int64_t now_wall, bool between);

  /// The caller's CPU time on the job since the window opened, and the
  /// items started since then (in `items`), without a reading of its CPU
  /// clock at the job's start (a system call of about 1.5 us on a virtual
  /// machine, as long as a small job's item). The window opens at the first
  /// look (the CPU clock's first reading); -1 then, and between two
  /// readings (at most one per kWindow). Looks start at half the threshold
  /// (due), so a job shorter than that never reads the CPU clock.
  std::int64_t window_cpu_ns(std::int64_t now_wall, std::size_t& items);
  /// At the end of the job: 1 when the window measured at least the
  /// threshold of CPU time, 0 when it measured less, -1 when it was not
  /// opened (no reading is taken then).
  int window_long_enough(std::int64_t now_wall);
};

/// The work a job does on the calling thread alone before the pool threads
/// are woken, and the least work that must be left for them then. Waking a
/// blocked thread costs a futex call and a reschedule (tens of microseconds
/// on an idle VM, a time slice on a busy machine), a prepare step's copies
/// cost more, the woken thread's copies start with cold caches, and the
/// caller waits at the end for the item the last woken thread took: more
/// than a whole job at low degree, and more than a job's last few items
/// save. A job that ends within this much CPU time never touches another
/// thread, so it costs what it costs on one; one is dispatched only when
/// at least this much is estimated to be left for the others, so that the
/// time they save (half of it on two workers) pays for them.
/// CPU time, not wall time: a caller descheduled on a busy machine has not
/// done more work, and threads would not make it faster.
constexpr std::int64_t kInlineCpu = 500000;      // ns
/// kInlineCpu for the first job of the process that would start a thread
/// (a pool thread or the dispatcher): glibc's allocator locks its arena in
/// every calloc, realloc and non-cached free once a second thread has
/// existed, for the rest of the process (1-2% of a low-degree computation,
/// whose numbers GMP and FLINT allocate), so a process of small jobs must
/// not start one for a job that threads would shorten by a fraction of a
/// millisecond.
constexpr std::int64_t kFirstThreadCpu = 2000000;  // ns
/// The dispatcher (the only way to wake threads while the caller is inside
/// a long item, e.g. two long steps side by side) is started after long
/// items (of inline_cpu() with others left) have taken this much wall time
/// in the process in all: a process whose one long item was a one-time
/// cost (a cold cache: the first run of a small job) does not pay for a
/// thread (kFirstThreadCpu) for the rest of its life; a process of long
/// jobs reaches it within its first few.
constexpr std::int64_t kDispatcherAfterLongItems = 4 * kFirstThreadCpu;  // ns
/// The wall time of the long items seen so far (Pool::run).
std::atomic<std::int64_t> g_long_items_wall{0};
/// Set once the process has started a pool thread or the dispatcher.
std::atomic<bool> g_threads_started{false};
/// kInlineCpu, or kFirstThreadCpu before the process's first thread.
std::int64_t inline_cpu() { return g_threads_started.load(std::memory_order_relaxed) ? kInlineCpu : kFirstThreadCpu; }
constexpr std::int64_t kInlineWall = 100000000;  // ns
/// The least wall time between two readings of the caller's CPU clock
/// (Job::window_cpu_ns).
constexpr std::int64_t kWindow = 100000;  // ns
/// How often the dispatcher looks at the published jobs, while there are
/// any: a long job waits at most this much beyond kInlineCpu for the pool
/// threads; each look is a wake-up of the dispatcher (microseconds).
constexpr std::chrono::microseconds kTick{1000};

std::int64_t Job::window_cpu_ns(std::int64_t now_wall, std::size_t& items) {
  std::lock_guard<std::mutex> lock(cpu_mutex);
  if (now_wall < next_look) return -1;
  next_look = now_wall + kWindow;
  const std::int64_t cpu = cpu_ns(caller_clock);
  if (window_wall == 0) {
    window_wall = now_wall;
    window_cpu = cpu;
    window_taken = next.load();
    return -1;
  }
  items = next.load() - window_taken;
  return std::max<std::int64_t>(cpu - window_cpu, 0);
}

int Job::window_long_enough(std::int64_t now_wall) {
  if (whole_job) return cpu_ns(caller_clock) - start_cpu >= inline_cpu() ? 1 : 0;
  {
    std::lock_guard<std::mutex> lock(cpu_mutex);
    if (window_wall == 0) return -1;
    next_look = 0;  // the window is open: one more reading closes it
  }
  std::size_t items = 0;
  return window_cpu_ns(now_wall, items) >= inline_cpu() ? 1 : 0;
}

bool Job::due(std::int64_t now_wall, bool between) {
  // Before the dispatch only the caller takes items: `taken` items were
  // started by it, all done when it is between two, all but the last
  // otherwise (the time per item then is too low, if anything).
  const std::size_t taken = next.load();
  if (taken == 0 || taken >= n) return false;  // nothing measured yet, or nothing left
  const std::size_t open = n - taken - (between ? 1 : 0);
  const std::int64_t wall = now_wall - start_wall;
  const std::int64_t threshold = inline_cpu();
  if (open == 0) {  // the caller's own next item is the last: threads cannot help
    // Its window still opens, for the end of the job (window_long_enough).
    std::size_t items = 0;
    if (!whole_job && wall >= threshold / 2) window_cpu_ns(now_wall, items);
    return false;
  }
  const auto left = [&](std::int64_t spent, std::size_t items) {  // the work left for the others
    return static_cast<std::int64_t>(open) * (spent / static_cast<std::int64_t>(std::max<std::size_t>(items, 1)));
  };
  if (wall >= kInlineWall && left(wall, taken) >= kInlineWall) return true;
  if (whole_job) {  // a process with threads: the CPU time since the start
    if (wall < kInlineCpu) return false;  // CPU time <= wall time: no system call
    const std::int64_t cpu = cpu_ns(caller_clock) - start_cpu;
    return cpu >= kInlineCpu && left(cpu, taken) >= kInlineCpu;
  }
  // A process without threads yet: the first half of the threshold in
  // wall time, which bounds the CPU time before the window (CPU time <=
  // wall time, and no reading of the CPU clock for a job that ends
  // sooner), then the second half measured in the window. A caller
  // descheduled before the window is not counted as working then; the time
  // per item is the window's.
  if (wall < threshold / 2) return false;
  std::size_t items = 0;
  const std::int64_t cpu = window_cpu_ns(now_wall, items);
  return cpu >= threshold / 2 && left(cpu, items) >= threshold;
}

/// The number of pools: a parallel_for made inside a task of another (an
/// operation's steps side by side, each with its own parallel loops) takes
/// the next pool, whose threads are as persistent as the first's. Deeper
/// nesting runs on the calling thread.
constexpr int kPools = 4;
thread_local int t_pool = -1;  // the pool this thread belongs to (-1: none)

/// Persistent worker threads, started when a job is first dispatched and
/// kept until the process exits. Their FLINT/Arb thread-local caches
/// (Gauss-Legendre nodes above all: computing them costs more than a
/// low-degree quadrature) then live from one parallel_for to the next, as
/// the calling thread's do. Pool thread k (k >= 1) is worker k of every
/// dispatched job that uses at least k + 1 workers. A job is published
/// without waking anyone; the calling thread works on it, and the pool
/// threads are woken only once the job is due (Job::due), by the calling
/// thread between two items or by the dispatcher (Dispatcher) during one. Threads block on a condition variable; nothing spins. One
/// job at a time: a call that finds the pool in use (from another thread,
/// or from inside a task) takes the next pool (parallel_for).
class Pool {
 public:
  /// Pool k (0 <= k < kPools); pool k's threads know they belong to it.
  static Pool& instance(int k) {
    static Pool pools[kPools] = {Pool(0), Pool(1), Pool(2), Pool(3)};
    return pools[k];
  }

  /// Runs job on the calling thread (worker 0) and, once it is due, on pool
  /// threads 1..workers-1; false (nothing run) when the pool is in use.
  bool run(Job& job);

  /// Dispatches the current job if it is due (the dispatcher's tick; the
  /// caller is taken to be inside an item); true when the pool has a job
  /// that is not yet dispatched and has no prepare step (one with a prepare
  /// step is the caller's to dispatch, between two items).
  bool poll(std::int64_t now_wall) {
    // Nothing published (read without the lock): no lock taken, so a tick
    // never contends with a calling thread starting or ending a job.
    if (!waiting_.load()) return false;
    std::unique_lock<std::mutex> lock(m_);
    if (!job_ || job_->dispatched || job_->prepare) return false;
    if (!job_->due(now_wall, false)) return true;
    dispatch_locked();
    lock.unlock();
    wake_.notify_all();
    return false;
  }

  /// A job without a prepare step is published and not yet dispatched
  /// (read without the lock): the dispatcher has something to look at.
  bool waiting() const { return waiting_.load(); }

  ~Pool() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    wake_.notify_all();
    for (auto& t : threads_) t.join();
  }

 private:
  explicit Pool(int level) : level_(level) {}

  /// \pre m_ held, job_ set and not dispatched.
  void dispatch_locked() {
    while (threads_.size() + 1 < job_->workers) {
      const std::size_t k = threads_.size() + 1;
      g_threads_started.store(true);
      threads_.emplace_back([this, k] { loop(k); });
    }
    job_->dispatched.store(true);
    waiting_.store(false);
    ++generation_;
    g_dispatched.fetch_add(1);
  }

  void loop(std::size_t k) {
    t_pool = level_;
    std::uint64_t seen = 0;
    for (;;) {
      Job* job = nullptr;
      {
        std::unique_lock<std::mutex> lock(m_);
        wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_) break;
        seen = generation_;
        // null: the job this generation dispatched has ended, or needs fewer workers
        if (job_ && job_->dispatched && k < job_->workers) {
          job = job_;
          ++joined_;
        }
      }
      if (!job) continue;
      {
        const ScopedDeadline inherit(job->deadline);
        const ScopedWorkerCount inherit_workers(job->worker_override);
        job->work(k);
      }
      bool last;
      {
        std::lock_guard<std::mutex> lock(m_);
        last = --joined_ == 0;
      }
      if (last) done_.notify_all();
    }
    flint_cleanup();  // this thread's FLINT/Arb caches
  }

  int level_;                        // this pool's index (Pool::instance)
  std::atomic<bool> in_use_{false};  // a parallel_for is using the pool
  std::atomic<bool> waiting_{false};  // job_ set, not dispatched, without a prepare step
  std::mutex m_;  // guards everything below
  std::condition_variable wake_, done_;
  std::vector<std::thread> threads_;
  Job* job_ = nullptr;
  std::size_t joined_ = 0;  // pool threads working on job_ (or on the job before it)
  std::uint64_t generation_ = 0;  // bumped by every dispatch
  bool stop_ = false;
};

/// One thread that wakes the pool threads for the jobs that are due while
/// their calling thread is inside an item (e.g. an operation's two long
/// steps side by side): it looks every kTick while any pool has a published
/// job without a prepare step, and blocks otherwise (a parallel_for that
/// finds it blocked wakes it). It never runs items itself. Started (start())
/// by the first dispatch, or by the end of the first job in which one of
/// the caller's items ran for inline_cpu() while others were left, so a
/// process that only runs small jobs has no thread besides its own (the
/// allocator's single-thread fast paths stay on, and nothing wakes up);
/// the calling thread dispatches between items by itself.
class Dispatcher {
 public:
  /// The dispatcher, started on first call.
  static Dispatcher& start() {
    static Dispatcher d;
    started_.store(&d);
    return d;
  }
  /// The dispatcher if started, else null.
  static Dispatcher* started() { return started_.load(); }

  /// A job was just published on some pool.
  void arm() {
    if (!idle_.load()) return;
    std::lock_guard<std::mutex> lock(m_);
    if (idle_.load()) {
      idle_.store(false);
      cv_.notify_one();
    }
  }

  ~Dispatcher() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    cv_.notify_one();
    thread_.join();
  }

 private:
  Dispatcher() : thread_((g_threads_started.store(true), [this] { loop(); })) {}

  void loop() {
    std::unique_lock<std::mutex> lock(m_);
    int quiet = 0;  // ticks without a waiting job
    while (!stop_) {
      bool any = false;
      for (int k = 0; k < kPools; ++k) any = Pool::instance(k).poll(wall_ns()) || any;
      quiet = any ? 0 : quiet + 1;
      if (quiet >= 4) {
        // Block until a job is published. Set idle_ first, then look again:
        // a job published meanwhile either sees idle_ (and wakes us) or is
        // seen here.
        idle_.store(true);
        bool waiting = false;
        for (int k = 0; k < kPools; ++k) waiting = waiting || Pool::instance(k).waiting();
        if (waiting) {
          idle_.store(false);
        } else {
          cv_.wait(lock, [this] { return stop_ || !idle_.load(); });
        }
        quiet = 0;
        continue;
      }
      cv_.wait_for(lock, kTick, [this] { return stop_; });
    }
  }

  std::mutex m_;
  std::condition_variable cv_;
  std::atomic<bool> idle_{false};
  bool stop_ = false;
  std::thread thread_;  // last: started once the members above exist
  static std::atomic<Dispatcher*> started_;
};

std::atomic<Dispatcher*> Dispatcher::started_{nullptr};

bool Pool::run(Job& job) {
  bool expected = false;
  if (!in_use_.compare_exchange_strong(expected, true)) return false;
  struct Release {
    std::atomic<bool>& flag;
    ~Release() { flag.store(false); }
  } release{in_use_};
  if (pthread_getcpuclockid(pthread_self(), &job.caller_clock) != 0) job.caller_clock = CLOCK_THREAD_CPUTIME_ID;
  // A process that has threads runs long jobs: one reading of the CPU
  // clock per job lets the dispatcher judge it from its first tick.
  if (g_threads_started.load()) {
    job.whole_job = true;
    job.start_cpu = cpu_ns(job.caller_clock);
  }
  job.start_wall = wall_ns();
  const bool for_dispatcher = !job.prepare;  // a prepare step runs on the caller
  {
    std::lock_guard<std::mutex> lock(m_);
    job_ = &job;
    waiting_.store(for_dispatcher);
  }
  if (Dispatcher* d = Dispatcher::started(); d && for_dispatcher) d->arm();
  // Between its items the caller dispatches a job that is due itself (the
  // dispatcher may not run yet, and cannot run a prepare step).
  // Whether one of the caller's items ran for inline_cpu() of wall time
  // while items were left for others: a job the dispatcher could have
  // dispatched during that item.
  std::int64_t item_start = job.start_wall;
  bool long_item = false;
  job.work(0, [&] {
    const std::int64_t now = wall_ns();
    if (now - item_start >= inline_cpu() && job.next.load() < job.n) {
      long_item = true;
      g_long_items_wall.fetch_add(now - item_start, std::memory_order_relaxed);
    }
    item_start = now;
    if (job.dispatched.load() || !job.due(now, true)) return;
    Dispatcher::start();
    if (job.prepare) job.prepare(job.workers);  // no task runs now: the caller is between items
    {
      std::lock_guard<std::mutex> lock(m_);
      if (job.dispatched.load()) return;
      dispatch_locked();
    }
    wake_.notify_all();
  });
  // A job with an item that long, once such items have taken
  // kDispatcherAfterLongItems in the process: later ones get the
  // dispatcher. Not a job that was long only in its number of items (the
  // caller dispatches those between items), nor one whose long item was
  // its last: starting a thread costs the process (inline_cpu()). Nor a
  // caller that was only descheduled for that long: its CPU time in the
  // job's window must reach the threshold too.
  if (long_item && !Dispatcher::started() &&
      g_long_items_wall.load(std::memory_order_relaxed) >= kDispatcherAfterLongItems &&
      job.window_long_enough(wall_ns()) == 1)
    Dispatcher::start();
  std::unique_lock<std::mutex> lock(m_);
  job_ = nullptr;  // threads woken from now on sit this job out
  waiting_.store(false);
  done_.wait(lock, [this] { return joined_ == 0; });
  return true;
}

}  // namespace

std::uint64_t parallel_dispatches() { return g_dispatched.load(); }

bool parallel_threads_started() { return g_threads_started.load(); }

void parallel_for(std::size_t n, std::size_t max_workers, const std::function<void(std::size_t, std::size_t)>& task,
                  const std::function<void(std::size_t)>& prepare) {
  const std::size_t workers = std::min(std::max<std::size_t>(max_workers, 1), n);
  if (workers <= 1) {
    for (std::size_t i = 0; i < n; ++i) task(0, i);
    return;
  }
  Job job(n, workers, task, prepare);
  // A free pool after the calling thread's own (the caller is worker 0 of
  // whatever job it is running; the pools before its own may be busy with
  // the job it belongs to).
  bool ran = false;
  for (int k = t_pool + 1; k < kPools && !ran; ++k) ran = Pool::instance(k).run(job);
  if (!ran) job.work(0);  // every pool busy: the machine's threads are too
  if (job.error) std::rethrow_exception(job.error);
}

}  // namespace uniparam
