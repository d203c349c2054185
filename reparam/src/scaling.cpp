#include "uniparam/reparam/scaling.hpp"

#include <cmath>
#include <vector>

#include <flint/fmpz.h>

#include "moebius_map.hpp"

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

namespace {

// y = alpha x / (alpha x + beta (1 - x)) for the exact x (alpha, beta > 0).
Rational moebius_q(const Integer& alpha, const Integer& beta, const Rational& x) {
  const Rational p(alpha), q(beta);
  Rational y;
  detail::moebius_map(detail::RationalMapArith{}, &y, nullptr, nullptr, &x, &p, &q);
  return y;
}

// The image of x under y = alpha x / (alpha x + beta (1 - x)): its inverse
// is x = beta y / (beta y + alpha (1 - y)), so the root's polynomial f
// becomes f(beta y / L(y)) L(y)^deg f with L = alpha + (beta - alpha) y.
RealAlgebraic moebius_algebraic(const Integer& alpha, const Integer& beta, const RealAlgebraic& x) {
  if (x.is_rational()) return RealAlgebraic(moebius_q(alpha, beta, x.rational()));
  const Poly& f = x.poly();
  const Poly by(std::vector<Integer>{Integer(0), beta});
  const Poly L(std::vector<Integer>{alpha, beta - alpha});
  const Poly g = homogenized(f, f.degree(), by, L).primitive();
  return RealAlgebraic(g, moebius_q(alpha, beta, x.lo()), moebius_q(alpha, beta, x.hi()));
}

}  // namespace

RealAlgebraic balance_map(const BalancedCurve& bal, const RealAlgebraic& s) {
  return moebius_algebraic(bal.a, bal.b, s);
}

RealAlgebraic balance_unmap(const BalancedCurve& bal, const RealAlgebraic& t) {
  return moebius_algebraic(bal.b, bal.a, t);
}

namespace {

// D(s) = a s + b (1 - s) = b + (a - b) s as a sum of two positive terms.
Ball weight_at(const BalancedCurve& bal, const Ball& s, long prec) {
  Ball oms, d, t;
  arb_sub_si(oms.get(), s.get(), 1, prec);
  arb_neg(oms.get(), oms.get());
  arb_mul_fmpz(t.get(), oms.get(), bal.b.get(), prec);
  arb_mul_fmpz(d.get(), s.get(), bal.a.get(), prec);
  arb_add(d.get(), d.get(), t.get(), prec);
  return d;
}

}  // namespace

Ball balance_local_k(const BalancedCurve& bal, const RealAlgebraic& s0, const RealAlgebraic& s1, long prec) {
  if (s0.is_rational() && s1.is_rational()) return Ball(balance_local_k(bal, s0.rational(), s1.rational()), prec);
  const long p = prec + 16;
  Ball k;
  arb_div(k.get(), weight_at(bal, s1.to_ball(p), p).get(), weight_at(bal, s0.to_ball(p), p).get(), prec);
  return k;
}

Rational balance_local_k(const BalancedCurve& bal, const Rational& s0, const Rational& s1) {
  auto D = [&bal](const Rational& s) { return Rational(bal.a) * s + Rational(bal.b) * (Rational(1) - s); };
  return D(s1) / D(s0);
}

long balance_bits(const BalancedCurve& bal) {
  return std::labs(static_cast<long>(std::lround(log2_abs(bal.b) - log2_abs(bal.a))));
}

}  // namespace uniparam
