#include "uniparam/reparam/speed.hpp"

#include <acb_poly.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>

#include "uniparam/algebra/approx_roots.hpp"
#include "uniparam/algebra/local_poly.hpp"
#include "uniparam/algebra/quadrature.hpp"
#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/core/cdisk.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/parallel.hpp"
#define UNIPARAM_SPEED_DD_ARITH
#include "speed_enclosure.hpp"
#include "speed_formula.hpp"

namespace uniparam {

std::string to_string(SpeedKind k) { return k == SpeedKind::Angular ? "angular" : "parametric"; }

SpeedKind parse_speed_kind(const std::string& s) {
  if (s == "angular") return SpeedKind::Angular;
  if (s == "parametric" || s == "arclength") return SpeedKind::Parametric;
  throw InvalidArgument("unknown speed '" + s + "' (expected 'angular', 'parametric' or 'arclength')");
}

namespace {

// eval_double_word: the largest working precision it serves (double words
// carry ~100 bits); the largest loss of Horner's rule on [0, 1] (an
// estimate, cancellation_bits) for which it is tried; and the largest
// degree of a component's N or Q. Horner's rule costs O(degree) double-word
// operations where the local expansions cost O(terms) balls: measured
// (callgrind and probe, one thread, 15 digits), dense-plane degree 50
// uniformity gained 25%, degree 100 lost 22%.
constexpr long kDDMaxPrec = 110;
constexpr double kDDMaxLoss = 24;
constexpr long kDDMaxDegree = 64;
// singularity_hints: the largest degree of D or sum K^2 whose roots are
// approximated (O(degree^2) per Aberth sweep).
constexpr long kHintMaxDegree = 128;
// ... and the most bits Horner's rule may lose near [0, 1] (the estimates
// of power_basis_loss on [0, 1] for p's power basis, of
// approximate_roots_near_unit_interval on [-1, 1] for the centred one):
// roots from double coefficients are only as good as Horner's rule there,
// and power bases that lose more give hints that would mislead.
constexpr double kHintMaxLoss = 30;

// ... and up to which p's own power basis is taken without trying the
// centred one (its hints then hold ~8 digits already).
constexpr double kHintGoodLoss = 12;

// The hints from p's roots (appended to out): from p's own power basis when
// it loses at most kHintGoodLoss bits on [0, 1], else from the one of p's
// and its power basis centred at 1/2 (approximate_roots_near_unit_interval)
// that loses fewer, if at most kHintMaxLoss. Bezier curves' bases lose ~n
// bits on [0, 1] (D and sum K^2 of bez-rat-space d = 12: 57 and > 100,
// centred 10 and 16), while dense curves' roots, near the
// unit circle, settle in far fewer sweeps on their own basis (3 M
// instructions a run against 19 M on dense-plane d = 50's D centred). False
// when neither basis is good enough.
bool append_hints(const Poly& p, std::vector<std::complex<double>>& out) {
  if (p.degree() <= 0) return true;
  const double own = power_basis_loss(p);
  if (own > kHintGoodLoss) {
    double loss = 0;
    const auto z = approximate_roots_near_unit_interval(p, std::min(kHintMaxLoss, own), &loss);
    if (loss <= std::min(kHintMaxLoss, own)) {  // else refused: below, or no hints
      out.insert(out.end(), z.begin(), z.end());
      return true;
    }
  }
  if (!(own <= kHintMaxLoss)) return false;
  const auto z = approximate_complex_roots(p);
  out.insert(out.end(), z.begin(), z.end());
  return true;
}

Poly gcd_all(const std::vector<Poly>& ps) {
  Poly g;
  for (const auto& p : ps) g = gcd(g, p);
  return g;
}

// A polynomial curve q with q' = c Y for a constant c > 0: q_i = c int_0^t
// Y_i, with c the least positive rational that makes every coefficient of
// every q_i an integer (c = lcm of the denominators k + 1, divided by the
// content common to all q_i). The angular speed of a curve depends only on
// the direction of its derivative (p' = h Y with a scalar h != 0 gives
// x'y'' - x''y' = h^2 (Y_1 Y_2' - Y_1' Y_2), |p'|^2 = h^2 |Y|^2), so q has the
// angular speed of every curve whose derivative is parallel to Y.
// \pre Y non-empty, not all zero.
std::vector<RatFunc> direction_curve(const std::vector<Poly>& Y) {
  long top = 0;
  for (const auto& y : Y) top = std::max(top, y.degree());
  fmpz_t l, c, k;
  fmpz_init_set_ui(l, 1);
  fmpz_init(c);
  fmpz_init(k);
  for (long i = 1; i <= top + 1; ++i) {
    fmpz_set_si(k, i);
    fmpz_lcm(l, l, k);
  }
  std::vector<Poly> q;
  for (const auto& y : Y) {
    Poly r;
    for (long i = 0; i <= y.degree(); ++i) {
      fmpz_poly_get_coeff_fmpz(c, y.get(), i);
      fmpz_mul(c, c, l);
      fmpz_divexact_si(c, c, i + 1);
      fmpz_poly_set_coeff_fmpz(r.get(), i + 1, c);
    }
    q.push_back(std::move(r));
  }
  fmpz_zero(c);
  for (const auto& r : q) {
    fmpz_poly_content(k, r.get());
    fmpz_gcd(c, c, k);
  }
  std::vector<RatFunc> out;
  for (auto& r : q) {
    if (!fmpz_is_zero(c) && !fmpz_is_one(c)) fmpz_poly_scalar_divexact_fmpz(r.get(), r.get(), c);
    out.emplace_back(r);
  }
  fmpz_clear(l);
  fmpz_clear(c);
  fmpz_clear(k);
  return out;
}



}  // namespace

namespace detail {
// Speed::eval_dd's components over one common denominator, x_i = M_i / L.
struct SpeedDD {
  std::vector<DDPoly> M;
  DDPoly L;
  bool unit_den = false;  // L == 1 (a polynomial curve)
  // The angular speed with L != 1: A_i = M_i' L - M_i L' as polynomials
  // (B_i = A_i'), where they are double words losing few bits: one Horner
  // pass for A_i and A_i' instead of M_i and L with two derivatives each and
  // four products. Empty otherwise; where it is not, M and L are empty
  // (they only had to pass the path's checks).
  std::vector<DDPoly> A;
};
}  // namespace detail

Speed::Speed(const Curve& c, SpeedKind kind) : kind_(kind) {
  const auto& X = c.derivative_numerators();
  std::vector<Poly> Y;
  // The curve whose components the evaluations take (comp_, dd_, piece_signs'
  // exact x', x''): the curve itself, except for the angular speed when the
  // numerators of p' share a factor of positive degree gx (a cusp where gx
  // has a real root). omega depends on the direction of p' only, and p' = (gx
  // / W) Y, so omega is that of the polynomial curve q with q' = Y (up to a
  // positive scale: direction_curve): the same speed with the factor
  // cancelled. The components of p itself would give 0/0 at every real root
  // of gx, and x'y'' - x''y' vanishes there while omega does not.
  std::vector<RatFunc> reduced;
  if (kind == SpeedKind::Angular) {
    Poly gx = gcd_all(X);
    for (const auto& x : X) Y.push_back(divexact(x, gx));
    if (gx.degree() > 0) reduced = direction_curve(Y);
  }
  const std::vector<RatFunc>& comps = reduced.empty() ? c.components() : reduced;
  // The exact x', x'' fix the sign of a plane curve's angular speed
  // (piece_signs); elsewhere they are not needed (and cost two exact
  // quotient rules on high-degree rational functions).
  const bool exact_derivatives = kind == SpeedKind::Angular && comps.size() == 2;
  for (const auto& x : comps) {
    Component k;
    Poly n = x.num(), q = x.den();
    k.N = LocalPoly(n);
    k.Q = LocalPoly(q);
    k.q_index = comp_.size();
    // Equal denominators (a rational curve's common weight) share one
    // LocalPoly's cache, and are evaluated once per ball (eval_derivatives).
    for (std::size_t e = 0; e < comp_.size(); ++e)
      if (comp_[e].Q.poly() == q) {
        k.Q = comp_[e].Q;
        k.q_index = comp_[e].q_index;
        break;
      }
    k.unit_den = q == Poly(1);
    if (exact_derivatives) {
      k.d1 = x.derivative();
      k.d2 = k.d1.derivative();
    }
    comp_.push_back(std::move(k));
  }
  {
    // The double-word path for the nodes (eval_double_word): only where
    // Horner's rule on the power basis keeps enough bits on [0, 1] (high
    // degree Bezier curves lose more than 24; the local expansions serve
    // them). The components over one common denominator L (the lcm of the
    // Q_i; L = 1 for a polynomial curve): x_i = M_i / L, M_i = N_i L / Q_i.
    auto dd = std::make_shared<detail::SpeedDD>();
    bool ok = comps.size() <= 3;  // eval_dd's bound
    Poly L(1);
    for (const auto& x : comps) {
      if (!ok) break;
      L = divexact(L * x.den(), gcd(L, x.den()));
      ok = L.degree() <= kDDMaxDegree;
    }
    std::vector<Poly> Ms;  // M_i, exactly
    for (const auto& x : comps) {
      if (!ok) break;
      Ms.push_back(x.num() * divexact(L, x.den()));
      ok = Ms.back().degree() <= kDDMaxDegree;
      if (ok) dd->M.emplace_back(Ms.back());
    }
    if (ok) {
      dd->unit_den = L == Poly(1);
      dd->L = DDPoly(L);
      ok = dd->L.usable() && dd->L.cancellation_bits() <= kDDMaxLoss;
    }
    for (const DDPoly& m : dd->M) ok = ok && m.usable() && m.cancellation_bits() <= kDDMaxLoss;
    if (ok && kind == SpeedKind::Angular && !dd->unit_den) {
      const Poly L1 = L.derivative();
      bool a_ok = true;
      for (const Poly& M : Ms) {
        const Poly A = M.derivative() * L - M * L1;
        if (!(a_ok = A.degree() <= kDDMaxDegree)) break;
        dd->A.emplace_back(A);
        a_ok = dd->A.back().usable() && dd->A.back().cancellation_bits() <= kDDMaxLoss;
        if (!a_ok) break;
      }
      if (!a_ok) dd->A.clear();
      if (a_ok) {  // speed_dd takes A_i alone: M_i and L only had to pass the checks above
        dd->M.clear();
        dd->L = DDPoly();
      }
    }
    if (ok) dd_ = std::move(dd);
  }
  // Two independent halves, side by side (the construction is serial
  // otherwise, ~10% of radical's time at degree 150): D and (parametric
  // speed) the check that it has no root in [0, 1]; the numerators N,
  // g = gcd(N), the cofactors K and g's zeros. Both are exact, so nothing
  // depends on the threads. An error (a root of D) is rethrown after both
  // have stopped.
  std::vector<Poly> N;
  parallel_for(2, std::min<std::size_t>(worker_count(), 2), [&](std::size_t, std::size_t task) {
    if (task == 0) {
      if (kind == SpeedKind::Angular) {
        D_ = Poly(0);
        for (const auto& y : Y) D_ = D_ + y * y;
        // No check needed: the Y_i = X_i / gcd(X) are coprime, so they have
        // no common complex zero and D = sum Y_i^2 > 0 on the whole real
        // line. (Its isolation on [0, 1] cost ~1% of dense-plane d=150
        // uniformity's instructions.)
        return;
      }
      D_ = c.derivative_denominator();
      // D must not vanish on [0, 1] (the speed would be infinite there).
      auto r = isolate_real_roots(D_, Rational(0), Rational(1));
      if (!r.empty()) {
        RealAlgebraic at(r.front());
        throw DomainError("the " + to_string(kind) + " speed is infinite at t = " + at.str() + " (t ~ " +
                          at.decimal(10) + "): the curve is not regular there");
      }
      return;
    }
    if (kind == SpeedKind::Angular) {
      for (std::size_t i = 0; i < Y.size(); ++i)
        for (std::size_t j = i + 1; j < Y.size(); ++j) {
          Poly e = Y[i].derivative() * Y[j] - Y[i] * Y[j].derivative();
          if (!e.is_zero()) N.push_back(std::move(e));
        }
    } else {
      for (const auto& x : X)
        if (!x.is_zero()) N.push_back(x);
    }
    if (N.empty()) return;  // angular speed of a straight line
    g_ = gcd_all(N).primitive();
    for (const auto& n : N) K_.push_back(divexact(n, g_));
    g_sqf_ = squarefree_factorization(g_);
    g_content_ = g_sqf_.content;
    for (const auto& f : g_sqf_.factors) {
      g_h_.emplace_back(f.factor);
      g_m_.push_back(f.multiplicity);
      for (const auto& r : isolate_real_roots(f.factor, Rational(0), Rational(1)))
        zeros_.push_back(SpeedZero{RealAlgebraic(r), f.multiplicity, g_h_.size() - 1});
    }
  });
  if (kind == SpeedKind::Angular)
    for (const auto& y : Y) Y_b_.emplace_back(y);
  else
    W_b_ = LocalPoly(D_);
  lazy_ = std::make_shared<Lazy>();
  if (N.empty()) {  // the second task stopped at once
    zero_ = true;
    g_ = Poly(0);
    return;
  }
  std::sort(zeros_.begin(), zeros_.end(), [](const SpeedZero& a, const SpeedZero& b) { return a.t < b.t; });
  for (std::size_t i = 0; i < zeros_.size(); ++i) zeros_[i].index = i;
  g_b_ = LocalPoly(g_);
  for (const auto& k : K_) K_b_.emplace_back(k);
  disk_form_ = true;
  for (const auto* v : {&Y_b_, &K_b_, &g_h_})
    for (const LocalPoly& q : *v) disk_form_ = disk_form_ && q.has_disk_form();
  if (kind == SpeedKind::Parametric) disk_form_ = disk_form_ && W_b_.has_disk_form();
  components_disk_form_ = !comp_.empty();
  for (const Component& k : comp_)
    components_disk_form_ = components_disk_form_ && k.N.has_disk_form() && (k.unit_den || k.Q.has_disk_form());
}

const RatFunc& Speed::squared() const {
  // Built on first use (only tests, callers of the API and the uniformity's
  // exact checks need it): the products and the canonical form cost ~10%
  // of the construction at degree 150. Copies share it; call_once makes the
  // first use thread-safe.
  std::call_once(lazy_->once, [this] {
    if (zero_) {
      lazy_->squared = RatFunc(0);
      return;
    }
    Poly sumK2(0);
    for (const auto& k : K_) sumK2 = sumK2 + k * k;
    lazy_->squared = RatFunc(g_ * g_ * sumK2, D_ * D_);
  });
  return lazy_->squared;
}

const std::vector<std::complex<double>>& Speed::singularity_hints(bool squared) const {
  std::call_once(lazy_->hints_once, [this] {
    if (zero_) return;
    long k = 0;
    for (const auto& c : K_) k = std::max(k, c.degree());
    if (D_.degree() > kHintMaxDegree || 2 * k > kHintMaxDegree) return;
    // sigma has a square root unless it is a plane curve's angular speed
    const bool root = !(kind_ == SpeedKind::Angular && comp_.size() == 2);
    // the poles and the branch points side by side (independent serial
    // iterations: the same hints on any number of threads)
    const bool branches = root && k > 0;
    std::vector<std::complex<double>> poles, branch;
    bool poles_ok = true, branch_ok = true;
    parallel_for(branches ? 2 : 1, std::min<std::size_t>(worker_count(), branches ? 2 : 1),
                 [&](std::size_t, std::size_t i) {
                   if (i == 0) {
                     poles_ok = append_hints(D_, poles);
                   } else {
                     Poly sumK2(0);
                     for (const auto& c : K_) sumK2 = sumK2 + c * c;
                     branch_ok = append_hints(sumK2, branch);
                   }
                 });
    if (!poles_ok) return;  // no hints rather than half of them
    lazy_->hints_squared = poles;
    lazy_->hints_sigma = std::move(poles);
    if (!branch_ok) lazy_->hints_sigma.clear();
    else lazy_->hints_sigma.insert(lazy_->hints_sigma.end(), branch.begin(), branch.end());
  });
  return squared ? lazy_->hints_squared : lazy_->hints_sigma;
}

Speed::PieceSigns Speed::piece_signs(const RealAlgebraic& a, const RealAlgebraic& b) const {
  if (!(a < b)) throw DomainError("piece_signs needs a < b");
  if (zero_) return PieceSigns{};
  // The interval between consecutive zeros of sigma that holds (a, b).
  std::size_t piece = 0;
  while (piece < zeros_.size() && !(a < zeros_[piece].t)) ++piece;
  if (piece < zeros_.size() && zeros_[piece].t < b)
    throw DomainError("piece_signs: the speed vanishes inside the piece");
  {
    std::lock_guard<std::mutex> lock(lazy_->signs_mutex);
    if (lazy_->signs.size() <= piece) lazy_->signs.resize(zeros_.size() + 1);
    if (lazy_->signs[piece].first) return lazy_->signs[piece].second;
  }
  const PieceSigns p = piece_signs_at(a, b);
  std::lock_guard<std::mutex> lock(lazy_->signs_mutex);
  lazy_->signs[piece] = {true, p};
  return p;
}

Speed::PieceSigns Speed::piece_signs_at(const RealAlgebraic& a, const RealAlgebraic& b) const {
  // A rational strictly between a and b: the simplest one in the middle half
  // of a rational interval between them (small numerator and denominator:
  // the exact signs below are cheap at it).
  Rational lo, hi;
  if (a.is_rational() && b.is_rational()) {
    lo = a.rational();
    hi = b.rational();
  } else {
    long bits = 8;
    a.refine(bits);
    b.refine(bits);
    while (!(a.hi() < b.lo())) {
      bits *= 2;
      if (bits > (1L << 16)) throw BudgetExceeded("could not separate two piece ends");
      a.refine(bits);
      b.refine(bits);
    }
    lo = a.hi();
    hi = b.lo();
  }
  const Rational quarter = (hi - lo) * Rational(1, 4);
  const Rational q = Rational::simplest_between(lo + quarter, hi - quarter);
  PieceSigns p;
  if (zero_) return p;
  const int sg = g_.sign_at(q), sd = D_.sign_at(q);
  if (sg == 0 || sd == 0) throw DomainError("piece_signs: the speed vanishes inside the piece");
  p.g = sg * sd;
  if (kind_ == SpeedKind::Angular && comp_.size() == 2) {
    Rational e = comp_[0].d1(q) * comp_[1].d2(q) - comp_[0].d2(q) * comp_[1].d1(q);
    if (e.sign() == 0) throw DomainError("piece_signs: the speed vanishes inside the piece");
    p.component = e.sign();
  }
  return p;
}

speed_formula::Form Speed::form() const {
  if (kind_ == SpeedKind::Parametric) return speed_formula::Form::Parametric;
  return comp_.size() == 2 ? speed_formula::Form::Plane : speed_formula::Form::Space;
}

void Speed::eval_derivatives(AcbBox* d1, AcbBox* d2, const acb_t z, long prec) const {
  using namespace speed_formula;
  const AcbArith ar{prec};
  AcbBox n, n1, n2, q, q1, q2, a, v, w;
  std::size_t q_done = comp_.size();  // index of the Q held in q, q1, q2, v, w
  for (std::size_t i = 0; i < comp_.size(); ++i) {
    const Component& k = comp_[i];
    if (k.unit_den) {  // a polynomial component: x' = N', x'' = N''
      k.N.eval(n, d1[i], d2 ? d2[i].get() : nullptr, z, prec);
      continue;
    }
    k.N.eval(n, n1, d2 ? n2.get() : nullptr, z, prec);
    if (k.q_index != q_done) {  // a rational curve's common weight: once
      k.Q.eval(q, q1, d2 ? q2.get() : nullptr, z, prec);
      ar.inv(v, q);  // v = 1 / Q (one division)
      ar.mul(w, v, v);
      q_done = k.q_index;
    }
    scaled_derivatives(ar, a, d2 ? &n2 : nullptr, n, n1, &n2, q, q1, &q2);
    quotient_derivatives(ar, d1[i], d2 ? d2 + i : nullptr, a, d2 ? &n2 : nullptr, q1, v, w);
  }
}

void Speed::eval_components(AcbBox& S, AcbBox& F, const acb_t z, long prec) const {
  using namespace speed_formula;
  const AcbArith ar{prec};
  const std::size_t n = comp_.size();
  const bool angular = kind_ == SpeedKind::Angular;
  bool common = angular && !comp_.empty() && !comp_[0].unit_den;
  for (const Component& k : comp_) common = common && k.q_index == comp_[0].q_index;
  std::vector<AcbBox> d(angular ? 2 * n : n);
  AcbBox* d1 = d.data();
  AcbBox* d2 = angular ? d1 + n : nullptr;
  if (common) {
    // One denominator Q (a rational curve's weight): with A_i = N_i' Q -
    // N_i Q' and B_i = N_i'' Q - N_i Q'' in place of x_i' and x_i''
    // (speed_formula.hpp), S and F come scaled by Q^4 and Q^8 (E by Q^4),
    // which sigma's ratios F / S^2, E / S do not see: no division by Q,
    // whose complex zeros (the curve's poles, not sigma's) no longer spoil
    // wide balls.
    AcbBox nv, n1, n2, q, q1, q2;
    comp_[0].Q.eval(q, q1, q2, z, prec);
    for (std::size_t i = 0; i < n; ++i) {
      comp_[i].N.eval(nv, n1, n2, z, prec);
      scaled_derivatives(ar, d1[i], d2 + i, nv, n1, &n2, q, q1, &q2);
    }
  } else {
    eval_derivatives(d1, d2, z, prec);
  }
  sum_of_squares(ar, S, n, [d1](std::size_t i) -> const AcbBox& { return d1[i]; });
  if (d2) cross_terms(ar, F, d1, d2, n);
}

void Speed::eval_g(AcbBox& out, const acb_t z, long prec, std::size_t skip) const {
  const AcbArith ar{prec};
  AcbBox content;
  acb_set_fmpz(content, g_content_.get());
  speed_formula::factored_g(
      ar, out, content, g_h_.size(), [&](std::size_t i, AcbBox& v) { g_h_[i].eval(v, z, prec); },
      [&](std::size_t i) { return g_m_[i]; }, skip);
}

bool Speed::eval_double_word(acb_t out, const acb_t z, const PieceSigns& p, bool squared, long prec) const {
  if (!dd_ || zero_ || prec > kDDMaxPrec || !arb_is_zero(acb_imagref(z)) ||
      mag_cmp_2exp_si(arb_radref(acb_realref(z)), -30) >= 0)
    return false;
  DDBall x, r;
  if (!dd_set_arb(x, acb_realref(z)) || !eval_dd(r, x, p, squared, prec)) return false;
  dd_get_arb(acb_realref(out), r);
  arb_zero(acb_imagref(out));
  return true;
}

namespace {

using namespace dd_detail;

// The angular (angular = true) or parametric speed, or its square, at the
// double-word ball x: Speed::eval_dd's arithmetic, with the operations of
// core/dd_inline.hpp inlined (F: the processor's FMA).
//
// With x_i = M_i / L: x_i' = A_i / L^2 and x_i'' = (B_i L - 2 L' A_i) / L^3
// for A_i = M_i' L - M_i L', B_i = A_i' = M_i'' L - M_i L''. So
//   sum x_i'^2 = S / L^4,                         S = sum A_i^2,
//   x_i' x_j'' - x_i'' x_j' = C_ij / L^4,         C_ij = A_i B_j - A_j B_i,
// and L cancels from the angular speed: sigma = sqrt(sum C_ij^2) / S
// (plane: C_12 / S, times the piece's sign); the parametric one is
// sqrt(S) / L^2. A polynomial curve (L = 1) has A_i = M_i', B_i = M_i''; a
// rational one's angular speed takes A_i and A_i' = B_i from A_i's own
// power basis where SpeedDD::A holds it.
// False where a ball is not finite, a divisor's ball holds 0 or a square
// root's holds a non-positive number.
template <bool F>
[[gnu::always_inline]] inline bool speed_dd(DDBall& out, const detail::SpeedDD& dd, bool angular, int sign,
                                            bool squared, const DDBall& x) {
  const bool direct = angular && !dd.A.empty();  // A_i and B_i = A_i' from their own polynomials
  const std::size_t n = direct ? dd.A.size() : dd.M.size();
  DDBall A[3], B[3];  // curves of up to 3 components take this path
  DDBall q, q1, q2;
  // Every polynomial value the speed needs, as lanes of one interleaved
  // Horner loop (DDPoly::eval_lanes): A_i, A_i' (direct); M_i', M_i''
  // (polynomial curves); or L, M_i and their first two derivatives.
  const DDPoly* lp[DDPoly::kMaxLanes];
  int lj[DDPoly::kMaxLanes];
  DDBall* lo[DDPoly::kMaxLanes];
  DDBall m[3][3];  // the general case's M_i, M_i', M_i''
  int k = 0;
  auto lane = [&](const DDPoly& poly, int deriv, DDBall* o) {
    lp[k] = &poly;
    lj[k] = deriv;
    lo[k++] = o;
  };
  const int top = angular ? 2 : 1;  // the highest derivative of M_i and L needed
  if (!direct && !dd.unit_den)
    for (int d = 0; d <= top; ++d) lane(dd.L, d, d == 0 ? &q : d == 1 ? &q1 : &q2);
  for (std::size_t i = 0; i < n; ++i) {
    if (direct) {
      lane(dd.A[i], 0, A + i);
      lane(dd.A[i], 1, B + i);
    } else if (dd.unit_den) {
      lane(dd.M[i], 1, A + i);
      if (angular) lane(dd.M[i], 2, B + i);
    } else {
      for (int d = 0; d <= top; ++d) lane(dd.M[i], d, &m[i][d]);
    }
  }
  if (!DDPoly::eval_lanes<F>(k, lp, lj, lo, x)) return false;
  using namespace speed_formula;
  DDArith<F> ar;
  if (!direct && !dd.unit_den)
    for (std::size_t i = 0; i < n; ++i)
      scaled_derivatives(ar, A[i], angular ? B + i : nullptr, m[i][0], m[i][1], &m[i][2], q, q1, &q2);
  DDBall S, Fs{0, 0, 0}, r, l2;
  sum_of_squares(ar, S, n, [&A](std::size_t i) -> const DDBall& { return A[i]; });
  const Form form = !angular ? Form::Parametric : n == 2 ? Form::Plane : Form::Space;
  if (angular) cross_terms(ar, Fs, A, B, n);
  const bool scaled = !angular && !dd.unit_den;  // the parametric speed of M_i / L: S = L^4 sum x_i'^2
  if (scaled) ar.mul(l2, q, q);
  if (squared) speed_squared(ar, r, S, Fs, form, scaled ? &l2 : nullptr);
  else speed_value(ar, r, S, Fs, form, sign, scaled ? &l2 : nullptr);
  out = r;
  return dd_is_finite(r);
}

UNIPARAM_DD_FMA bool speed_dd_fma(DDBall& out, const detail::SpeedDD& dd, bool angular, int sign, bool squared,
                                  const DDBall& x) {
  return speed_dd<kHaveFmaTarget>(out, dd, angular, sign, squared, x);
}

}  // namespace

bool Speed::eval_dd(DDBall& out, const DDBall& x, const PieceSigns& p, bool squared, long prec) const {
  if (!dd_ || zero_ || prec > kDDMaxPrec || !dd_is_finite(x) || !(x.rad < 0x1p-30)) return false;
  const bool angular = kind_ == SpeedKind::Angular;
  DDBall r;
  const bool ok = dd_fma_in_use() ? speed_dd_fma(r, *dd_, angular, p.component, squared, x)
                                  : speed_dd<false>(r, *dd_, angular, p.component, squared, x);
  if (!ok || !(dd_rel_rad(r) <= std::ldexp(1.0, -static_cast<int>(prec - kNodeFastSlackBits)))) return false;
  out = r;
  return true;
}

void Speed::eval(acb_t out, const acb_t z, const PieceSigns& p, bool analytic, long prec, bool double_word) const {
  if (zero_) { acb_zero(out); return; }
  if (!analytic && double_word && eval_double_word(out, z, p, false, prec)) return;
  // Space curves' angular speed on an ellipse (the quadrature's error
  // bounds): F = |p' x p''|^2 from the components reaches 0 there on >= 90%
  // of the benchmark curves' ellipses (any degree), so the factored form
  // alone is tried. Where it fails, sigma's branch points (the complex zeros
  // of sum K^2, which F shares) are in the ellipse or D's enclosure holds 0,
  // and the components rarely do better (they succeed on only 1
  // of 143 ellipses at d = 6, 34 of 352 at d = 150): the ellipse is refused
  // at once (4-14% fewer instructions, same values). Plane curves' ellipses
  // succeed more often from the components, where the factored form costs
  // more.
  if (analytic && kind_ == SpeedKind::Angular && comp_.size() >= 3) {
    // In discs first (cheap); where every factor has its centred form in
    // double there, Arb's balls would not succeed where the discs failed
    // (they hold the same enclosures, in boxes), so they are not tried.
    const DiskResult r = disk_form_ ? eval_factored_disk(out, z, p, prec) : DiskResult::Unknown;
    if (r == DiskResult::Ok) return;
    if (r == DiskResult::Refused || !eval_factored(out, z, p, analytic, prec)) acb_indeterminate(out);
    return;
  }
  // Ellipses in discs first (see eval_disk); Arb's balls only where a
  // factor lacks its centred form in double (see above).
  if (analytic) {
    const DiskResult r = eval_disk(out, z, p, prec);
    if (r == DiskResult::Ok) return;
    if (r == DiskResult::Refused) {
      acb_indeterminate(out);
      return;
    }
  }
  // From the components first (low degree: cheap); where that is not
  // finite (space curves on wide balls: F = |p' x p''|^2 is a difference of
  // products whose enclosure may reach 0, so sqrt(F) is not certified
  // analytic; or the branch point near a zero of sigma), the factored form
  // g sqrt(sum K^2) / D below, tight but of degree ~4x higher.
  AcbBox S, F, r;
  eval_components(S, F, z, prec);
  // A real segment where holomorphy is not asked (Arb's direct bound on a
  // subinterval): sigma is real there, F = |p' x p''|^2 and S = |p'|^2 are
  // >= 0 at every real point, so sqrt may be taken of [max(0, lo), hi]
  // (arb_sqrtpos) instead of failing where the enclosure reaches below 0.
  const bool real = !analytic && acb_is_real(z) && acb_is_real(F) && acb_is_real(S);
  const AcbArith ar{prec, analytic, real};
  speed_formula::speed_value(ar, r, S, F, form(), p.component, nullptr);
  acb_swap(out, r);
  if (!acb_is_finite(out)) {
    // Near a zero of sigma the square root's branch point is in reach:
    // the factored form s g R is analytic there.
    eval_factored(out, z, p, analytic, prec);
  }
  // sigma is real at real points: on a real segment Re(out) holds it
  if (!analytic && acb_is_real(z)) arb_zero(acb_imagref(out));
}

bool Speed::eval_factored(acb_t out, const acb_t z, const PieceSigns& p, bool analytic, long prec) const {
  AcbBox d, s, r;
  // D first: where its enclosure holds 0 the quotient is not finite anyway,
  // and the K_k (degree ~4x the curve's) need not be expanded there.
  eval_D(d, z, prec);
  if (acb_contains_zero(d)) {
    acb_indeterminate(out);
    return false;
  }
  // s = sqrt(sum K^2); a single cofactor is a nonzero integer constant: |K|.
  if (K_b_.size() == 1) {
    K_b_[0].eval(s, z, prec);
    if (arb_is_negative(acb_realref(s.get())) && arb_is_zero(acb_imagref(s.get()))) acb_neg(s, s);
  } else {
    eval_sumK2(s, z, prec);
    // on a real segment (not analytic) sum K^2 >= 0: arb_sqrtpos
    const AcbArith root{prec, analytic, !analytic && acb_is_real(s)};
    root.sqrt(s, s);
  }
  const AcbArith ar{prec};
  speed_formula::factored_value(ar, r, s, d, [&](AcbBox& g) { eval_g(g, z, prec); }, p.g);
  acb_swap(out, r);
  return acb_is_finite(out);
}

namespace {

// Whether the disc x, which could not be divided by (root: or square-rooted),
// holds 0 (root: or meets the cut (-inf, 0]) with a finite centre and radius
// within 2^400: Arb's balls, holding the same enclosure, would fail there
// too. Otherwise (a magnitude out of the discs' range) Arb may still succeed.
bool holds_singularity(const CDisk& x, bool root) {
  if (!cdisk_is_finite(x) || std::max(std::fabs(x.re), std::fabs(x.im)) > 0x1p400 || x.rad > 0x1p400) return false;
  if (std::hypot(x.re, x.im) <= x.rad) return true;
  return root && x.re <= 0 && std::fabs(x.im) <= x.rad;
}

}  // namespace

Speed::DiskResult Speed::factored_disks(CDisk& g, CDisk& q, CDisk& d, const acb_t z, long prec) const {
  using namespace speed_formula;
  DiskArith ar;
  CDisk v;
  if (kind_ == SpeedKind::Parametric) {
    d = W_b_.eval_disk(z, prec);
  } else {
    sum_of_squares(ar, d, Y_b_.size(), [&](std::size_t i) -> const CDisk& { return v = Y_b_[i].eval_disk(z, prec); });
  }
  // first: see eval_factored
  if (!cdisk_is_finite(cdisk_inv(d))) return holds_singularity(d, false) ? DiskResult::Refused : DiskResult::Unknown;
  if (K_b_.size() == 1)
    q = K_b_[0].eval_disk(z, prec);
  else
    sum_of_squares(ar, q, K_b_.size(), [&](std::size_t i) -> const CDisk& { return v = K_b_[i].eval_disk(z, prec); });
  // g = content * prod h_i^m_i; fmpz_get_d rounds towards zero (< 2u relative)
  const double content = fmpz_get_d(g_content_.get());
  factored_g(
      ar, g, CDisk{content, 0, cdisk_detail::up(0x1p-52 * std::fabs(content))}, g_h_.size(),
      [&](std::size_t i, CDisk& h) { h = g_h_[i].eval_disk(z, prec); }, [&](std::size_t i) { return g_m_[i]; },
      static_cast<std::size_t>(-1));
  return cdisk_is_finite(q) && cdisk_is_finite(g) ? DiskResult::Ok : DiskResult::Unknown;
}

Speed::DiskResult Speed::eval_factored_disk(acb_t out, const acb_t z, const PieceSigns& p, long prec) const {
  CDisk g, s, d;
  const DiskResult parts = factored_disks(g, s, d, z, prec);
  if (parts != DiskResult::Ok) return parts;
  if (K_b_.size() == 1) {  // a nonzero integer constant: its absolute value
    if (!(s.im == 0 && std::fabs(s.re) > s.rad)) return DiskResult::Unknown;
    if (s.re < 0) s = cdisk_neg(s);
  } else {
    const CDisk q = s;
    s = cdisk_sqrt_analytic(q);
    if (!cdisk_is_finite(s)) return holds_singularity(q, true) ? DiskResult::Refused : DiskResult::Unknown;
  }
  DiskArith ar;
  CDisk r;
  speed_formula::factored_value(ar, r, s, d, [&g](CDisk& v) { v = g; }, p.g);
  if (!cdisk_is_finite(r)) return DiskResult::Unknown;
  cdisk_get_acb(out, r);
  return DiskResult::Ok;
}

bool Speed::components_disk(CDisk& S, CDisk& F, const acb_t z, long prec) const {
  using namespace speed_formula;
  constexpr std::size_t kMax = 8;
  const std::size_t n = comp_.size();
  const bool angular = kind_ == SpeedKind::Angular;
  if (!components_disk_form_ || n > kMax) return false;
  bool poly = true, common = true;
  for (const Component& k : comp_) {
    poly = poly && k.unit_den;
    common = common && !k.unit_den && k.q_index == comp_[0].q_index;
  }
  if (!poly && !(common && angular)) return false;
  DiskArith ar;
  CDisk d1[kMax], d2[kMax];
  if (poly) {  // x' = N', x'' = N''
    for (std::size_t i = 0; i < n; ++i) comp_[i].N.eval_disks(nullptr, d1 + i, angular ? d2 + i : nullptr, z, prec);
  } else {  // A_i and B_i (eval_components)
    CDisk q, q1, q2, v, v1, v2;
    comp_[0].Q.eval_disks(&q, &q1, &q2, z, prec);
    for (std::size_t i = 0; i < n; ++i) {
      comp_[i].N.eval_disks(&v, &v1, &v2, z, prec);
      scaled_derivatives(ar, d1[i], d2 + i, v, v1, &v2, q, q1, &q2);
    }
  }
  sum_of_squares(ar, S, n, [&d1](std::size_t i) -> const CDisk& { return d1[i]; });
  F = CDisk{0, 0, 0};
  if (angular) cross_terms(ar, F, d1, d2, n);
  return cdisk_is_finite(S) && cdisk_is_finite(F);
}

Speed::DiskResult Speed::eval_disk(acb_t out, const acb_t z, const PieceSigns& p, long prec) const {
  CDisk S, F;
  bool unknown = true;  // the components failed for want of range, not at a singularity
  if (components_disk(S, F, z, prec)) {
    const speed_formula::Form f = form();
    if (f == speed_formula::Form::Parametric) unknown = !holds_singularity(S, true);
    else if (f == speed_formula::Form::Plane) unknown = !holds_singularity(S, false);
    else unknown = !holds_singularity(S, false) && !holds_singularity(F, true);
    DiskArith ar;
    CDisk r;
    speed_formula::speed_value(ar, r, S, F, f, p.component, nullptr);
    if (cdisk_is_finite(r)) {
      cdisk_get_acb(out, r);
      return DiskResult::Ok;
    }
  }
  if (!disk_form_) return DiskResult::Unknown;
  const DiskResult f = eval_factored_disk(out, z, p, prec);
  return f == DiskResult::Refused && unknown ? DiskResult::Unknown : f;
}

Speed::DiskResult Speed::eval_squared_disk(acb_t out, const acb_t z, long prec) const {
  DiskArith ar;
  CDisk S, F, r;
  bool unknown = true;  // as in eval_disk
  if (components_disk(S, F, z, prec)) {
    speed_formula::speed_squared(ar, r, S, F, form(), nullptr);
    if (kind_ == SpeedKind::Angular) unknown = !holds_singularity(S, false);
    if (cdisk_is_finite(r)) {
      cdisk_get_acb(out, r);
      if (arb_is_zero(acb_imagref(z))) arb_zero(acb_imagref(out));  // sigma^2 is real on a real segment
      return DiskResult::Ok;
    }
  }
  // the factored form g^2 sum K^2 / D^2 (p'(z) = 0 in reach: see eval_squared)
  if (!disk_form_) return DiskResult::Unknown;
  CDisk g, q, d, ratio;
  const DiskResult parts = factored_disks(g, q, d, z, prec);
  if (parts != DiskResult::Ok) return parts == DiskResult::Refused && unknown ? DiskResult::Unknown : parts;
  if (K_b_.size() == 1) q = cdisk_mul(q, q);
  speed_formula::factored_ratio_squared(ar, ratio, q, d);
  speed_formula::factored_squared(ar, r, ratio, g);
  if (!cdisk_is_finite(r)) return DiskResult::Unknown;
  cdisk_get_acb(out, r);
  if (arb_is_zero(acb_imagref(z))) arb_zero(acb_imagref(out));
  return DiskResult::Ok;
}

void Speed::eval_squared(acb_t out, const acb_t z, long prec, bool double_word) const {
  if (zero_) { acb_zero(out); return; }
  if (double_word && eval_double_word(out, z, PieceSigns{}, true, prec)) return;
  // Wide balls in discs first, as eval's ellipses.
  if (is_wide_ball(z)) {  // (its enclosures only bound sigma^2)
    const DiskResult r = eval_squared_disk(out, z, prec);
    if (r == DiskResult::Ok) return;
    if (r == DiskResult::Refused) {
      acb_indeterminate(out);
      return;
    }
  }
  AcbBox S, F, r;
  eval_components(S, F, z, prec);
  const AcbArith ar{prec};
  speed_formula::speed_squared(ar, r, S, F, form(), nullptr);
  if (kind_ == SpeedKind::Angular && !acb_is_finite(r)) {
    // p'(z) = 0 in reach (a cusp): F / S^2 is 0/0 there, while the
    // factored form g^2 sum K^2 / D^2 has the common factor cancelled.
    AcbBox g, ratio;
    eval_g(g, z, prec);
    eval_sumK2_over_D2(ratio, z, prec);
    speed_formula::factored_squared(ar, r, ratio, g);
  }
  acb_swap(out, r);
}

double Speed::squared_double(double t) const {
  if (zero_) return 0;
  const std::size_t n = comp_.size();
  double buf[16];  // the optimisers call this ~10^5 times: no allocation up to 8 components
  std::vector<double> heap(n > 8 ? 2 * n : 0);
  double* d1 = n > 8 ? heap.data() : buf;
  double* d2 = d1 + n;
  for (std::size_t i = 0; i < n; ++i) {
    double nv, n1, n2, q, q1, q2;
    comp_[i].N.eval_double(t, &nv, &n1, &n2);
    comp_[i].Q.eval_double(t, &q, &q1, &q2);
    const double a = n1 * q - nv * q1, qq = q * q;
    d1[i] = a / qq;
    d2[i] = (n2 * q - nv * q2) / qq - 2 * q1 * a / (qq * q);
  }
  double S = 0;
  for (std::size_t i = 0; i < n; ++i) S += d1[i] * d1[i];
  if (kind_ == SpeedKind::Parametric) return S;
  double F = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const double e = d1[i] * d2[j] - d2[i] * d1[j];
      F += e * e;
    }
  return F / (S * S);
}

