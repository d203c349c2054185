// tests/support/iterations.hpp -- the random cases of a property test: how
// many it runs, the seed, and random decimal integers.
#pragma once

#include <cstdlib>
#include <random>
#include <string>

#include "uniparam/core/number.hpp"

namespace uniparam::test_support {

/// base * UNIPARAM_TEST_MULTIPLIER (a positive integer, default 1), as Arb's
/// tests scale with ARB_TEST_MULTIPLIER: CI runs the base counts, a soak run
/// sets e.g. UNIPARAM_TEST_MULTIPLIER=20.
inline long iterations(long base) {
  const char* m = std::getenv("UNIPARAM_TEST_MULTIPLIER");
  const long k = m ? std::atol(m) : 1;
  return base * (k > 0 ? k : 1);
}

/// The seed of a property test: UNIPARAM_TEST_SEED when set (to rerun a
/// failure printed with its seed), else the test's own fixed `fallback`.
inline unsigned test_seed(unsigned fallback) {
  const char* s = std::getenv("UNIPARAM_TEST_SEED");
  return s ? static_cast<unsigned>(std::strtoul(s, nullptr, 10)) : fallback;
}

/// A string of 1 to max_len random decimal digits (leading zeros allowed).
inline std::string random_digits(std::mt19937_64& rng, int max_len) {
  std::uniform_int_distribution<int> len(1, max_len), dig(0, 9);
  std::string s;
  for (int i = len(rng); i > 0; --i) s += static_cast<char>('0' + dig(rng));
  return s;
}

/// A string of exactly `digits` random decimal digits, the first nonzero: a
/// positive integer of that many digits (e.g. a huge coefficient C).
template <class Rng>
std::string random_positive_digits(Rng& rng, int digits) {
  std::string s(1, static_cast<char>('1' + rng() % 9));
  for (int i = 1; i < digits; ++i) s += static_cast<char>('0' + rng() % 10);
  return s;
}

/// A random rational k / den strictly inside (0, 1), den from 3 to 19 (a
/// feature's position with a small denominator).
template <class Rng>
Rational random_inner_rational(Rng& rng) {
  const long den = 3 + static_cast<long>(rng() % 17);
  return Rational(1 + static_cast<long>(rng() % static_cast<unsigned long>(den - 1)), den);
}

/// A random integer of 1 to max_digits decimal digits, either sign.
inline Integer random_integer(std::mt19937_64& rng, int max_digits) {
  const Integer v(random_digits(rng, max_digits));
  return (rng() & 1) ? Integer(0) - v : v;
}

}  // namespace uniparam::test_support
