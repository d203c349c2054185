// uniparam/uniparam.hpp -- the public C++ API of uniparam.
//
//   #include <uniparam/uniparam.hpp>
//   namespace up = uniparam::api;
//   up::Curve c = up::Curve::parse("(t, t^3)");
//   up::Options o;                                  // angular speed, 15 digits
//   up::Uniformity u = up::uniformity(c, o);        // u.mu, u.u: certified balls
//   up::Reparameterization r = up::radical(c, o);   // owns its curve
//   r.u_after();                                    // u(p o r), certified
//   r.eval_r(up::Rational(1, 2));                   // r(1/2), certified
//
// Every number is exact (Rational) or a Ball proven to contain the true value
// and meeting Options::digits. The types hold their data themselves (values,
// or shared immutable state): a result stays valid after the Curve and the
// Options it was computed from are gone. This header includes the C++
// standard library and uniparam/error.hpp only.
//
// Errors are exceptions derived from uniparam::Error (uniparam/error.hpp):
// ParseError (malformed text, with its column), DomainError (undefined
// mathematics: a pole in [0, 1], a constant curve, a speed without a
// parameter to locate), InvalidArgument (an option or argument out of range;
// a method the curve does not admit), BudgetExceeded (a limit of Options
// reached: precision, degree, input size), TimeLimitExceeded (a
// BudgetExceeded: Options::time_limit ran out). Messages name the Options
// field that raises a limit. The library never exits and never returns an
// uncertified number in place of a failure.
//
// Thread safety: distinct objects may be used from distinct threads at once;
// one object (and its copies, which share their state) from one thread at a
// time.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "uniparam/error.hpp"

namespace uniparam {
namespace api {

/// Which speed sigma of the curve p is made uniform: the angular speed
/// |p' x p''| / |p'|^2 (turning angle per parameter) or the parametric speed
/// |p'| (arc length per parameter).
enum class SpeedKind { Angular, Parametric };

/// Formula syntax of Reparameterization::formulas.
enum class Format { Text, Latex, Maple };

/// An exact rational number (value semantics).
class Rational {
 public:
  /// 0.
  Rational();
  /// The integer n, exactly.
  Rational(long n);  // NOLINT: exact
  Rational(int n) : Rational(static_cast<long>(n)) {}  // NOLINT: exact
  Rational(double) = delete;  ///< 0.1 is 1/10 only when parsed from text
  /// num / den. \throws DomainError when den == 0.
  Rational(long num, long den);
  /// Parses "a", "-a", "a/b" or a decimal "1.25", "-0.1", "1e-3", exactly.
  /// \throws ParseError (with the column) for anything else; InvalidArgument
  ///         for text longer than 100000 characters or a decimal exponent of
  ///         1000 or more in absolute value.
  static Rational parse(const std::string& text);

  /// Canonical text "a" or "a/b" (gcd 1, b > 0).
  std::string str() const;
  /// Numerator and (positive) denominator of the canonical form, in decimal.
  std::string num() const;
  std::string den() const;
  /// -1, 0 or 1.
  int sign() const;

  /// Exact comparisons.
  friend bool operator==(const Rational& a, const Rational& b);
  friend bool operator!=(const Rational& a, const Rational& b) { return !(a == b); }
  friend bool operator<(const Rational& a, const Rational& b);

  struct Impl;
  /// Internal.
  explicit Rational(std::shared_ptr<const Impl> p) : p_(std::move(p)) {}
  const Impl& impl() const { return *p_; }

 private:
  std::shared_ptr<const Impl> p_;
};

/// A certified real ball [mid +/- rad]: it contains the true value of the
/// quantity it stands for. Its ends are exact dyadic rationals.
class Ball {
 public:
  /// The exact ball [0 +/- 0].
  Ball();

