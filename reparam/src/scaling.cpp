#include "uniparam/reparam/scaling.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <flint/fmpz.h>
#include <flint/fmpz_poly.h>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/algebra/newton_polygon.hpp"
#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/reparam/speed.hpp"
#include "uniparam/reparam/uniformity.hpp"

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

namespace {

// q = p o m with m(s) = a s / (a s + b (1 - s)), lambda = b / a = 2^k (k != 0).
BalancedCurve balanced_by(const Curve& p, long k) {
  Integer a(1), b(1), two_k(1);
  fmpz_mul_2exp(two_k.get(), two_k.get(), static_cast<ulong>(std::labs(k)));
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

// The tropical polynomials of the speed's factors (Newton polygons).
using Tropical = NewtonPolygon;

// The x >= 0 maximising the estimated mass 2^(T_g(x) + max_k T_K_k(x) -
// T_D(x) - x) of the band [2^-x-1, 2^-x] (the smallest maximiser among the
// breakpoints and 0, where a piecewise linear function takes its maximum;
// the last slope is negative: sigma is integrable at 0).
double mass_peak(const Poly& g, const std::vector<Poly>& K, const Poly& D) {
  Tropical Tg(g), TD(D);
  std::vector<Tropical> TK;
  for (const Poly& k : K)
    if (!k.is_zero()) TK.emplace_back(k);
  std::vector<double> xs{0.0};
  Tg.breakpoints(xs);
  TD.breakpoints(xs);
  for (const Tropical& t : TK) t.breakpoints(xs);
  std::sort(xs.begin(), xs.end());
  double best_x = 0, best = -HUGE_VAL;
  for (const double x : xs) {
    double k_max = -HUGE_VAL;
    for (Tropical& t : TK) k_max = std::max(k_max, t(x));
    const double m = Tg(x) + k_max - TD(x) - x;
    if (m > best) {
      best = m;
      best_x = x;
    }
  }
  return best_x;
}

// P(1 + t), whose coefficients' sizes are those of P(1 - t).
Poly shifted_to_one(const Poly& P) {
  Poly r;
  fmpz_t one;
  fmpz_init_set_ui(one, 1);
  fmpz_poly_taylor_shift(r.get(), P.get(), one);
  fmpz_clear(one);
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
  return balanced_by(p, static_cast<long>(k));
}

namespace {

// Speed::scale_bits without g: a certified d with no pole or branch point
// of sigma (a root of D or sum K_k^2) within 2^-d of 0 or 1 other than at
// the end itself. The roots of g are zeros of the polynomial factor of
// sigma = |g| sqrt(sum K^2) / D, which is analytic at them (a real one in
// [0, 1] is a zero every integral splits at), so they cost a quadrature
// nothing: (t, C t^3) balanced at 0 has q's g vanish next to s = 1, where
// m brings t = infinity, while q is as easy to integrate as any curve.
long singularity_depth_bits(const Speed& s) {
  long d = 0;
  for (const Poly* P : {&s.denominator(), &s.cofactor_square_sum()})
    if (P->degree() >= 1) d = std::max(d, end_root_depth_bits(*P));
  return d;
}

// Bits from which a concentration of mass (an end's, mass_peak; an
// interior feature's, append_features) is balanced or split off.
constexpr double kMinBits = 16;

// mass_peak at 0 and at 1 (x0, x1).
void end_mass_peaks(const Speed& s, double& x0, double& x1) {
  x0 = mass_peak(s.g(), s.cofactors(), s.denominator());
  std::vector<Poly> K1;
  for (const Poly& k : s.cofactors()) K1.push_back(shifted_to_one(k));
  x1 = mass_peak(shifted_to_one(s.g()), K1, shifted_to_one(s.denominator()));
}

}  // namespace

std::optional<BalancedCurve> balance(const Curve& p, const Speed& s) {
  if (std::optional<BalancedCurve> w = balance(p)) return w;
  if (s.identically_zero()) return std::nullopt;
  double x0 = 0, x1 = 0;
  end_mass_peaks(s, x0, x1);
  const bool at0 = x0 >= kMinBits, at1 = x1 >= kMinBits;
  if (at0 == at1) return std::nullopt;
  const double x = at0 ? x0 : x1;
  if (!std::isfinite(x) || x > 1e15) return std::nullopt;
  const long k = std::lround(x);
  BalancedCurve bal = balanced_by(p, at0 ? k : -k);
  // m takes t = infinity to s = b / (b - a), within 2^-|k| of an end:
  // features of p far from [0, 1] (a root of D or sum K^2 at |t| ~ 2^j)
  // come within about 2^-(|k| + j) of that end. Balanced only where q's
  // nearest singularity is farther from the ends than p's.
  if (!(singularity_depth_bits(Speed(bal.q, s.kind())) + kMinBits <= singularity_depth_bits(s))) return std::nullopt;
  return bal;
}

namespace {

// A feature of sigma inside (0, 1): a point c where the roots of one of
// the factored form's polynomials come within 2^-depth of the real line.
struct Feature {
  Rational c;
  long depth;
};

// For each real critical point of P in (0, 1) (a near-real pair of roots
// a +- i e of P has one within about e^2 of a): a rational c within
// 2^-(depth + 8) of it, where depth = root_depth_bits of P about c (no root
// of P other than c lies within 2^-depth of c), appended to out where depth
// >= kMinBits and c lies farther than 2^(8 - depth) from both ends (an
// end's concentration is balance()'s).
void append_features(const Poly& P, std::vector<Feature>& out) {
  if (P.degree() < 2) return;
  for (const IsolatedRoot& root : isolate_real_roots(P.derivative(), Rational(0), Rational(1))) {
    const RealAlgebraic r(root);
    Rational c;
    long depth = 0;
    for (long bits = 64, it = 0; it < 16; ++it) {
      if (r.is_rational()) {
        c = r.rational();
      } else {
        r.refine(bits + 2);
        c = grid_floor((r.lo() + r.hi()) * Rational(1, 2), -bits);
      }
      depth = root_depth_bits(mapped_to_unit_interval(P, c, c + Rational(1)));  // P(c + u), scaled
      if (r.is_rational() || depth + 8 <= bits) break;
      // c is within 2^-bits of the critical point, and the roots about it
      // are at least that close: doubled, so a feature 2^-1000 wide is
      // reached in a few rounds (by 16 bits a round, 16 rounds stopped at
      // about 2^-320, off the feature by 2^680 of its widths)
      bits = std::max(depth + 16, 2 * bits);
    }
    if (depth < kMinBits) continue;
    const Rational margin = pow2(8 - depth);
    if (c <= margin || c >= Rational(1) - margin) continue;
    out.push_back({c, depth});
  }
}

}  // namespace

bool peak_split_searched(const Speed& s) {
  if (s.identically_zero()) return false;
  // From the degrees alone (deg sum K^2 <= 2 max deg K_k): sum K^2 is built
  // only for a curve that is searched.
  long max_degree = std::max(s.g().degree(), s.denominator().degree());
  for (const Poly& k : s.cofactors()) max_degree = std::max(max_degree, 2 * k.degree());
  return speed_coefficient_bits(s) >= kPeakCoefficientBitsPerDegree * max_degree + kPeakCoefficientBits;
}

std::optional<PeakSplit> peak_split(const Speed& s) {
  if (!peak_split_searched(s)) return std::nullopt;
  const Poly* polys[] = {&s.g(), &s.denominator(), &s.cofactor_square_sum()};
  std::vector<Feature> found;
  for (const Poly* P : polys) append_features(*P, found);
  double x0 = 0, x1 = 0;
  end_mass_peaks(s, x0, x1);
  const bool at0 = x0 >= kMinBits, at1 = x1 >= kMinBits;
  if (found.empty() && !(at0 && at1)) return std::nullopt;
  std::sort(found.begin(), found.end(), [](const Feature& a, const Feature& b) { return a.c < b.c; });
  // One feature of several polynomials (a pole of sigma where a branch
  // point is too) is one split point: the deeper one's.
  std::vector<Feature> features;
  for (const Feature& f : found) {
    if (!features.empty() && f.c - features.back().c <= pow2(8 - std::min(f.depth, features.back().depth))) {
      if (f.depth > features.back().depth) features.back() = f;
      continue;
    }
    features.push_back(f);
  }
  // Every part with a concentration at both ends is halved.
  PeakSplit out;
  const auto add = [&out](const Rational& k, bool feature) {
    out.knots.push_back(k);
    out.feature.push_back(feature);
  };
  add(Rational(0), at0);
  for (const Feature& f : features) {
    if (out.feature.back()) add((out.knots.back() + f.c) * Rational(1, 2), false);
    add(f.c, true);
  }
  if (out.feature.back() && at1) add((out.knots.back() + Rational(1)) * Rational(1, 2), false);
  add(Rational(1), at1);
  return out;
}

Curve restrict_to(const Curve& p, const Rational& a, const Rational& b) {
  const Rational h = b - a;
  if (h.sign() == 0) throw InvalidArgument("restrict_to: the interval is a point");
  // a + h u = (a_n h_d + h_n a_d u) / (a_d h_d)
  const Poly num(std::vector<Integer>{a.num() * h.den(), h.num() * a.den()});
  const Poly den(std::vector<Integer>{a.den() * h.den()});
  const RatFunc L(num, den);
  std::vector<RatFunc> q;
  for (const RatFunc& c : p.components()) q.push_back(compose(c, L));
  return Curve(std::move(q));
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

Ball balance_map_ball(const BalancedCurve& bal, const Ball& s, long prec) {
  if (!s.is_finite()) throw DomainError("balance_map_ball: the parameter is not finite");
  arf_t lo, hi;
  arf_init(lo);
  arf_init(hi);
  arb_get_lbound_arf(lo, s.get(), prec);
  arb_get_ubound_arf(hi, s.get(), prec);
  const bool outside = arf_cmp_si(hi, 0) < 0 || arf_cmp_si(lo, 1) > 0;
  if (arf_sgn(lo) < 0) arf_zero(lo);
  if (arf_cmp_si(hi, 1) > 0) arf_one(hi);
  auto m_at = [&](const arf_t x) {
    Ball as, bs, d;
    arb_set_arf(as.get(), x);
    arb_sub_si(bs.get(), as.get(), 1, prec);
    arb_neg(bs.get(), bs.get());
    arb_mul_fmpz(bs.get(), bs.get(), bal.b.get(), prec);
    arb_mul_fmpz(as.get(), as.get(), bal.a.get(), prec);
    arb_add(d.get(), as.get(), bs.get(), prec);
    arb_div(as.get(), as.get(), d.get(), prec);
    return as;
  };
  Ball out;
  if (!outside) arb_union(out.get(), m_at(lo).get(), m_at(hi).get(), prec);
  arf_clear(lo);
  arf_clear(hi);
  if (outside) throw DomainError("balance_map_ball: the parameter is outside [0, 1]");
  return out;
}

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
