// Real algebraic numbers: exact rationals or a simple root of a squarefree
// integer polynomial in an isolating interval, refined on demand.
#include "uniparam/algebra/algebraic.hpp"

#include <arb.h>
#include <arb_fmpz_poly.h>
#include <mag.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <mutex>
#include <string>
#include <vector>

#include "root_refine.hpp"
#include "uniparam/core/ball_regions.hpp"
#include "uniparam/core/decimal.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

using detail::exact_sign;
using detail::floor_log2;

/// Largest refinement (bits) any loop here asks for before giving up.
constexpr long kMaxBits = 1L << 20;

/// Refinement short_interval asks for before it prints the current interval.
constexpr long kMaxShortIntervalBits = 1L << 14;

/// d*t - n for q = n/d (primitive, positive leading coefficient).
Poly linear_poly(const Rational& q) { return Poly(std::vector<Integer>{Integer(0) - q.num(), q.den()}); }

Rational abs(const Rational& x) { return x.sign() < 0 ? -x : x; }

/// Bits b with hi - lo <= 2^-b already (a starting point for refinement).
long current_bits(const RealAlgebraic& x) {
  if (x.is_rational()) return kMaxBits;
  return -floor_log2(x.hi() - x.lo());
}

/// Sign of x - q, exact.
int compare_rational(const RealAlgebraic& x, const Rational& q) {
  if (x.is_rational()) {
    const Rational& v = x.rational();
    return v < q ? -1 : (q < v ? 1 : 0);
  }
  if (q <= x.lo()) return 1;  // x > lo >= q
  if (x.hi() <= q) return -1;
  const int s = exact_sign(x.poly(), q);
  if (s == 0) return 0;  // unreachable for an irrational x
  // Same sign as at lo: the only root of poly in (lo, hi) lies in (q, hi).
  return s == exact_sign(x.poly(), x.lo()) ? 1 : -1;
}

}  // namespace

struct RealAlgebraic::Shared {
  Shared(Rational lo, Rational hi) : lo0(std::move(lo)), hi0(std::move(hi)) {}
  // The isolating interval the number was made with: poly has no root in
  // [lo0, hi0] but the number (short_interval). Never changes.
  const Rational lo0, hi0;
  std::mutex mu;
  Rational lo, hi;      // empty (lo == hi == 0) until a copy publishes
  long newton_log = 2;  // the refinement's Newton rate, continued by the next call
  std::shared_ptr<const ScaledEvaluator> sev;  // set at construction, then only read
};

RealAlgebraic::RealAlgebraic(const Rational& q) : poly_(linear_poly(q)), lo_(q), hi_(q) {}

RealAlgebraic::RealAlgebraic(const IsolatedRoot& r) { init(r, nullptr); }

namespace {

// The sign of lambda f(x) from sev's enclosure at 64 bits on a ball of
// radius 2^(kCoarseBallLog2 + 1) = 2^-23 around x, 0 when the enclosure does
// not exclude 0 (undecided). Certified as sev's contract is. The radius, as
// in the interval Newton steps (root_refine.cpp): a ball that is not wide
// (core/ball_regions.hpp) would make a factored evaluator build
// full-precision expansions near every end.
int evaluator_sign(const ScaledEvaluator& sev, const Rational& x) {
  arb_t X, v;
  arb_init(X);
  arb_init(v);
  arb_set_fmpq(X, x.get(), 64);
  // widened, not replaced: the rounding of a far x (|x| > 2^40) exceeds
  // 2^-23, and a ball without x could decide the wrong sign
  if (mag_cmp_2exp_si(arb_radref(X), kCoarseBallLog2 + 1) < 0) arb_add_error_2exp_si(X, kCoarseBallLog2 + 1);
  sev.ev(v, nullptr, X, 64);
  const int s = !arb_is_finite(v) ? 0 : arb_is_positive(v) ? 1 : arb_is_negative(v) ? -1 : 0;
  arb_clear(X);
  arb_clear(v);
  return s;
}

}  // namespace

