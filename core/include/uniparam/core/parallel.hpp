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
/// deadline, see budget.hpp) and release FLINT/Arb's thread-local caches
/// when they finish.
/// \post all items ran, or the first exception thrown by a task is rethrown
///       here after every worker has stopped (items not yet started are
///       skipped).
void parallel_for(std::size_t n, std::size_t workers,
                  const std::function<void(std::size_t worker, std::size_t i)>& task);

}  // namespace uniparam
