// tests/support/curves.hpp -- helpers shared by the test executables:
// random rational curves and exact composition with a reparameterization.
#pragma once

#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/core/poly.hpp"
#include "uniparam/core/ratfunc.hpp"

namespace uniparam::test_support {

/// Random polynomial of exact degree `deg` with coefficients in [-bound, bound].
inline Poly random_poly(std::mt19937_64& rng, long deg, long bound) {
  std::uniform_int_distribution<long> d(-bound, bound);
  std::vector<long> c(static_cast<std::size_t>(deg + 1));
  for (auto& x : c) x = d(rng);
  if (c.back() == 0) c.back() = 1;
  return Poly(c);
}

/// f(r) for a rational function f and r in Q(s): exact composition.
inline RatFunc compose(const RatFunc& f, const RatFunc& r) {
  auto poly_at = [&](const Poly& p) {
    RatFunc acc(0);
    for (long i = p.degree(); i >= 0; --i) acc = acc * r + RatFunc(Rational(p.coeff(i)));
    return acc;
  };
  return poly_at(f.num()) / poly_at(f.den());
}

}  // namespace uniparam::test_support