  /// The midpoint and the radius, exactly (rad >= 0). \throws DomainError
  /// for a ball that is not finite (no reported ball is).
  Rational mid() const;
  Rational rad() const;
  /// mid - rad and mid + rad, exactly: certified lower and upper bounds.
  Rational lower() const;
  Rational upper() const;
  /// rad == 0.
  bool is_exact() const;
  /// True when x lies in the ball (certainly).
  bool contains(const Rational& x) const;
  /// True when the ball b lies in this one.
  bool contains(const Ball& b) const;
  /// True when rad <= 10^-digits * max(1, |mid|): the accuracy every reported
  /// ball meets for Options::digits.
  bool meets_digits(long digits) const;
  /// "[mid +/- rad]" with `digits` significant digits of the midpoint (the
  /// printed interval contains the ball).
  std::string str(long digits = 20) const;
  /// The midpoint rounded to nearest, `digits` significant digits ("0" for 0).
  /// For display: not an enclosure.
  std::string mid_decimal(long digits) const;
  /// An upper bound of the radius, 3 significant digits ("0" when exact).
  std::string rad_decimal() const;
  /// UNCERTIFIED: the midpoint rounded to the nearest double, for drawing
  /// and other floating-point consumers; not an enclosure.
  double to_double_uncertified() const;

  struct Impl;
  /// Internal.
  explicit Ball(std::shared_ptr<const Impl> p) : p_(std::move(p)) {}
  const Impl& impl() const { return *p_; }

 private:
  std::shared_ptr<const Impl> p_;
};

/// Everything a caller sets: speed, accuracy, resources and size limits.
/// Every function checks the fields it uses and throws InvalidArgument
/// naming the field when one is out of range.
struct Options {
  SpeedKind speed = SpeedKind::Angular;
  /// Correct decimal digits of every reported ball, 1..2000 (past about 2000
  /// digits the quadrature's cost grows exponentially with the digits).
  long digits = 15;
  /// Largest working precision in bits before BudgetExceeded; 0 (default)
  /// means 16384 bits (enough for any digits), otherwise 64..2^24.
  long max_prec = 0;
  /// Largest degree of a curve (or of any segment) accepted, 1..20000.
  long max_degree = 1000;
  /// Longest text input (curve text, control points, SVG path data, NURBS
  /// JSON) in characters, 1..2^30.
  std::size_t max_input_length = std::size_t(1) << 20;
  /// Worker threads for independent integrals, 1..64; 0 (default) = the
  /// machine's cores, at most 8. Results do not depend on it.
  unsigned threads = 0;
  /// Wall-clock limit of each call in seconds (> 0, at most 1e9); 0
  /// (default) = none. A call that runs out throws TimeLimitExceeded.
  double time_limit = 0;
};

/// A rational curve p : [0, 1] -> R^n (n >= 2) with exact rational data: one
/// curve, or a composite curve (a path or spline: segments joined at exact
/// knots 0 = k_0 < ... < k_m = 1, segment j on [k_j, k_{j+1}]).
/// Checked at construction: not constant, no pole in [0, 1].
class Curve {
 public:
  /// Parses "(x(t), y(t), ...)": +, -, *, /, ^ (integer exponents), exact
  /// decimals and fractions, the variable t.
  /// \throws ParseError (column) for malformed text; InvalidArgument for
  ///         fewer than two components or bad options; DomainError for a
  ///         constant curve or a pole in [0, 1]; BudgetExceeded for text
  ///         longer than Options::max_input_length or a degree above
  ///         Options::max_degree.
  static Curve parse(const std::string& text, const Options& o = {});
  /// The Bezier curve of control points p_0..p_n (n >= 1, all of one
  /// dimension >= 2) and, when not empty, positive weights v_0..v_n.
  /// \throws InvalidArgument naming the offending point or weight;
  ///         DomainError when every point is equal; BudgetExceeded for a
  ///         degree above Options::max_degree.
  static Curve bezier(const std::vector<std::vector<Rational>>& points, const std::vector<Rational>& weights = {},
                      const Options& o = {});
  /// The same from text "[[x0, y0], [x1, y1], ...]" and "[w0, w1, ...]"
  /// ("" = no weights). \throws ParseError (column) for malformed text; as
  /// above otherwise.
  static Curve bezier(const std::string& control, const std::string& weights = "", const Options& o = {});
  /// SVG path data ("M 0 0 Q 1 2 2 0 ..."): one composite curve per
  /// subpath. Arcs are exact only for rotations by multiples of 90 degrees
  /// and rational centres (InvalidArgument otherwise: nothing is
  /// approximated). \throws ParseError (column) for malformed data;
  /// InvalidArgument as said; BudgetExceeded for more than
  /// Options::max_input_length characters.
  static std::vector<Curve> svg_path(const std::string& d, const Options& o = {});
  /// A NURBS or B-spline curve from JSON {"degree": p, "knots": [...],
  /// "control": [[x, y], ...], "weights": [...]} (weights optional; numbers
  /// exact). \throws ParseError for malformed JSON; InvalidArgument naming
  /// the field for inconsistent data; BudgetExceeded for text above
  /// Options::max_input_length or a degree above Options::max_degree.
  static Curve nurbs_json(const std::string& json, const Options& o = {});

