// uniparam/core/parallel.hpp -- a minimal parallel loop over independent
// work items (the pieces of a reparameterization), on a few threads.
#pragma once

#include <cstddef>
#include <functional>

namespace uniparam {

/// Number of worker threads parallel_for uses: the environment variable
/// UNIPARAM_THREADS when set to a positive integer (1 = everything on the
/// calling thread), otherwise std::thread::hardware_concurrency() capped
/// at 8 (1 when unknown).
std::size_t worker_count();

/// Runs task(worker, i) for every i in [0, n), on min(workers, n) threads
/// (workers >= 1; typically worker_count()); worker 0 is the calling thread,
/// and every item runs on exactly one worker, with worker < min(workers, n),
/// so a task may use per-worker state indexed by `worker` without locking. Items are handed out in
/// increasing order as workers become free.
/// Worker threads inherit the calling thread's time budget (the same
/// deadline, see budget.hpp). Workers 1.. are persistent pool threads,
/// started on first use and kept until the process exits (when they release
/// FLINT/Arb's thread-local caches), so those caches (Gauss-Legendre nodes)
/// serve every later call as the calling thread's do. A pool thread that
/// has finished, and the caller waiting for the pool threads, poll for up to
/// 0.5 ms before they sleep, so that the calls of one operation (each a
/// fraction of a millisecond at low degree) do not wait for a thread to be
/// woken and rescheduled. A pool runs one call at a time: a call made while
/// it is busy (from another thread, or nested inside a task, e.g. an
/// operation's steps side by side with loops of their own) takes the next
/// of four such pools, equally persistent, and when all are busy runs on
/// threads of its own, started for the call and released (caches included)
/// when it returns. Which thread runs which item
/// is not fixed either way, so tasks must not depend on it beyond `worker`.
/// \post all items ran, or the first exception thrown by a task is rethrown
///       here after every worker has stopped (items not yet started are
///       skipped).
void parallel_for(std::size_t n, std::size_t workers,
                  const std::function<void(std::size_t worker, std::size_t i)>& task);

}  // namespace uniparam