namespace {

// sum_of_squares_d2: s = sum p_i^2, s1 = (sum p_i^2)' = 2 sum p_i p_i' and, when s2 is
// non-null, s2 = (sum p_i^2)'' = 2 sum (p_i'^2 + p_i p_i'').
void sum_of_squares_d2(acb_t s, acb_t s1, acb_t s2, const std::vector<LocalPoly>& ps, const acb_t z, long prec) {
  AcbBox a, a1, a2;
  acb_zero(s);
  acb_zero(s1);
  if (s2) acb_zero(s2);
  for (const auto& p : ps) {
    p.eval(a, a1, s2 ? a2.get() : nullptr, z, prec);
    acb_addmul(s, a, a, prec);
    acb_addmul(s1, a, a1, prec);
    if (s2) {
      acb_addmul(s2, a1, a1, prec);
      acb_addmul(s2, a, a2, prec);
    }
  }
  acb_mul_2exp_si(s1, s1, 1);
  if (s2) acb_mul_2exp_si(s2, s2, 1);
}

}  // namespace

void Speed::eval_critical(acb_t v, acb_t d, const acb_t z, long prec) const {
  if (zero_) {
    acb_zero(v);
    if (d) acb_zero(d);
    return;
  }
  AcbBox g[3], q[3], e[3], t, u;
  g_b_.eval(g[0], g[1], d ? g[2].get() : nullptr, z, prec);
  sum_of_squares_d2(q[0], q[1], d ? q[2].get() : nullptr, K_b_, z, prec);  // Q = sum K^2
  if (kind_ == SpeedKind::Parametric) W_b_.eval(e[0], e[1], d ? e[2].get() : nullptr, z, prec);  // D = W
  else sum_of_squares_d2(e[0], e[1], d ? e[2].get() : nullptr, Y_b_, z, prec);                     // D = sum Y^2
  // P = (2 g' Q + g Q') D - 2 g Q D'
  acb_mul(t, g[1], q[0], prec);
  acb_mul_2exp_si(t, t, 1);
  acb_addmul(t, g[0], q[1], prec);
  acb_mul(v, t, e[0], prec);  // (2 g' Q + g Q') D
  acb_mul(t, g[0], q[0], prec);
  acb_mul_2exp_si(t, t, 1);
  acb_submul(v, t, e[1], prec);  // - 2 g Q D'
  if (d) {
    // P' = (2 g'' Q + 3 g' Q' + g Q'') D - g Q' D' - 2 g Q D''
    acb_mul(t, g[2], q[0], prec);
    acb_mul_2exp_si(t, t, 1);
    acb_addmul(t, g[0], q[2], prec);
    acb_mul(u, g[1], q[1], prec);
    acb_mul_ui(u, u, 3, prec);
    acb_add(t, t, u, prec);
    acb_mul(d, t, e[0], prec);  // (2 g'' Q + 3 g' Q' + g Q'') D
    acb_mul(t, g[0], q[1], prec);
    acb_submul(d, t, e[1], prec);  // - g Q' D'
    acb_mul(t, g[0], q[0], prec);
    acb_mul_2exp_si(t, t, 1);
    acb_submul(d, t, e[2], prec);  // - 2 g Q D''
  }
}

