// tests/support/de_boor.hpp -- an independent exact evaluator of NURBS curves,
// the oracle of the NURBS tests.
#pragma once

#include <vector>

#include "uniparam/core/number.hpp"

namespace uniparam::test_support {

/// The NURBS curve of degree p >= 1 with knots U (clamped, nondecreasing),
/// control points P and positive weights w (|U| = |P| + p + 1 = |w| + p + 1),
/// at s in [U[p], U[|P|]], exactly: de Boor's algorithm on the homogeneous
/// points (w P, w), in the span U[k] <= s < U[k+1] (the last nonempty span
/// for the last knot).
inline std::vector<Rational> de_boor(long p, const std::vector<Rational>& U, const std::vector<std::vector<Rational>>& P,
                                     const std::vector<Rational>& w, const Rational& s) {
  const long m = static_cast<long>(P.size());
  long k = p;
  while (k + 1 < m && U[k + 1] <= s) ++k;
  std::vector<std::vector<Rational>> d;
  for (long j = 0; j <= p; ++j) {
    const long i = j + k - p;
    std::vector<Rational> h;
    for (const auto& x : P[i]) h.push_back(x * w[i]);
    h.push_back(w[i]);
    d.push_back(h);
  }
  for (long r = 1; r <= p; ++r)
    for (long j = p; j >= r; --j) {
      const long i = j + k - p;
      const Rational a = (s - U[i]) / (U[i + p - r + 1] - U[i]);
      for (std::size_t c = 0; c < d[j].size(); ++c) d[j][c] = (Rational(1) - a) * d[j - 1][c] + a * d[j][c];
    }
  std::vector<Rational> out;
  for (std::size_t c = 0; c + 1 < d[p].size(); ++c) out.push_back(d[p][c] / d[p].back());
  return out;
}

}  // namespace uniparam::test_support