void RealAlgebraic::init(const IsolatedRoot& r, const ScaledEvaluator* sev) {
  if (r.is_exact()) {
    poly_ = linear_poly(r.lo);
    lo_ = hi_ = r.lo;
    return;
  }
  if (!(r.lo < r.hi)) throw InvalidArgument("isolated root with empty interval [" + r.lo.str() + ", " + r.hi.str() + "]");
  Poly f = r.factor.primitive();
  if (f.degree() < 1) throw InvalidArgument("isolated root of a constant polynomial");
  // The ends must be no roots and f must change sign between them. An
  // evaluator of lambda f usually decides that at once (a high-degree f's
  // power basis costs far more: two exact signs of the degree-1633 critical
  // numerator per root at d = 150); the exact signs decide otherwise.
  bool checked = r.certified;  // proven by the isolator (real_roots.hpp)
  if (!checked && sev && sev->ev) {
    const int el = evaluator_sign(*sev, r.lo), eh = evaluator_sign(*sev, r.hi);
    checked = el != 0 && eh != 0 && el != eh;
  }
  if (!checked) {
    const int sl = exact_sign(f, r.lo), sh = exact_sign(f, r.hi);
    if (sl == 0 || sh == 0 || sl == sh)
      throw InvalidArgument("(" + r.lo.str() + ", " + r.hi.str() + ") is not an isolating interval of " + f.str());
  }
  if (f.degree() == 1) {  // rational after all: keep it exact
    const Rational q = -Rational(f.coeff(0)) / Rational(f.coeff(1));
    poly_ = linear_poly(q);
    lo_ = hi_ = q;
    return;
  }
  poly_ = std::move(f);
  lo_ = r.lo;
  hi_ = r.hi;
  shared_ = std::make_shared<Shared>(r.lo, r.hi);
}

RealAlgebraic::RealAlgebraic(const Poly& squarefree, const Rational& lo, const Rational& hi) {
  if (squarefree.degree() < 1) throw InvalidArgument("an algebraic number needs a polynomial of degree >= 1");
  if (!(lo < hi)) throw InvalidArgument("isolating interval (" + lo.str() + ", " + hi.str() + ") is empty");
  if (gcd(squarefree, squarefree.derivative()).degree() > 0)
    throw InvalidArgument(squarefree.str() + " is not squarefree");
  if (exact_sign(squarefree, lo) == 0 || exact_sign(squarefree, hi) == 0)
    throw InvalidArgument("an end of (" + lo.str() + ", " + hi.str() + ") is a root of " + squarefree.str());
  std::vector<IsolatedRoot> roots = isolate_real_roots(squarefree, lo, hi);
  if (roots.size() != 1)
    throw InvalidArgument("(" + lo.str() + ", " + hi.str() + ") holds " + std::to_string(roots.size()) +
                          " roots of " + squarefree.str() + ", not exactly one");
  const IsolatedRoot& r = roots.front();
  poly_ = r.is_exact() ? linear_poly(r.lo) : r.factor;  // the isolator makes rational roots exact
  lo_ = r.lo;
  hi_ = r.hi;
  if (!r.is_exact()) shared_ = std::make_shared<Shared>(lo, hi);
}

RealAlgebraic::RealAlgebraic(const IsolatedRoot& r, std::shared_ptr<const ScaledEvaluator> sev) {
  init(r, sev.get());
  if (shared_ && sev && sev->ev) shared_->sev = std::move(sev);
}

const Rational& RealAlgebraic::rational() const {
  if (!is_rational()) throw InvalidArgument("RealAlgebraic::rational() on the irrational " + str());
  return lo_;
}

void RealAlgebraic::refine(long bits) const {
  if (is_rational()) return;
  // Adopt what a copy refined (an empty shared interval: nothing published
  // yet), refine outside the lock, publish if narrower. Two copies may
  // refine at once; both results are isolating intervals of the same root.
  long newton_log = 2;
  if (shared_) {
    std::lock_guard<std::mutex> lock(shared_->mu);
    if (shared_->lo < shared_->hi && shared_->hi - shared_->lo <= hi_ - lo_) {
      lo_ = shared_->lo;
      hi_ = shared_->hi;
      newton_log = shared_->newton_log;
    }
  }
  if (hi_ - lo_ <= pow2(-bits)) return;
  // An exact hit (impossible for an irrational root) would leave lo == hi,
  // still a correct value.
  detail::refine_isolating_interval(poly_, lo_, hi_, bits, &newton_log, shared_ ? shared_->sev.get() : nullptr);
  if (shared_ && lo_ < hi_) {
    std::lock_guard<std::mutex> lock(shared_->mu);
    if (!(shared_->lo < shared_->hi) || hi_ - lo_ < shared_->hi - shared_->lo) {
      shared_->lo = lo_;
      shared_->hi = hi_;
      shared_->newton_log = newton_log;
    }
  }
}

