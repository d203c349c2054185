// tests/reparam/speed_eval_support.hpp -- random exact curves shared by the
// speed evaluation tests (test_speed_eval.cpp, test_speed_exact.cpp).
#pragma once

#include <random>
#include <vector>

#include "uniparam/reparam/all.hpp"

namespace uniparam::speed_eval_test {

// sum_k P_k C(d,k) t^k (1-t)^(d-k), exactly.
inline Poly bernstein(const std::vector<long>& P) {
  const long d = static_cast<long>(P.size()) - 1;
  Poly acc(0), omt = Poly(1) - Poly::t();
  Integer binom(1);
  for (long k = 0; k <= d; ++k) {
    if (k > 0) {
      fmpz_mul_ui(binom.get(), binom.get(), static_cast<ulong>(d - k + 1));
      fmpz_divexact_ui(binom.get(), binom.get(), static_cast<ulong>(k));
    }
    Integer c;
    fmpz_mul_si(c.get(), binom.get(), P[static_cast<std::size_t>(k)]);
    acc = acc + Poly(std::vector<Integer>{c}) * Poly::t().pow(static_cast<ulong>(k)) * omt.pow(static_cast<ulong>(d - k));
  }
  return acc;
}

inline Curve random_bezier(std::mt19937_64& rng, long d, std::size_t dim, bool rational) {
  std::uniform_int_distribution<long> coord(-50, 50), weight(1, 4);
  std::vector<long> w;
  for (long k = 0; k <= d; ++k) w.push_back(rational ? weight(rng) : 1);
  const Poly W = bernstein(w);
  std::vector<RatFunc> comps;
  for (std::size_t i = 0; i < dim; ++i) {
    std::vector<long> P;
    for (long k = 0; k <= d; ++k) P.push_back(w[static_cast<std::size_t>(k)] * (i == 0 ? 20 * k : coord(rng)));
    comps.emplace_back(bernstein(P), W);
  }
  return Curve(comps);
}


}  // namespace uniparam::speed_eval_test
