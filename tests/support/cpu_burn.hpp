// Test support: busy work measured in the calling thread's CPU time, for
// the tests of parallel_for's dispatch rule (which counts CPU time).
#pragma once

#include <time.h>

#include <cstdint>

namespace uniparam::test_support {

/// The calling thread's CPU time in nanoseconds (CLOCK_THREAD_CPUTIME_ID).
inline std::int64_t thread_cpu_ns() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

/// Busy work for about `ns` of the calling thread's CPU time (at least ns).
inline void burn(std::int64_t ns) {
  const std::int64_t until = thread_cpu_ns() + ns;
  volatile std::uint64_t x = 1;
  while (thread_cpu_ns() < until)
    for (int i = 0; i < 100; ++i) x = x * 6364136223846793005ULL + 1;
}

}  // namespace uniparam::test_support
