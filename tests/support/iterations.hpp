// tests/support/iterations.hpp -- how many random cases a property test runs.
#pragma once

#include <cstdlib>

namespace uniparam::test_support {

/// base * UNIPARAM_TEST_MULTIPLIER (a positive integer, default 1), as Arb's
/// tests scale with ARB_TEST_MULTIPLIER: CI runs the base counts, a soak run
/// sets e.g. UNIPARAM_TEST_MULTIPLIER=20.
inline long iterations(long base) {
  const char* m = std::getenv("UNIPARAM_TEST_MULTIPLIER");
  const long k = m ? std::atol(m) : 1;
  return base * (k > 0 ? k : 1);
}

}  // namespace uniparam::test_support
