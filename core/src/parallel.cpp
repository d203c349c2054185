// parallel.cpp -- parallel_for (see parallel.hpp).
#include "uniparam/core/parallel.hpp"

#include <flint/flint.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <exception>
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

void parallel_for(std::size_t n, std::size_t max_workers, const std::function<void(std::size_t, std::size_t)>& task) {
  const std::size_t workers = std::min(std::max<std::size_t>(max_workers, 1), n);
  if (workers <= 1) {
    for (std::size_t i = 0; i < n; ++i) task(0, i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&](std::size_t worker) {
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
  };
  const Deadline deadline = current_deadline();
  std::vector<std::thread> threads;
  threads.reserve(workers - 1);
  for (std::size_t w = 1; w < workers; ++w)
    threads.emplace_back([&, w] {
      {
        const ScopedDeadline inherit(deadline);
        work(w);
      }
      flint_cleanup();  // this thread's FLINT/Arb caches (Gauss-Legendre nodes, ...)
    });
  work(0);
  for (auto& t : threads) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace uniparam
