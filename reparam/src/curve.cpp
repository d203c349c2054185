#include "uniparam/reparam/curve.hpp"

#include "uniparam/core/ball_poly.hpp"

#include <algorithm>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {

Curve::Curve(std::vector<RatFunc> components) : components_(std::move(components)) {
  if (components_.size() < 2)
    throw InvalidArgument("a curve needs at least two components, got " + std::to_string(components_.size()));

  // Poles: a real root in [0, 1] of any component's (canonical) denominator.
  for (std::size_t i = 0; i < components_.size(); ++i) {
    Poly den = components_[i].den();
    if (den.degree() < 1) continue;
    auto roots = isolate_real_roots(den, Rational(0), Rational(1));
    if (!roots.empty()) {
      RealAlgebraic at(roots.front());
      throw DomainError("the curve has a pole in [0, 1]: component " + std::to_string(i + 1) +
                        " is infinite at t = " + at.str() + " (t ~ " + at.decimal(10) + ")");
    }
  }

  // p' = X / W over the least common denominator.
  std::vector<RatFunc> d;
  d.reserve(components_.size());
  W_ = Poly(1);
  for (const auto& c : components_) {
    d.push_back(c.derivative());
    Poly b = d.back().den();
    W_ = divexact(W_ * b, gcd(W_, b));
  }
  bool all_zero = true;
  for (const auto& di : d) {
    X_.push_back(di.num() * divexact(W_, di.den()));
    all_zero = all_zero && di.is_zero();
  }
  if (all_zero) throw DomainError("the curve is constant (a single point): no speed to make uniform");
  // Remove a common integer content of X_1..X_n and W (keeps p' unchanged).
  Poly g = W_;
  for (const auto& x : X_) g = gcd(g, x);
  if (g.degree() == 0 && g.leading() != Integer(1)) {
    W_ = divexact(W_, g);
    for (auto& x : X_) x = divexact(x, g);
  }
}

Curve Curve::parse(const std::string& text, const ParseLimits& limits) {
  return Curve(parse_tuple(text, limits));
}

Curve::Curve(std::vector<RatFunc> components, BernsteinForm b) : Curve(std::move(components)) {
  bernstein_ = std::make_shared<const BernsteinForm>(std::move(b));
}

long Curve::degree() const {
  long d = 0;
  for (const auto& c : components_) d = std::max({d, c.num().degree(), c.den().degree()});
  return d;
}

std::string Curve::str() const {
  std::string s = "(";
  for (std::size_t i = 0; i < components_.size(); ++i) s += (i ? ", " : "") + components_[i].str();
  return s + ")";
}

std::vector<Ball> Curve::eval(const Ball& t, long prec) const {
  std::vector<Ball> out;
  for (const auto& x : components_) {
    Ball n = BallPoly(x.num())(t, prec), d = BallPoly(x.den())(t, prec), v;
    arb_div(v.get(), n.get(), d.get(), prec);
    out.push_back(v);
  }
  return out;
}

}  // namespace uniparam