  /// The number of components n (>= 2) of p : [0, 1] -> R^n.
  std::size_t dimension() const;
  /// Number of segments (1 for a single curve).
  std::size_t segments() const;
  /// The knots 0 = k_0 < ... < k_m = 1 (m = segments()).
  std::vector<Rational> knots() const;
  /// Largest degree of a numerator or denominator of any segment.
  long degree() const;
  /// Given as one Bezier curve (Curve::bezier): bezier_bilinear applies.
  bool is_bezier() const;
  /// "(x(t), y(t))" for a single curve; the segments' texts joined by "; "
  /// (each in its own parameter) for a composite one.
  std::string str() const;

  struct Impl;
  /// Internal.
  explicit Curve(std::shared_ptr<const Impl> p) : p_(std::move(p)) {}
  const Impl& impl() const { return *p_; }

 private:
  std::shared_ptr<const Impl> p_;
};

/// A zero of sigma in [0, 1]: sigma(t) ~ c |t - t0|^multiplicity.
struct Zero {
  Ball t;  ///< contains t0 (exact when t0 is rational and dyadic)
  int multiplicity = 0;
};

/// How uniform the curve's own parameter is.
struct Uniformity {
  Ball mu;           ///< int_0^1 sigma (arc length or total turning)
  Ball mean_square;  ///< int_0^1 sigma^2
  Ball u;            ///< mu^2 / int sigma^2, in (0, 1]; 1 = uniform
  /// sigma == 0 on [0, 1] (the angular speed of a straight line): mu = 0, u = 1.
  bool identically_zero = false;
  /// In the curve's (global) parameter, increasing; for a composite curve
  /// segment by segment (a zero at a knot listed by each segment it ends).
  std::vector<Zero> zeros;
};

/// Certified uniformity of c for Options::speed.
/// \post mu, mean_square, u contain the true values and meet Options::digits.
/// \throws InvalidArgument for bad options; DomainError for an infinite
///         speed; BudgetExceeded (Options::max_prec, max_degree) and
///         TimeLimitExceeded (time_limit).
Uniformity uniformity(const Curve& c, const Options& o = {});

/// A point of the exactly uniform parameterization (see locate).
struct Located {
  Ball t;                   ///< contains the parameter t
  std::vector<Ball> point;  ///< contains p(t)
};

/// The parameter t with int_0^t sigma = value (fraction == false: an arc
/// length or a turning angle in radians) or = value * mu (fraction == true,
/// 0 <= value <= 1). Unique since sigma >= 0 vanishes only at isolated points.
/// \post t, point meet Options::digits; value 0 gives t = 0 and fraction 1
///       gives t = 1 exactly.
/// \throws InvalidArgument for a negative value, a fraction above 1, an
///         integral above mu; DomainError when sigma is identically zero on
///         c (or on some but not all segments); as uniformity() otherwise.
Located locate(const Curve& c, const Rational& value, bool fraction, const Options& o = {});
/// K points at exactly equal steps of int sigma (k mu / (K - 1)), t_0 = 0 and
/// t_{K-1} = 1 exactly. \pre 2 <= K <= 1000000 (InvalidArgument).
/// \throws as locate().
std::vector<Located> exact_samples(const Curve& c, long K, const Options& o = {});

/// A NURBS curve in R^n with clamped knots, positive weights: p o r of a
/// Moebius map, exactly where the data are exact.
class Nurbs {
 public:
  /// The degree of every piece, and the number of coordinates of the points.
  long degree() const;
  std::size_t dimension() const;
  /// Every number exact: knots_exact(), points_exact(), weights_exact() set.
  bool exact() const;
  /// Certified enclosures of every datum (always set).
  std::vector<Ball> knots() const;
  std::vector<std::vector<Ball>> points() const;
  std::vector<Ball> weights() const;
  /// The exact data (empty when not exact; knots and points may be exact
  /// with irrational weights: then weights_text() holds them).
  std::vector<Rational> knots_exact() const;
  std::vector<std::vector<Rational>> points_exact() const;
  std::vector<Rational> weights_exact() const;
  /// Exact weights in Q(sqrt c) as text "(a + b*sqrt(c))/d" (Bezier's
  /// bilinear map of an integral Bezier curve); empty otherwise.
  std::vector<std::string> weights_text() const;
  /// The curve as a STEP AP214 file (a rational B-spline curve; reals are
  /// the midpoints rounded to double: STEP carries doubles).
  /// \throws InvalidArgument for a dimension above 3.
  std::string step(const std::string& name = "uniparam.stp") const;

