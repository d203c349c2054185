// uniparam/reparam/curve.hpp -- rational curves p : [0, 1] -> R^n, n >= 2.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "uniparam/core/ball.hpp"

#include "uniparam/core/parser.hpp"
#include "uniparam/core/poly.hpp"
#include "uniparam/core/ratfunc.hpp"

namespace uniparam {

/// A (rational) Bezier curve's exact Bernstein coefficients of one degree
/// n: component i is sum_k num[i][k] B_k^n(t) / sum_k den[k] B_k^n(t)
/// (den[k] all equal for an integral curve). The speed evaluates such a
/// curve from these coefficients (speed tiers, reparam/src/curve_model.hpp).
struct BernsteinForm {
  std::vector<std::vector<Integer>> num;
  std::vector<Integer> den;
};

/// A rational curve with rational coefficients on the parameter interval
/// [0, 1], checked at construction to be usable:
/// * n >= 2 components,
/// * not constant (some component has a nonzero derivative),
/// * no pole in the closed interval [0, 1].
/// Its derivative is kept as p' = (X_1, ..., X_n) / W with X_i, W in Z[t],
/// gcd(X_1, ..., X_n, W) = 1 and W with positive leading coefficient.
class Curve {
 public:
  /// \throws InvalidArgument (fewer than two components), DomainError
  ///         (constant curve; pole in [0, 1], named as an algebraic number).
  explicit Curve(std::vector<RatFunc> components);
  /// The curve with the given components that also keeps their Bernstein
  /// form b. \pre components[i] == (sum_k b.num[i][k] B_k^n) / (sum_k
  /// b.den[k] B_k^n) exactly, every row of one length n + 1 >= 2 (not
  /// checked: BezierCurve::to_curve builds both). \throws as above.
  Curve(std::vector<RatFunc> components, BernsteinForm b);
  /// The Bernstein form given at construction, or null.
  const BernsteinForm* bernstein() const { return bernstein_.get(); }
  /// Parses "(x(t), y(t), ...)" (see parser.hpp) and checks as above.
  static Curve parse(const std::string& text, const ParseLimits& limits = {});

  /// The number of components (>= 2), and the components x_i(t).
  std::size_t dimension() const { return components_.size(); }
  const std::vector<RatFunc>& components() const { return components_; }
  /// Numerators of p' over the common denominator W().
  const std::vector<Poly>& derivative_numerators() const { return X_; }
  const Poly& derivative_denominator() const { return W_; }
  /// Largest degree among numerators and denominators of the components.
  long degree() const;
  /// "(x(t), y(t))" in plain text.
  std::string str() const;
  /// Enclosures of the components p_i(t) at the real ball t (inside [0, 1],
  /// where no component has a pole).
  std::vector<Ball> eval(const Ball& t, long prec) const;

 private:
  std::vector<RatFunc> components_;
  std::shared_ptr<const BernsteinForm> bernstein_;  // shared by copies
  std::vector<Poly> X_;
  Poly W_;
};

}  // namespace uniparam
