// speed.cpp -- Speed's construction from a curve (the factored form, its
// zeros, the evaluation curve's components), sigma^2 exactly and the signs
// of a piece. The evaluations are in speed_eval.cpp (Arb's balls),
// speed_disk.cpp (discs in double), speed_dd.cpp (double words) and
// speed_critical.cpp; their arithmetic in speed_formula.hpp.
#include "uniparam/reparam/speed.hpp"

#include <algorithm>
#include <memory>
#include <mutex>

#include "curve_model.hpp"
#include "speed_detail.hpp"
#include "speed_model.hpp"
#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/parallel.hpp"
#include "uniparam/reparam/scaling.hpp"

namespace uniparam {

std::string to_string(SpeedKind k) { return k == SpeedKind::Angular ? "angular" : "parametric"; }

SpeedKind parse_speed_kind(const std::string& s) {
  if (s == "angular") return SpeedKind::Angular;
  if (s == "parametric" || s == "arclength") return SpeedKind::Parametric;
  throw InvalidArgument("unknown speed '" + s + "' (expected 'angular', 'parametric' or 'arclength')");
}

namespace {

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
  const SpeedModel& sm = speed_model(kind);
  std::vector<RatFunc> reduced;
  if (sm.direction_only()) {
    Poly gx = gcd_all(X);
    for (const auto& x : X) Y.push_back(divexact(x, gx));
    if (gx.degree() > 0) reduced = direction_curve(Y);
  }
  const std::vector<RatFunc>& comps = reduced.empty() ? c.components() : reduced;
  // The exact x', x'' fix the sign of a plane curve's angular speed
  // (piece_signs); elsewhere they are not needed (and cost two exact
  // quotient rules on high-degree rational functions).
  const bool exact_derivatives = sm.form(comps.size()) == speed_formula::Form::Plane;
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
  // The evaluation tiers' curve model: a Bezier curve's own components
  // (not the direction curve) from their Bernstein coefficients, up to
  // kBernsteinMaxDegree (bernstein_model_serves); else the power basis.
  const BernsteinForm* bern = reduced.empty() ? c.bernstein() : nullptr;
  if (bern && bernstein_model_serves(*bern)) {
    model_ = bernstein_curve_model(*bern);
  } else {
    std::vector<PowerComponent> pc;
    for (const Component& k : comp_) pc.push_back(PowerComponent{k.N, k.Q, k.unit_den, k.q_index});
    model_ = power_curve_model(std::move(pc));
  }
  // The double-word path for the nodes (eval_double_word), where it applies.
  dd_ = detail::make_speed_dd(comps, kind);
  // A Bezier curve whose power basis loses too many bits for it (degree
  // above ~20) takes it from its Bernstein sums, which lose few.
  if (!dd_ && bern) dd_ = detail::make_speed_dd_bernstein(*bern);
  // Two independent halves, side by side (the construction is serial
  // otherwise, ~10% of radical's time at degree 150): D and (parametric
  // speed) the check that it has no root in [0, 1]; the numerators N,
  // g = gcd(N), the cofactors K and g's zeros. Both are exact, so nothing
  // depends on the threads. An error (a root of D) is rethrown after both
  // have stopped.
  std::vector<Poly> N;
  parallel_for(2, std::min<std::size_t>(worker_count(), 2), [&](std::size_t, std::size_t task) {
    if (task == 0) {
      D_ = sm.denominator(c, Y);
      // (The angular D = sum Y_i^2 needs no check: it is positive on the
      // whole real line; its isolation on [0, 1] cost ~1% of dense-plane
      // d=150 uniformity's instructions.)
      if (!sm.denominator_may_vanish()) return;
      // D must not vanish on [0, 1] (the speed would be infinite there).
      auto r = isolate_real_roots(D_, Rational(0), Rational(1));
      if (!r.empty()) {
        RealAlgebraic at(r.front());
        throw DomainError("the " + to_string(kind) + " speed is infinite at t = " + at.str() + " (t ~ " +
                          at.decimal(10) + "): the curve is not regular there");
      }
      return;
    }
    N = sm.numerators(X, Y);
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
  // D from the squares it is the sum of (angular: Y_i), else itself
  for (const auto& y : sm.denominator_squares(Y)) Y_b_.emplace_back(y);
  if (Y_b_.empty()) W_b_ = LocalPoly(D_);
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
  if (Y_b_.empty()) disk_form_ = disk_form_ && W_b_.has_disk_form();
  // Kept for the charts (charts(), speed_charts.cpp), where they may exist.
  if (peak_split_searched(*this)) lazy_->curve = std::make_shared<const Curve>(c);
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
    lazy_->squared = RatFunc(g_ * g_ * cofactor_square_sum(), D_ * D_);
  });
  return lazy_->squared;
}

const Poly& Speed::cofactor_square_sum() const {
  std::call_once(lazy_->sumK2_once, [this] {
    Poly sum(0);
    for (const auto& k : K_) sum = sum + k * k;
    lazy_->sumK2 = std::move(sum);
  });
  return lazy_->sumK2;
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

}  // namespace uniparam
