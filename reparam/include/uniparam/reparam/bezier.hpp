// uniparam/reparam/bezier.hpp -- Bezier curves (integral and rational, any
// degree and dimension) and their optimal bilinear reparameterization for the
// parametric speed (Farouki 1997 as simplified by Juettler 1997;
// docs/math.md section 2).
//
// The Moebius map is (2.1), t = (1 - a) s / ((1 - a) s + a (1 - s)); applied to
// a Bezier curve with weights v_i it gives the rational Bezier curve with the
// same control points and weights v_i (1 - a)^i a^(n - i) (Juettler 1997, eq. 4). The
// optimal a is the root in (0, 1) of P (1 - a)^2 + Q a^2 = 0 (Juettler 1997, eq. 22) with
//     P = -int_0^1 (1 - t)^2 |p'(t)|^2 dt = -A,   Q = int_0^1 t^2 |p'(t)|^2 dt = C.
// For an integral curve P and Q are exact rationals (Juettler 1997, eq. 21), so a is an
// exact quadratic surd.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/core/printer.hpp"
#include "uniparam/reparam/curve.hpp"
#include "uniparam/reparam/uniformity.hpp"

namespace uniparam {

/// A Bezier curve p(t) = sum_i B_i^n(t) v_i p_i / sum_i B_i^n(t) v_i, t in [0, 1],
/// with exact rational control points p_0, ..., p_n in Q^d and, for a rational
/// curve, exact positive weights v_i (an integral curve has no weights: v_i = 1).
class BezierCurve {
 public:
  /// \pre n + 1 >= 2 points, all of the same dimension d >= 2; weights empty
  ///      or n + 1 positive rationals (all checked: InvalidArgument naming the
  ///      offending point or weight).
  explicit BezierCurve(std::vector<std::vector<Rational>> points, std::vector<Rational> weights = {});

  /// Parses control points "[[x0, y0], [x1, y1], ...]" and, when `weights` is
  /// not empty, weights "[w0, w1, ...]". Entries are exact rationals ("1/3",
  /// "-2", "0.25", "1e-3"); brackets may also be parentheses; whitespace is
  /// ignored.
  /// \throws ParseError (with the 1-based column, prefixed "control points" or
  ///         "weights") for malformed text, a zero denominator or text after the
  ///         list; InvalidArgument as the constructor, and for more than
  ///         `max_points` points or an input longer than 2^20 characters.
  static BezierCurve parse(const std::string& control, const std::string& weights = "",
                           std::size_t max_points = 20001);

  /// The degree n (n + 1 control points), the dimension of the points,
  /// whether weights were given (a rational curve), and the control points.
  long degree() const { return static_cast<long>(points_.size()) - 1; }
  std::size_t dimension() const { return points_.front().size(); }
  bool is_rational() const { return !weights_.empty(); }
  const std::vector<std::vector<Rational>>& points() const { return points_; }
  /// The weights v_i (all 1 for an integral curve).
  std::vector<Rational> weights() const;

  /// The same curve in the power basis, exactly: components N_k / D with
  /// N_k = sum_i binom(n, i) t^i (1 - t)^(n - i) v_i p_ik (D = sum of the same
  /// with p_ik = 1), canonicalised. The curve also keeps the Bernstein
  /// coefficients v_i p_ik, v_i (scaled to integers; Curve::bernstein), from
  /// which Speed evaluates it (no power basis's alternating coefficients).
  /// \throws DomainError when the curve is constant (all control points equal).
  Curve to_curve() const;

  /// "[[x0, y0], ...]" with exact rationals.
  std::string str() const;

 private:
  std::vector<std::vector<Rational>> points_;
  std::vector<Rational> weights_;
};

/// An element x + y sqrt(c) of Q(sqrt c), c >= 2 an integer with the square
/// factors found by trial division (by every prime below 2^16) and a final
/// perfect-square test removed ("squarefree-ish"), or a rational (y = 0, c = 1).
class QuadraticSurd {
 public:
  /// The rational q.
  explicit QuadraticSurd(const Rational& q);
  /// x + y sqrt(r) for a rational r >= 0 (InvalidArgument for r < 0): the
  /// square part of r is pulled out of the root, and a perfect square gives a
  /// rational.
  static QuadraticSurd make(const Rational& x, const Rational& y, const Rational& r);

  /// Whether y = 0 (the value is the rational x); x, y and c of x + y sqrt(c)
  /// (c = 1 when y = 0).
  bool is_rational() const { return y_.is_zero(); }
  const Rational& x() const { return x_; }
  const Rational& y() const { return y_; }
  const Integer& c() const { return c_; }
  /// The exact value; \pre is_rational().
  const Rational& rational() const;
  /// The form (a + b sqrt(c)) / d with integers, d > 0, gcd(a, b, d) = 1.
  Integer a() const;
  Integer b() const;
  Integer d() const;
  /// Ball with radius <= 2^-prec * max(1, |value|).
  Ball to_ball(long prec) const;
  /// Exact sign.
  int sign() const;
  /// "(-33 + 2*sqrt(330))/7" (text), "\frac{-33 + 2\sqrt{330}}{7}" (LaTeX),
  /// "(-33+2*sqrt(330))/7" style with Maple's sqrt (Maple); rationals as
  /// format_rational.
  std::string str(Format f = Format::Text) const;