void Speed::eval_sumK2(AcbBox& out, const acb_t z, long prec) const {
  const AcbArith ar{prec};
  AcbBox v;
  speed_formula::sum_of_squares(ar, out, K_b_.size(), [&](std::size_t i) -> const AcbBox& {
    K_b_[i].eval(v, z, prec);
    return v;
  });
}

void Speed::eval_D(AcbBox& out, const acb_t z, long prec) const {
  if (kind_ == SpeedKind::Parametric) {
    W_b_.eval(out, z, prec);
    return;
  }
  const AcbArith ar{prec};
  AcbBox v;
  speed_formula::sum_of_squares(ar, out, Y_b_.size(), [&](std::size_t i) -> const AcbBox& {  // D = sum Y_i^2
    Y_b_[i].eval(v, z, prec);
    return v;
  });
}

void Speed::eval_sumK2_over_D2(AcbBox& out, const acb_t z, long prec) const {
  AcbBox d, q;
  eval_D(d, z, prec);  // first: see eval_factored
  if (acb_contains_zero(d)) {
    acb_indeterminate(out);
    return;
  }
  eval_sumK2(q, z, prec);
  const AcbArith ar{prec};
  speed_formula::factored_ratio_squared(ar, out, q, d);
}

void Speed::eval_squared_over_zero(acb_t out, const acb_t z, const SpeedZero& zero, int side, int power, long prec,
                                   bool double_word) const {
  if (zero_) { acb_zero(out); return; }
  const std::size_t j = zero.factor;
  const int mu = zero.multiplicity;
  if (power < 0 || power > 2 * mu) throw InvalidArgument("eval_squared_over_zero: power out of range");
  if (zero.index >= zeros_.size() || zeros_[zero.index].factor != j)
    throw InvalidArgument("eval_squared_over_zero: not a zero of this speed");
  AcbBox w, h, r;
  // w = side (z - gamma)
  const Ball gb = zero.t.to_ball(prec + 16);
  acb_sub_arb(w, z, gb.get(), prec);
  if (side < 0) acb_neg(w, w);
  // Away from gamma relative to the ball's size (|w| > 8 rad w), dividing is
  // harmless: sigma^2 from the components, divided by w^power.
  mag_t lo, rad;
  mag_init(lo);
  mag_init(rad);
  acb_get_mag_lower(lo, w);
  mag_hypot(rad, arb_radref(acb_realref(w.get())), arb_radref(acb_imagref(w.get())));
  mag_mul_2exp_si(rad, rad, 3);
  const bool far = mag_cmp(lo, rad) > 0;
  mag_clear(lo);
  mag_clear(rad);
  if (far) {
    eval_squared(out, z, prec, double_word);
    acb_pow_ui(w, w, static_cast<ulong>(power), prec);
    acb_div(out, out, w, prec);
  } else {
    // Near gamma: out = w^(2 mu - power) h_gamma(z)^(2 mu) (c g_1(z))^2 sum K^2 / D^2.
    acb_pow_ui(w, w, static_cast<ulong>(2 * mu - power), prec);
    g_h_[j].eval_deflated(h, z, zero.t, prec);
    acb_pow_ui(h, h, static_cast<ulong>(2 * mu), prec);
    acb_mul(w, w, h, prec);
    eval_g(h, z, prec, j);  // c g_1(z): g without the factor vanishing at gamma
    acb_mul(w, w, h, prec);
    acb_mul(w, w, h, prec);
    eval_sumK2_over_D2(r, z, prec);
    acb_mul(out, r, w, prec);
  }
}

}  // namespace uniparam