  struct Impl;
  /// Internal.
  explicit Nurbs(std::shared_ptr<const Impl> p) : p_(std::move(p)) {}

 private:
  std::shared_ptr<const Impl> p_;
};

/// A reparameterization r : [0, 1] -> [0, 1] of a curve p (every method
/// returns one) with p o r closer to uniform speed. It owns its curve and
/// options: every member works on them, with Options::threads and
/// time_limit in force per call. Joints 0 = s_0 < ... < s_N = 1 with
/// r(s_i) = t_i; r is analytic between joints, continuous at them.
class Reparameterization {
 public:
  /// "none", "radical", "C0 piecewise Moebius", "C1 piecewise Moebius" or
  /// "Bezier bilinear".
  std::string method() const;
  /// The curve p and the options it was computed with.
  const Curve& curve() const;
  const Options& options() const;

  /// Number of pieces N (over all segments of a composite curve).
  std::size_t pieces() const;
  /// The joints (s_i, t_i), i = 0..N, in the global parameters; s_0 = t_0 =
  /// 0 and s_N = t_N = 1 exactly. \post each ball contains the joint and
  /// meets Options::digits.
  struct Joint {
    Ball s, t;
  };
  /// The N + 1 joints (see Joint).
  std::vector<Joint> breakpoints() const;
  /// mu = int_0^1 sigma, u(p) and u(p o r) as certified by the method
  /// (Options::digits).
  Ball mu() const;
  Ball u_before() const;
  Ball u_after() const;
  /// C1 with a target (moebius_target): u_after >= target is certified.
  /// True for every other method.
  bool target_reached() const;
  /// The map has exact rational data (rational()).
  bool is_rational() const;

  /// r(s) for s in [0, 1]. \post contains r(s), meets Options::digits;
  ///       exact at s = 0 and s = 1.
  /// \throws InvalidArgument for s outside [0, 1]; BudgetExceeded or
  ///         TimeLimitExceeded when Options' limits do not allow the
  ///         accuracy.
  Ball eval_r(const Rational& s) const;
  /// One sample of p o r at s.
  struct Sample {
    Rational s;
    Ball t;                   ///< r(s)
    std::vector<Ball> point;  ///< p(r(s))
    Ball speed;               ///< sigma of p o r at s (see at_joint)
    /// s is at (or not separable from) an interior joint: speed is the union
    /// of both one-sided speeds and not held to Options::digits.
    bool at_joint = false;
  };
  /// The sample at s. \post t, point (and speed unless at_joint) contain
  ///       the true values and meet Options::digits. \throws as eval_r.
  Sample at(const Rational& s) const;
  /// The samples at s = k / (K - 1), k = 0..K-1. \pre 2 <= K <= 1000000
  /// (InvalidArgument). \throws as eval_r.
  std::vector<Sample> samples(long K) const;