  /// Exact arithmetic in Q(sqrt c): \pre both operands rational or of the
  /// same c (checked: InvalidArgument).
  friend QuadraticSurd operator+(const QuadraticSurd& p, const QuadraticSurd& q);
  friend QuadraticSurd operator-(const QuadraticSurd& p, const QuadraticSurd& q);
  friend QuadraticSurd operator*(const QuadraticSurd& p, const QuadraticSurd& q);

  /// Work counter (tests, benchmarks): the number of products of two surds
  /// with both parts x and y nonzero (four rational products and two sums)
  /// this thread has made. A product with a rational or with a pure y sqrt(c)
  /// takes two rational products and is not counted.
  static std::size_t full_products();

 private:
  QuadraticSurd(Rational x, Rational y, Integer c);
  Rational x_, y_;
  Integer c_;
};

/// Exact A = int (1-t)^2 |p'|^2, B = int 2t(1-t) |p'|^2, C = int t^2 |p'|^2
/// over [0, 1] for an integral Bezier curve, by Bernstein products (Juettler 1997, eq. 21):
///     A = n^2/(2n+1) sum_ij binom(n-1,i) binom(n-1,j) / binom(2n, i+j)   dp_i.dp_j,
///     B = n^2/(2n+1) sum_ij binom(n-1,i) binom(n-1,j) 2/binom(2n, i+j+1) dp_i.dp_j,
///     C = n^2/(2n+1) sum_ij binom(n-1,i) binom(n-1,j) / binom(2n, i+j+2) dp_i.dp_j,
/// dp_i = p_{i+1} - p_i. A + B + C = int_0^1 |p'|^2. \pre !b.is_rational()
/// (InvalidArgument otherwise).
struct BezierMoments {
  Rational A, B, C;
};
/// The moments A, B, C of b (see BezierMoments), exact.
/// \pre !b.is_rational() (InvalidArgument otherwise).
BezierMoments bezier_moments(const BezierCurve& b);

/// The optimal bilinear reparameterization of a Bezier curve for the
/// parametric speed.
struct BezierResult {
  bool exact = false;  ///< integral curve: P, Q (and A, B, C) exact, alpha a quadratic surd
  /// Exact data (set when exact): P = -A, Q = C of Juettler 1997 (eq. 21), B, and
  /// int |p'|^2 = A + B + C.
  std::optional<Rational> P_exact, Q_exact, B_exact, mean_square_exact;
  /// alpha as a quadratic surd and as a real algebraic number (a root of the
  /// integer form of (Q + P) a^2 - 2 P a + P in (0, 1)); set when exact.
  std::optional<QuadraticSurd> alpha_exact;
  std::optional<RealAlgebraic> alpha_algebraic;
  /// The new weights v_i (1 - alpha)^i alpha^(n - i), exactly in Q(sqrt c);
  /// set when exact. Computed as v_i alpha^n sqrt(rho)^i (rho = C / A, so
  /// (1 - alpha) / alpha = sqrt(rho)): O(log n) products of two surds, then
  /// one cheap product per weight.
  std::vector<QuadraticSurd> weights_exact;

  Ball P, Q;            ///< certified (exact balls of the rationals when exact)
  Ball alpha;           ///< the root of P (1 - a)^2 + Q a^2 in (0, 1)
  std::vector<Ball> weights;  ///< v_i (1 - alpha)^i alpha^(n - i), i = 0..n
  Ball mu;              ///< arc length int_0^1 |p'|
  Ball u_before;        ///< u(p) for the parametric speed
  Ball u_after;         ///< u(p o m) = mu^2 / (B + 2 sqrt(A C))
};

/// Optimal alpha, new weights and certified uniformity before/after.
/// Integral curves: P, Q, B exact (bezier_moments), alpha exact, mu by
/// certified quadrature. Rational curves: P = -A and Q = C by certified
/// quadrature (moebius_optimal with the parametric speed).
/// \post every Ball contains the true value and meets Options::digits + 1
///       digits (so a printed decimal still meets Options::digits).
/// \throws InvalidArgument for bad options or a degree above
///         Options::max_degree; DomainError for a constant curve;
///         BudgetExceeded when the accuracy is not reached within
///         Options::max_prec.
BezierResult bezier_optimal(const BezierCurve& b, const Options& opt = {});

}  // namespace uniparam
