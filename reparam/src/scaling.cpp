#include "uniparam/reparam/scaling.hpp"

#include <cmath>
#include <vector>

#include <flint/fmpz.h>

namespace uniparam {

namespace {

// log2 |x| for x != 0, in double (exponents of any size).
double log2_abs(const Integer& x) {
  slong e = 0;
  const double m = fmpz_get_d_2exp(&e, x.get());
  return std::log2(std::fabs(m)) + static_cast<double>(e);
}

// P(m(s)) (a s + b (1 - s))^n for deg P <= n: sum_j P_j (a s)^j L(s)^(n - j)
// with L(s) = b + (a - b) s, by Horner's rule in a s (r = P_n, then
// r = r a s + P_j L^(n - j) for j = n - 1, ..., 0).
Poly homogenized(const Poly& p, long n, const Poly& as, const Poly& L) {
  Poly r(0), Lk(1);
  for (long j = n; j >= 0; --j) {
    const Poly c(std::vector<Integer>{j <= p.degree() ? p.coeff(j) : Integer(0)});
    r = r * as + c * Lk;
    Lk = Lk * L;
  }
  return r;
}

}  // namespace

std::optional<BalancedCurve> balance(const Curve& p) {
  // W: the least common denominator of the components.
  Poly W(1);
  for (const RatFunc& c : p.components()) W = divexact(W * c.den(), gcd(W, c.den()));
  const long n = W.degree();
  if (n < 1) return std::nullopt;
  const Integer w0 = W.coeff(0);
  Integer w1(0);
  for (long i = 0; i <= n; ++i) w1 = w1 + W.coeff(i);
  if (w0.sign() == 0 || w1.sign() == 0) return std::nullopt;  // a pole at an end: not a curve
  const double k = std::nearbyint((log2_abs(w1) - log2_abs(w0)) / static_cast<double>(n));
  if (!(std::fabs(k) >= 16) || !std::isfinite(k)) return std::nullopt;
  Integer a(1), b(1), two_k(1);
  fmpz_mul_2exp(two_k.get(), two_k.get(), static_cast<ulong>(std::fabs(k)));
  (k > 0 ? b : a) = two_k;
  const Poly as(std::vector<Integer>{Integer(0), a});
  const Poly L(std::vector<Integer>{b, a - b});
  std::vector<RatFunc> q;
  for (const RatFunc& c : p.components()) {
    const long nc = std::max(c.num().degree(), c.den().degree());
    q.emplace_back(homogenized(c.num(), nc, as, L), homogenized(c.den(), nc, as, L));
  }
  return BalancedCurve{Curve(std::move(q)), a, b};
}

}  // namespace uniparam