Ball RealAlgebraic::to_ball(long prec) const {
  if (prec < 1) prec = 1;
  if (prec == ball_prec_) return ball_;
  Ball b;
  if (is_rational()) {
    b = Ball(lo_, prec + 4);
  } else {
    // Canonical: the ball of the grid cell [k, k + 1] 2^-p holding x, with
    // p = prec + 1 + e and k = floor(x 2^p) decided exactly, so the enclosure
    // depends on (x, prec) alone, never on earlier refinements (results do
    // not depend on the order of evaluations, e.g. on threads).
    // Radius 2^-(p + 1) = 2^-(prec + 2 + e) <= 2^-prec |x| / 2, with
    // e = small_shift() = max(0, -floor(log2 |x|)).
    const long p = prec + 1 + small_shift();
    // kToBallExtraBits - 1 bits beyond the grid: (lo, hi) then straddles a
    // grid point only with odds ~2^-10, so the exact comparison below (one
    // exact sign of the polynomial at a short dyadic, ~ one Arb evaluation)
    // is rare, and later calls at this or a lower precision need no
    // refinement. (Many more extra bits would cost a Newton step of refinement
    // on most roots of the critical numerators, for comparisons that are cheap.)
    refine(p - 1 + kToBallExtraBits);
    fmpz_t klo, khi;
    fmpz_init(klo);
    fmpz_init(khi);
    Rational t = lo_ * pow2(p);
    fmpz_fdiv_q(klo, fmpq_numref(t.get()), fmpq_denref(t.get()));
    t = hi_ * pow2(p);
    fmpz_fdiv_q(khi, fmpq_numref(t.get()), fmpq_denref(t.get()));
    if (!fmpz_equal(klo, khi)) {
      // hi - lo <= 2^-(p+2): one grid point g = khi 2^-p in (lo, hi]
      Integer kh;
      fmpz_set(kh.get(), khi);
      const Rational g = Rational(kh) * pow2(-p);
      if (compare_rational(*this, g) >= 0) fmpz_set(klo, khi);
    }
    // midpoint (2k + 1) 2^-(p+1), radius 2^-(p+1)
    fmpz_mul_2exp(klo, klo, 1);
    fmpz_add_ui(klo, klo, 1);
    arb_set_fmpz(b.get(), klo);
    arb_mul_2exp_si(b.get(), b.get(), -(p + 1));
    mag_set_ui_2exp_si(arb_radref(b.get()), 1, -(p + 1));
    fmpz_clear(klo);
    fmpz_clear(khi);
  }
  ball_ = b;
  ball_prec_ = prec;
  return b;
}

long RealAlgebraic::small_shift() const {
  if (small_shift_ >= 0) return small_shift_;
  sign();  // now 0 is not inside (lo, hi) (it may be an end)
  for (long b = std::max(8L, current_bits(*this)); lo_.is_zero() || hi_.is_zero(); b *= 2) {
    if (b > kMaxBits) throw BudgetExceeded("could not bound " + str() + " away from 0");
    refine(b);
  }
  // |x| in (m, M): floor(log2 |x|) is in [floor_log2(m), floor_log2(M)],
  // decided by exact comparisons with the powers of 2 in between (x is
  // irrational: never equal to one).
  const int s = lo_.sign() > 0 ? 1 : -1;
  const Rational m = std::min(abs(lo_), abs(hi_)), M = std::max(abs(lo_), abs(hi_));
  long e = floor_log2(m);
  const long e_hi = floor_log2(M);
  while (e < 0 && e < e_hi && s * compare_rational(*this, Rational(s) * pow2(e + 1)) > 0) ++e;
  small_shift_ = std::max(0L, -e);
  return small_shift_;
}

int RealAlgebraic::sign() const {
  const int s = compare_rational(*this, Rational(0));
  // 0 separates the interval: keep the half holding the number (0 is not a
  // root of poly_ there, since the number is irrational).
  if (!is_rational() && lo_.sign() < 0 && hi_.sign() > 0) {
    if (s > 0) lo_ = Rational(0);
    else hi_ = Rational(0);
  }
  return s;
}

std::string RealAlgebraic::decimal(long digits) const {
  if (digits < 1) throw InvalidArgument("decimal: at least one significant digit is needed");
  if (is_rational()) return decimal_string(lo_, digits);
  sign();  // now 0 is not in [lo, hi] (0 may be an end)
  for (long b = std::max(8L, current_bits(*this)); lo_.is_zero() || hi_.is_zero(); b *= 2) {
    if (b > kMaxBits) throw BudgetExceeded("could not bound " + str() + " away from 0");
    refine(b);
  }
  if (is_rational()) return decimal_string(lo_, digits);
  const Rational m = std::min(abs(lo_), abs(hi_));
  // width <= m 10^-digits / 16: with the rounding of the midpoint the
  // printed value is within one unit of its last digit.
  refine(-floor_log2(m) + digits * 3322 / 1000 + 6);
  if (is_rational()) return decimal_string(lo_, digits);
  return decimal_string((lo_ + hi_) * Rational(1, 2), digits);
}

