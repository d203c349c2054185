#include "uniparam/reparam/speed.hpp"

#include <algorithm>

#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {

std::string to_string(SpeedKind k) { return k == SpeedKind::Angular ? "angular" : "parametric"; }

SpeedKind parse_speed_kind(const std::string& s) {
  if (s == "angular") return SpeedKind::Angular;
  if (s == "parametric") return SpeedKind::Parametric;
  throw InvalidArgument("unknown speed '" + s + "' (expected 'angular' or 'parametric')");
}

namespace {

Poly gcd_all(const std::vector<Poly>& ps) {
  Poly g;
  for (const auto& p : ps) g = gcd(g, p);
  return g;
}

}  // namespace

Speed::Speed(const Curve& c, SpeedKind kind) : kind_(kind) {
  const auto& X = c.derivative_numerators();
  std::vector<Poly> N;
  if (kind == SpeedKind::Angular) {
    Poly gx = gcd_all(X);
    std::vector<Poly> Y;
    for (const auto& x : X) Y.push_back(divexact(x, gx));
    D_ = Poly(0);
    for (const auto& y : Y) D_ = D_ + y * y;
    for (std::size_t i = 0; i < Y.size(); ++i)
      for (std::size_t j = i + 1; j < Y.size(); ++j) {
        Poly e = Y[i].derivative() * Y[j] - Y[i] * Y[j].derivative();
        if (!e.is_zero()) N.push_back(std::move(e));
      }
    for (const auto& y : Y) Y_b_.emplace_back(y);
  } else {
    for (const auto& x : X)
      if (!x.is_zero()) N.push_back(x);
    D_ = c.derivative_denominator();
    W_b_ = BallPoly(D_);
  }

  // D must not vanish on [0, 1] (the speed would be infinite there).
  {
    auto r = isolate_real_roots(D_, Rational(0), Rational(1));
    if (!r.empty()) {
      RealAlgebraic at(r.front());
      throw DomainError("the " + to_string(kind) + " speed is infinite at t = " + at.str() + " (t ~ " +
                        at.decimal(10) + "): the curve is not regular there");
    }
  }

  if (N.empty()) {  // angular speed of a straight line
    zero_ = true;
    squared_ = RatFunc(0);
    g_ = Poly(0);
    return;
  }
  g_ = gcd_all(N).primitive();
  for (const auto& n : N) K_.push_back(divexact(n, g_));
  Poly sumK2(0);
  for (const auto& k : K_) sumK2 = sumK2 + k * k;
  squared_ = RatFunc(g_ * g_ * sumK2, D_ * D_);

  g_sqf_ = squarefree_factorization(g_);
  g_content_ = g_sqf_.content;
  for (const auto& f : g_sqf_.factors) {
    g_h_.emplace_back(f.factor);
    g_m_.push_back(f.multiplicity);
    for (const auto& r : isolate_real_roots(f.factor, Rational(0), Rational(1)))
      zeros_.push_back(SpeedZero{RealAlgebraic(r), f.multiplicity});
  }
  std::sort(zeros_.begin(), zeros_.end(), [](const SpeedZero& a, const SpeedZero& b) { return a.t < b.t; });
  for (const auto& k : K_) K_b_.emplace_back(k);
}

int Speed::piece_sign(const RealAlgebraic& a, const RealAlgebraic& b) const {
  if (!(a < b)) throw DomainError("piece_sign needs a < b");
  // A rational strictly between a and b.
  a.refine(8);
  b.refine(8);
  long bits = 8;
  while (!(a.hi() < b.lo())) {
    bits *= 2;
    if (bits > 1 << 16) throw BudgetExceeded("could not separate two piece ends");
    a.refine(bits);
    b.refine(bits);
  }
  Rational q = (a.hi() + b.lo()) * Rational(1, 2);
  if (a.is_rational() && b.is_rational()) q = (a.rational() + b.rational()) * Rational(1, 2);
  int sg = zero_ ? 1 : g_.sign_at(q);
  int sd = D_.sign_at(q);
  if (sg == 0 || sd == 0) throw DomainError("piece_sign: the speed vanishes inside the piece");
  return sg * sd;
}

void Speed::eval_g(acb_t out, const acb_t z, long prec) const {
  acb_t h;
  acb_init(h);
  acb_set_fmpz(out, g_content_.get());
  for (std::size_t i = 0; i < g_h_.size(); ++i) {
    g_h_[i].evaluate(h, z, prec);
    acb_pow_ui(h, h, static_cast<ulong>(g_m_[i]), prec);
    acb_mul(out, out, h, prec);
  }
  acb_clear(h);
}

void Speed::eval_cofactor(acb_t out, const acb_t z, bool analytic, long prec) const {
  acb_t s, v, d;
  acb_init(s);
  acb_init(v);
  acb_init(d);
  // numerator: sqrt(sum K^2); a single cofactor is a nonzero integer constant.
  if (K_b_.size() == 1) {
    K_b_[0].evaluate(s, z, prec);
    if (arb_is_negative(acb_realref(s)) && arb_is_zero(acb_imagref(s))) acb_neg(s, s);
  } else {
    acb_zero(s);
    for (const auto& k : K_b_) {
      k.evaluate(v, z, prec);
      acb_addmul(s, v, v, prec);
    }
    acb_sqrt_analytic(s, s, analytic, prec);
  }
  // denominator D, from its factors
  if (kind_ == SpeedKind::Angular) {
    acb_zero(d);
    for (const auto& y : Y_b_) {
      y.evaluate(v, z, prec);
      acb_addmul(d, v, v, prec);
    }
  } else {
    W_b_.evaluate(d, z, prec);
  }
  acb_div(out, s, d, prec);
  acb_clear(s);
  acb_clear(v);
  acb_clear(d);
}

void Speed::eval(acb_t out, const acb_t z, int s, bool analytic, long prec) const {
  if (zero_) { acb_zero(out); return; }
  acb_t g;
  acb_init(g);
  eval_g(g, z, prec);
  eval_cofactor(out, z, analytic, prec);
  acb_mul(out, out, g, prec);
  if (s < 0) acb_neg(out, out);
  acb_clear(g);
}

void Speed::eval_squared(acb_t out, const acb_t z, long prec) const {
  if (zero_) { acb_zero(out); return; }
  acb_t g, v, d, s;
  acb_init(g);
  acb_init(v);
  acb_init(d);
  acb_init(s);
  eval_g(g, z, prec);
  acb_zero(s);
  for (const auto& k : K_b_) {
    k.evaluate(v, z, prec);
    acb_addmul(s, v, v, prec);
  }
  if (kind_ == SpeedKind::Angular) {
    acb_zero(d);
    for (const auto& y : Y_b_) {
      y.evaluate(v, z, prec);
      acb_addmul(d, v, v, prec);
    }
  } else {
    W_b_.evaluate(d, z, prec);
  }
  acb_mul(out, g, g, prec);
  acb_mul(out, out, s, prec);
  acb_div(out, out, d, prec);
  acb_div(out, out, d, prec);
  acb_clear(g);
  acb_clear(v);
  acb_clear(d);
  acb_clear(s);
}

}  // namespace uniparam
