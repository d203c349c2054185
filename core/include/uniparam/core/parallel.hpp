// uniparam/core/parallel.hpp -- a minimal parallel loop over independent
// work items (the pieces of a reparameterization), on a few threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

namespace uniparam {

/// Number of worker threads parallel_for uses: the count of a
/// ScopedWorkerCount in force in the calling thread, else the environment
/// variable UNIPARAM_THREADS when set to a positive integer (1 = everything
/// on the calling thread), otherwise std::thread::hardware_concurrency()
/// capped at 8 (1 when unknown), read once per process.
std::size_t worker_count();

/// Sets worker_count() for the calling thread, and for the worker threads
/// of the parallel loops it starts (they inherit it, as they inherit the
/// time budget), for the scope's lifetime; the previous setting is restored
/// at destruction. A library caller's per-call thread count (the Python
/// module's threads=), without touching the process environment.
/// \pre 1 <= n <= 64 (InvalidArgument otherwise); n = 0 leaves the default.
class ScopedWorkerCount {
 public:
  explicit ScopedWorkerCount(std::size_t n);
  ~ScopedWorkerCount();
  ScopedWorkerCount(const ScopedWorkerCount&) = delete;
  ScopedWorkerCount& operator=(const ScopedWorkerCount&) = delete;

 private:
  std::size_t prev_;
};

/// Runs task(worker, i) for every i in [0, n), on at most min(workers, n)
/// threads (workers >= 1; typically worker_count()); worker 0 is the calling
/// thread, and every item runs on exactly one worker, with worker <
/// min(workers, n), so a task may use per-worker state indexed by `worker`
/// without locking. Items are handed out in increasing order as workers
/// become free.
/// Small jobs, and the small ends of long ones, run on the calling thread
/// alone: the call publishes the job and starts on it; the other workers
/// are woken only once the calling thread has spent 0.5 ms of CPU time on
/// it and the items the others could take (those not started, less the
/// one the calling thread takes next when it is between two) are estimated,
/// at its CPU time per item so far, at 0.5 ms or more (the same with 0.1 s
/// of wall time, for tasks that block): by the calling thread between two
/// items, or during one by a dispatcher thread that looks every
/// millisecond while jobs without a prepare step run (started by the first
/// job in which one of the caller's items took that long while others were
/// left, once such items have taken 8 ms of wall time in the process in
/// all: until then a job can only be dispatched between items, and a
/// process of small jobs, or one whose only long item was a cold start,
/// starts no thread at all). Until the process has
/// started a thread, both bounds are 2 ms instead of 0.5 ms (from its
/// first thread on, glibc's allocator takes a lock in every calloc, realloc
/// and uncached free, which costs small computations 1-2% for the rest of
/// the process), and the first half of that CPU time is counted in wall
/// time, the second half (and so the time per item) in the calling
/// thread's CPU time: a job shorter than 1 ms reads only the wall clock,
/// without a system call. So a job shorter than the bounds, or one found
/// long only near its end, costs what it costs on one thread and never
/// waits for another. Waiting threads block on a condition variable (no
/// spinning).
/// Worker threads inherit the calling thread's time budget (the same
/// deadline, see budget.hpp). Workers 1.. are persistent pool threads,
/// started when first needed and kept until the process exits (when they
/// release FLINT/Arb's thread-local caches), so those caches (Gauss-Legendre
/// nodes) serve every later call as the calling thread's do. A pool runs one
/// call at a time: a call made while it is busy (from another thread, or
/// nested inside a task, e.g. an operation's steps side by side with loops
/// of their own) takes the next of four such pools, equally persistent, and
/// when all are busy runs on the calling thread alone. Which thread runs
/// which item is not fixed, so tasks must not depend on it beyond `worker`.
/// `prepare` (may be empty) makes the state workers 1.. need, e.g. their
/// own copies of objects with mutable caches: prepare(k) runs on the calling
/// thread, between two of its items (no task is running then), right
/// before workers 1..k-1 (k = min(workers, n)) are woken, and never for a
/// job that stays on the calling thread, so a small job does not pay for
/// copies it does not use. A job with a prepare step is dispatched only by
/// the calling thread, between two items, when it finds the job due.
/// An exception from prepare is treated as one from a task.
/// \post all items ran, or the first exception thrown by a task is rethrown
///       here after every worker has stopped (items not yet started are
///       skipped).
void parallel_for(std::size_t n, std::size_t workers,
                  const std::function<void(std::size_t worker, std::size_t i)>& task,
                  const std::function<void(std::size_t workers)>& prepare = {});

/// Work counter (tests, benchmarks): the number of jobs whose pool threads
/// parallel_for has woken, since the process started (all threads).
std::uint64_t parallel_dispatches();

/// Whether parallel_for has started a thread (a pool thread or the
/// dispatcher) in this process (tests).
bool parallel_threads_started();

}  // namespace uniparam