  /// One piece of r as formulas: t = r(s) on `interval` (segment `segment`'s
  /// own parameters for a composite curve; the radical method's s is its z).
  struct Formula {
    std::size_t segment = 0;
    std::string interval;            ///< "[s_i, s_{i+1}]"
    std::string r;                   ///< the map, e.g. "(a s + b) / (c s + d)"
    std::vector<std::string> point;  ///< components of p(r(s))
    /// Exact formulas (rational data, r = id); otherwise the coefficients
    /// are midpoints of certified balls, to Options::digits (rounded values,
    /// not enclosures: use eval_r and at for certified numbers).
    bool exact = false;
  };
  /// Every piece's formulas, in order. \throws as eval_r (time limit).
  std::vector<Formula> formulas(Format f = Format::Text) const;

  /// p o r as one NURBS (Moebius methods and Bezier bilinear; exact for a
  /// rational map). \throws InvalidArgument for radical or "none" maps;
  ///         BudgetExceeded when a weight's sign needs more precision.
  Nurbs nurbs() const;
  /// The same kind of Moebius map with exact rational data: T, S and every
  /// alpha rounded to simple rationals within 10^-rational_digits (relative),
  /// u(p o r) certified for that exact map (C1 stays exactly C1).
  /// \pre 1 <= rational_digits <= 100 (InvalidArgument). \throws
  ///      InvalidArgument for radical, "none" and Bezier maps; as eval_r.
  Reparameterization rational(long rational_digits = 8) const;

  struct Impl;
  /// Internal.
  explicit Reparameterization(std::shared_ptr<const Impl> p) : p_(std::move(p)) {}
  const Impl& impl() const { return *p_; }

 private:
  std::shared_ptr<const Impl> p_;
};

// The methods. Each returns a Reparameterization of c for Options::speed with
// every ball meeting Options::digits, and throws InvalidArgument for bad
// options or arguments, DomainError for undefined mathematics (e.g. on a
// composite curve, an angular speed identically zero on some segments but
// not all), BudgetExceeded / TimeLimitExceeded for the limits of Options.

/// r = id: the curve as given (u_before == u_after).
Reparameterization identity(const Curve& c, const Options& o = {});
/// The piecewise radical map (Hong, Wang, Yang 2023): breakpoints at the
/// zeros and critical points of sigma, radicals lifting the zeros, the
/// optimal piecewise Moebius map on top.
Reparameterization radical(const Curve& c, const Options& o = {});
/// The single optimal Moebius map (one piece per segment).
Reparameterization moebius(const Curve& c, const Options& o = {});
/// The C0 piecewise Moebius map with `pieces` pieces (over the whole curve),
/// breakpoints chosen by a local (uncertified) optimiser, everything
/// reported certified for them. \pre 1 <= pieces <= 1000, and at least
/// segments() (InvalidArgument).
Reparameterization moebius_pieces(const Curve& c, long pieces, const Options& o = {});
/// The optimal C0 piecewise Moebius map on the given breakpoints
/// 0 = t_0 < ... < t_N = 1 (global parameter; the knots are added).
/// \pre strictly increasing from exactly 0 to exactly 1 (InvalidArgument).
Reparameterization moebius_breakpoints(const Curve& c, const std::vector<Rational>& breakpoints,
                                       const Options& o = {});
/// A C1 piecewise Moebius map refined until u(p o r) >= target is certified
/// or max_pieces pieces (per segment) are used; target_reached() tells.
/// \pre 0 < target < 1, 1 <= max_pieces <= 1000 (InvalidArgument).
Reparameterization moebius_target(const Curve& c, const Rational& target, long max_pieces = 64,
                                  const Options& o = {});
/// The optimal bilinear (Moebius) map of a Bezier curve for the parametric
/// speed (Farouki 1997, Juettler 1997): exact (a quadratic surd) for an
/// integral curve. \pre c.is_bezier() and Options::speed == Parametric
/// (InvalidArgument).
Reparameterization bezier_bilinear(const Curve& c, const Options& o = {});

}  // namespace api
}  // namespace uniparam