std::pair<Rational, Rational> RealAlgebraic::short_interval() const {
  if (is_rational()) return {lo_, lo_};
  const Rational& lo0 = shared_->lo0;
  const Rational& hi0 = shared_->hi0;
  // Start at the widest cell that could fit: 10^-d <= hi0 - lo0 < 2^(e + 1)
  // needs d > -(e + 1) log10(2) (d0 below is at most that).
  const long e = floor_log2(hi0 - lo0);
  long d = (e >= 0 ? -(e * 30103) / 100000 : ((-e) * 30103 + 99999) / 100000) - 1;
  const Rational ten(10);
  fmpz_t k, khi;
  fmpz_init(k);
  fmpz_init(khi);
  for (;; ++d) {
    const long bits = static_cast<long>(std::ceil(static_cast<double>(d) * 3.3219280948873623)) + 2;
    if (bits > kMaxShortIntervalBits) break;
    // h = 10^-d; k = floor(x / h), decided on an interval narrower than h
    // (with one exact sign at the grid point when it straddles one).
    Rational h(1);
    for (long i = 0; i < (d < 0 ? -d : d); ++i) h = h * ten;
    if (d > 0) h = Rational(1) / h;
    refine(bits);  // hi - lo <= 2^-bits <= h / 4
    Rational t = lo_ / h;
    fmpz_fdiv_q(k, fmpq_numref(t.get()), fmpq_denref(t.get()));
    t = hi_ / h;
    fmpz_fdiv_q(khi, fmpq_numref(t.get()), fmpq_denref(t.get()));
    if (!fmpz_equal(k, khi)) {
      Integer g;
      fmpz_set(g.get(), khi);
      if (compare_rational(*this, Rational(g) * h) > 0) fmpz_set(k, khi);
    }
    Integer ki;
    fmpz_set(ki.get(), k);
    const Rational L = Rational(ki) * h, H = L + h;
    if (lo0 <= L && H <= hi0) {
      fmpz_clear(k);
      fmpz_clear(khi);
      return {L, H};
    }
  }
  fmpz_clear(k);
  fmpz_clear(khi);
  return {lo_, hi_};
}

std::string RealAlgebraic::str() const {
  if (is_rational()) return lo_.str();
  return "root of " + poly_.str() + " in [" + lo_.str() + ", " + hi_.str() + "]";
}

int compare(const RealAlgebraic& x, const RealAlgebraic& y) {
  if (x.is_rational()) return -compare_rational(y, x.rational());
  if (y.is_rational()) return compare_rational(x, y.rational());
  // Copies of one number (they share its refinement state): equal without
  // any algebra. Caches keyed by an algebraic number (LocalPoly's deflated
  // variants) look their key up this way thousands of times per quadrature.
  if (x.shared_ && x.shared_ == y.shared_) return 0;
  if (x.hi() <= y.lo()) return -1;
  if (y.hi() <= x.lo()) return 1;
  // Overlap: x == y iff gcd(x.poly, y.poly) has a root in the intersection
  // (L, H). Its ends are non-roots of one of the polys, hence of g, and g has
  // at most one (simple) root there: a sign change decides. (Both polys are
  // squarefree and primitive with positive leading coefficient: equal ones
  // are their own gcd.)
  const Rational L = std::max(x.lo(), y.lo()), H = std::min(x.hi(), y.hi());
  const Poly g = x.poly() == y.poly() ? x.poly() : gcd(x.poly(), y.poly());
  if (g.degree() >= 1 && exact_sign(g, L) != exact_sign(g, H)) return 0;
  // Distinct: refine both until the intervals separate.
  for (long b = std::max(8L, std::max(current_bits(x), current_bits(y)) + 1); b <= kMaxBits; b *= 2) {
    x.refine(b);
    y.refine(b);
    if (x.is_rational() || y.is_rational()) return compare(x, y);
    if (x.hi() <= y.lo()) return -1;
    if (y.hi() <= x.lo()) return 1;
  }
  throw BudgetExceeded("could not separate " + x.str() + " and " + y.str() + " within " + std::to_string(kMaxBits) +
                       " bits");
}

int sign_at(const Poly& p, const RealAlgebraic& x) {
  if (p.is_zero()) return 0;
  if (x.is_rational()) return exact_sign(p, x.rational());
  const Poly g = gcd(p, x.poly());  // divides x.poly: lo, hi are not its roots
  if (g.degree() >= 1 && exact_sign(g, x.lo()) != exact_sign(g, x.hi())) return 0;
  // p(x) != 0: evaluate on shrinking enclosures until the sign is certain.
  for (long b = std::max(64L, current_bits(x)); b <= kMaxBits; b *= 2) {
    x.refine(b);
    if (x.is_rational()) return exact_sign(p, x.rational());
    const long prec = b + 32 + p.max_bits();
    const Ball xb = interval_ball(x.lo(), x.hi(), prec);
    Ball v;
    arb_fmpz_poly_evaluate_arb(v.get(), p.get(), xb.get(), prec);
    if (v.certainly_positive()) return 1;
    if (v.certainly_negative()) return -1;
  }
  throw BudgetExceeded("could not certify the sign of " + p.str() + " at " + x.str() + " within " +
                       std::to_string(kMaxBits) + " bits");
}

}  // namespace uniparam
