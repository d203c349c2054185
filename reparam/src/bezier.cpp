#include "uniparam/reparam/bezier.hpp"

#include <flint/fmpq.h>
#include <flint/fmpz_poly.h>

#include <cctype>

#include "uniparam/core/error.hpp"
#include "uniparam/reparam/moebius.hpp"
#include "uniparam/reparam/speed.hpp"

namespace uniparam {

// ---------------------------------------------------------------- BezierCurve

BezierCurve::BezierCurve(std::vector<std::vector<Rational>> points, std::vector<Rational> weights)
    : points_(std::move(points)), weights_(std::move(weights)) {
  if (points_.size() < 2)
    throw InvalidArgument("a Bezier curve needs at least 2 control points, got " + std::to_string(points_.size()));
  const std::size_t d = points_.front().size();
  if (d < 2)
    throw InvalidArgument("control points need at least 2 coordinates, point 0 has " + std::to_string(d));
  for (std::size_t i = 1; i < points_.size(); ++i)
    if (points_[i].size() != d)
      throw InvalidArgument("control point " + std::to_string(i) + " has " + std::to_string(points_[i].size()) +
                            " coordinates, point 0 has " + std::to_string(d) + " (mixed dimensions)");
  if (!weights_.empty()) {
    if (weights_.size() != points_.size())
      throw InvalidArgument("got " + std::to_string(weights_.size()) + " weights for " +
                            std::to_string(points_.size()) + " control points (one weight per point)");
    for (std::size_t i = 0; i < weights_.size(); ++i)
      if (weights_[i].sign() <= 0)
        throw InvalidArgument("weight " + std::to_string(i) + " is " + weights_[i].str() +
                              "; weights must be positive");
  }
}

namespace {

constexpr std::size_t kMaxListLength = 1u << 20;

// A reader of nested lists of rationals: '[' or '(' opens, ']' or ')' closes.
class ListReader {
 public:
  ListReader(const std::string& s, const char* what) : s_(s), what_(what) {}

  [[noreturn]] void fail(std::size_t pos, const std::string& expected, const std::string& detail) const {
    throw ParseError(pos + 1, expected, std::string(what_) + ": " + detail);
  }
  void skip_ws() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  bool at_end() { skip_ws(); return i_ >= s_.size(); }
  char peek() { skip_ws(); return i_ < s_.size() ? s_[i_] : '\0'; }
  std::size_t pos() const { return i_; }

  // Reads '[' and returns the matching closer.
  char open() {
    char c = peek();
    if (c == '[') { ++i_; return ']'; }
    if (c == '(') { ++i_; return ')'; }
    if (c == '\0') fail(i_, "'['", "unexpected end of input");
    fail(i_, "'['", std::string("unexpected character '") + c + "'");
  }

  Rational number() {
    skip_ws();
    const std::size_t start = i_;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '.' ||
                              s_[i_] == '/' || s_[i_] == '-' || s_[i_] == '+'))
      ++i_;
    if (i_ == start) {
      if (i_ >= s_.size()) fail(i_, "a number", "unexpected end of input");
      fail(i_, "a number", std::string("unexpected character '") + s_[i_] + "'");
    }
    const std::string tok = s_.substr(start, i_ - start);
    try {
      return Rational::parse(tok);
    } catch (const ParseError& e) {
      fail(start + e.column() - 1, e.expected(), "invalid number '" + tok + "'");
    } catch (const DomainError&) {
      fail(start, "a nonzero denominator", "division by zero in '" + tok + "'");
    }
  }

  // Reads a list of items with `item()`, separated by commas, between brackets.
  template <class F>
  void list(F item) {
    const char close = open();
    if (peek() == close) fail(i_, "an entry", "empty list");
    for (;;) {
      item();
      char c = peek();
      if (c == ',') { ++i_; continue; }
      if (c == close) { ++i_; return; }
      if (c == '\0') fail(i_, std::string("',' or '") + close + "'", "unexpected end of input");
      fail(i_, std::string("',' or '") + close + "'", std::string("unexpected character '") + c + "'");
    }
  }

  void finish() {
    if (!at_end()) fail(i_, "end of input", std::string("unexpected text after the list: '") + s_[i_] + "'");
  }

 private:
  const std::string& s_;
  const char* what_;
  std::size_t i_ = 0;
};

}  // namespace

BezierCurve BezierCurve::parse(const std::string& control, const std::string& weights, std::size_t max_points) {
  if (control.size() > kMaxListLength || weights.size() > kMaxListLength)
    throw InvalidArgument("the control points or weights are longer than " + std::to_string(kMaxListLength) +
                          " characters");
  std::vector<std::vector<Rational>> pts;
  ListReader r(control, "control points");
  if (r.at_end()) r.fail(0, "'[['", "empty input");
  r.list([&] {
    if (pts.size() >= max_points)
      throw InvalidArgument("more than " + std::to_string(max_points) + " control points");
    pts.emplace_back();
    r.list([&] { pts.back().push_back(r.number()); });
  });
  r.finish();
  std::vector<Rational> w;
  if (!weights.empty()) {
    ListReader rw(weights, "weights");
    if (rw.at_end()) rw.fail(0, "'['", "empty input");
    rw.list([&] {
      if (w.size() >= max_points) throw InvalidArgument("more than " + std::to_string(max_points) + " weights");
      w.push_back(rw.number());
    });
    rw.finish();
  }
  return BezierCurve(std::move(pts), std::move(w));
}

std::vector<Rational> BezierCurve::weights() const {
  if (!weights_.empty()) return weights_;
  return std::vector<Rational>(points_.size(), Rational(1));
}

namespace {

Integer lcm(const Integer& a, const Integer& b) {
  Integer r;
  fmpz_lcm(r.get(), a.get(), b.get());
  return r;
}

Integer binom(unsigned long n, unsigned long k) {
  Integer r;
  fmpz_bin_uiui(r.get(), n, k);
  return r;
}

// The power-basis polynomial sum_i c_i binom(n, i) t^i (1 - t)^(n - i):
// its t^k coefficient is binom(n, k) (Delta^k c)_0 (forward differences).
Poly bernstein_to_power(std::vector<Integer> c) {
  const std::size_t n = c.size() - 1;
  Poly out;
  for (std::size_t k = 0; k <= n; ++k) {
    Integer a = binom(n, k) * c[0];
    fmpz_poly_set_coeff_fmpz(out.get(), static_cast<slong>(k), a.get());
    for (std::size_t j = 0; j + 1 < c.size() - k; ++j) c[j] = c[j + 1] - c[j];
  }
  return out;
}

}  // namespace

Curve BezierCurve::to_curve() const {
  const std::vector<Rational> v = weights();
  const std::size_t n1 = points_.size(), d = dimension();
  // Common denominator of every v_i p_ik and v_i.
  Integer L(1);
  for (std::size_t i = 0; i < n1; ++i) {
    L = lcm(L, v[i].den());
    for (std::size_t k = 0; k < d; ++k) L = lcm(L, (v[i] * points_[i][k]).den());
  }
  const Rational Lq{L};
  std::vector<Integer> den(n1);
  for (std::size_t i = 0; i < n1; ++i) den[i] = (v[i] * Lq).num();
  const Poly D = bernstein_to_power(den);
  std::vector<RatFunc> comps;
  BernsteinForm b;
  for (std::size_t k = 0; k < d; ++k) {
    std::vector<Integer> c(n1);
    for (std::size_t i = 0; i < n1; ++i) c[i] = (v[i] * points_[i][k] * Lq).num();
    comps.emplace_back(bernstein_to_power(c), D);
    b.num.push_back(std::move(c));
  }
  b.den = std::move(den);
  // The speed evaluates the curve from these coefficients (no power basis's
  // alternating coefficients); the exact algebra uses comps.
  return Curve(std::move(comps), std::move(b));
}

std::string BezierCurve::str() const {
  std::string s = "[";
  for (std::size_t i = 0; i < points_.size(); ++i) {
    s += i ? ", [" : "[";
    for (std::size_t k = 0; k < points_[i].size(); ++k) s += (k ? ", " : "") + points_[i][k].str();
    s += "]";
  }
  return s + "]";
}

// -------------------------------------------------------------- QuadraticSurd

namespace {

// n = k^2 c with the square factors of every prime below 2^16 and a final
// perfect square removed. \pre n > 0.
void square_part(const Integer& n, Integer& k, Integer& c) {
  c = n;
  k = Integer(1);
  Integer p2;
  for (unsigned long p = 2; p < 65536; ++p) {
    fmpz_set_ui(p2.get(), p * p);
    if (fmpz_cmp(p2.get(), c.get()) > 0) break;  // c has no square factor >= p^2
    while (fmpz_divisible(c.get(), p2.get())) {
      fmpz_divexact(c.get(), c.get(), p2.get());
      fmpz_mul_ui(k.get(), k.get(), p);
    }
  }
  if (fmpz_is_square(c.get())) {
    Integer s;
    fmpz_sqrt(s.get(), c.get());
    k = k * s;
    c = Integer(1);
  }
}

}  // namespace

QuadraticSurd::QuadraticSurd(const Rational& q) : x_(q), y_(0), c_(1) {}
QuadraticSurd::QuadraticSurd(Rational x, Rational y, Integer c)
    : x_(std::move(x)), y_(std::move(y)), c_(std::move(c)) {
  if (y_.is_zero()) c_ = Integer(1);
}

QuadraticSurd QuadraticSurd::make(const Rational& x, const Rational& y, const Rational& r) {
  if (r.sign() < 0) throw InvalidArgument("QuadraticSurd: square root of the negative number " + r.str());
  if (y.is_zero() || r.is_zero()) return QuadraticSurd(x);
  // sqrt(p/q) = sqrt(p q) / q = k sqrt(c) / q.
  Integer k, c;
  square_part(r.num() * r.den(), k, c);
  const Rational coef = y * Rational(k, r.den());
  if (c == Integer(1)) return QuadraticSurd(x + coef);
  return QuadraticSurd(x, coef, c);
}

const Rational& QuadraticSurd::rational() const {
  if (!is_rational()) throw InvalidArgument("QuadraticSurd::rational(): " + str() + " is irrational");
  return x_;
}

Integer QuadraticSurd::d() const { return lcm(x_.den(), y_.den()); }
Integer QuadraticSurd::a() const { return (x_ * Rational(d())).num(); }
Integer QuadraticSurd::b() const { return (y_ * Rational(d())).num(); }

Ball QuadraticSurd::to_ball(long prec) const {
  Ball v;
  if (is_rational()) {
    arb_set_fmpq(v.get(), x_.get(), prec);
    return v;
  }
  // x and y sqrt(c) may cancel: raise the working precision until the
  // relative accuracy is reached (the value is irrational, hence nonzero).
  for (long wp = prec + 32;; wp *= 2) {
    Ball s, t;
    arb_set_fmpz(s.get(), c_.get());
    arb_sqrt(s.get(), s.get(), wp);
    arb_set_fmpq(t.get(), y_.get(), wp);
    arb_mul(s.get(), s.get(), t.get(), wp);
    arb_set_fmpq(t.get(), x_.get(), wp);
    arb_add(v.get(), s.get(), t.get(), wp);
    if (arb_rel_accuracy_bits(v.get()) >= prec || wp > (1L << 24)) return v;
  }
}

int QuadraticSurd::sign() const {
  const int sx = x_.sign(), sy = y_.sign();
  if (sy == 0) return sx;
  if (sx == 0 || sx == sy) return sy;
  // opposite signs: compare x^2 with y^2 c
  const Rational lhs = x_ * x_, rhs = y_ * y_ * Rational(c_);
  return lhs > rhs ? sx : sy;
}

std::string QuadraticSurd::str(Format f) const {
  if (is_rational()) return format_rational(x_, f);
  // d = lcm of the denominators once; a = x d and b = y d by exact division
  // (the same integers as a(), b(), d(), without a gcd per coordinate).
  const Integer Dv = d();
  Integer A, Bv;
  fmpz_divexact(A.get(), Dv.get(), fmpq_denref(x_.get()));
  fmpz_mul(A.get(), A.get(), fmpq_numref(x_.get()));
  fmpz_divexact(Bv.get(), Dv.get(), fmpq_denref(y_.get()));
  fmpz_mul(Bv.get(), Bv.get(), fmpq_numref(y_.get()));
  const bool latex = f == Format::Latex;
  Integer absb = Bv;
  fmpz_abs(absb.get(), absb.get());
  std::string root = latex ? "\\sqrt{" + c_.str() + "}" : "sqrt(" + c_.str() + ")";
  std::string bterm = absb == Integer(1) ? root : absb.str() + (latex ? " " : "*") + root;
  std::string num;
  if (A.sign() == 0) num = (Bv.sign() < 0 ? "-" : "") + bterm;
  else num = A.str() + (Bv.sign() < 0 ? " - " : " + ") + bterm;
  if (Dv == Integer(1)) return num;
  if (latex) return "\\frac{" + num + "}{" + Dv.str() + "}";
  return (A.sign() == 0 ? num : "(" + num + ")") + "/" + Dv.str();
}

namespace {
Integer common_root(const QuadraticSurd& p, const QuadraticSurd& q) {
  if (p.is_rational()) return q.c();
  if (q.is_rational() || p.c() == q.c()) return p.c();
  throw InvalidArgument("QuadraticSurd: sqrt(" + p.c().str() + ") and sqrt(" + q.c().str() +
                        ") are in different fields");
}
}  // namespace

QuadraticSurd operator+(const QuadraticSurd& p, const QuadraticSurd& q) {
  Integer c = common_root(p, q);
  return QuadraticSurd(p.x_ + q.x_, p.y_ + q.y_, c);
}
QuadraticSurd operator-(const QuadraticSurd& p, const QuadraticSurd& q) {
  Integer c = common_root(p, q);
  return QuadraticSurd(p.x_ - q.x_, p.y_ - q.y_, c);
}
namespace {
thread_local std::size_t t_full_products = 0;
}  // namespace

std::size_t QuadraticSurd::full_products() { return t_full_products; }

QuadraticSurd operator*(const QuadraticSurd& p, const QuadraticSurd& q) {
  Integer c = common_root(p, q);
  // The terms that are zero are left out: a rational factor, or a factor
  // y sqrt(c) (as in the recurrence of the Bezier weights), costs two
  // rational products instead of four products and two sums.
  if (p.is_rational()) return QuadraticSurd(p.x_ * q.x_, p.x_ * q.y_, c);
  if (q.is_rational()) return QuadraticSurd(p.x_ * q.x_, p.y_ * q.x_, c);
  if (q.x_.is_zero()) return QuadraticSurd(p.y_ * (q.y_ * Rational(c)), p.x_ * q.y_, c);
  if (p.x_.is_zero()) return QuadraticSurd(q.y_ * (p.y_ * Rational(c)), q.x_ * p.y_, c);
  ++t_full_products;
  return QuadraticSurd(p.x_ * q.x_ + p.y_ * q.y_ * Rational(c), p.x_ * q.y_ + p.y_ * q.x_, c);
}

// -------------------------------------------------------------- eq. (21)

BezierMoments bezier_moments(const BezierCurve& b) {
  if (b.is_rational())
    throw InvalidArgument("bezier_moments: exact moments need an integral Bezier curve (no weights)");
  const auto& P = b.points();
  const std::size_t n = static_cast<std::size_t>(b.degree()), d = b.dimension();
  // Scale the points to integers by L; then dp_i . dp_j scales by L^2.
  Integer L(1);
  for (const auto& p : P)
    for (const auto& x : p) L = lcm(L, x.den());
  const Rational Lq{L};
  // G_k = sum_{i+j=k} binom(n-1,i) binom(n-1,j) dp_i . dp_j = sum over the
  // coordinates of the square of e(t) = sum_i binom(n-1,i) dp_ik t^i.
  Poly G;
  for (std::size_t k = 0; k < d; ++k) {
    Poly e;
    for (std::size_t i = 0; i < n; ++i) {
      Integer dp = ((P[i + 1][k] - P[i][k]) * Lq).num();
      Integer coef = binom(n - 1, i) * dp;
      fmpz_poly_set_coeff_fmpz(e.get(), static_cast<slong>(i), coef.get());
    }
    G = G + e * e;
  }
  Rational A(0), B(0), C(0);
  for (long k = 0; k <= G.degree(); ++k) {
    const Integer g = G.coeff(k);
    if (g.sign() == 0) continue;
    const auto uk = static_cast<unsigned long>(k);
    A = A + Rational(g, binom(2 * n, uk));
    B = B + Rational(g * Integer(2), binom(2 * n, uk + 1));
    C = C + Rational(g, binom(2 * n, uk + 2));
  }
  const Rational scale = Rational(Integer(static_cast<long>(n * n)), Integer(static_cast<long>(2 * n + 1)) * L * L);
  return {A * scale, B * scale, C * scale};
}

// -------------------------------------------------------------- the optimum

namespace {

// w_i = v_i (1 - alpha)^i alpha^(n - i) in ball arithmetic.
std::vector<Ball> ball_weights(const std::vector<Rational>& v, const Ball& alpha, long prec) {
  const std::size_t n1 = v.size();
  std::vector<Ball> pa(n1), pb(n1), w(n1);
  Ball one_minus;
  arb_sub_si(one_minus.get(), alpha.get(), 1, prec);
  arb_neg(one_minus.get(), one_minus.get());
  pa[0] = Ball(1);
  pb[0] = Ball(1);
  for (std::size_t k = 1; k < n1; ++k) {
    arb_mul(pa[k].get(), pa[k - 1].get(), alpha.get(), prec);
    arb_mul(pb[k].get(), pb[k - 1].get(), one_minus.get(), prec);
  }
  for (std::size_t i = 0; i < n1; ++i) {
    arb_mul(w[i].get(), pb[i].get(), pa[n1 - 1 - i].get(), prec);
    Ball vi(v[i], prec);
    arb_mul(w[i].get(), w[i].get(), vi.get(), prec);
  }
  return w;
}

// v_i (1 - alpha)^i alpha^(n - i), i = 0..n, for alpha = 1 / (1 + sr):
// (1 - alpha) / alpha = sr, so the unweighted terms u_i = (1 - alpha)^i
// alpha^(n - i) satisfy u_0 = alpha^n (binary powering) and u_{i+1} = u_i sr.
// Each step multiplies the coordinates of u_i by the small rationals of sr
// (sr = y sqrt(c) or rational): O(size of u_i) instead of a product of two
// large surds, so the cost is about n times the size of alpha^n.
// The values, hence their canonical forms, are those of the definition.
std::vector<QuadraticSurd> bilinear_weights(const std::vector<Rational>& v, const QuadraticSurd& alpha,
                                            const QuadraticSurd& sr) {
  const std::size_t n1 = v.size();
  QuadraticSurd u(Rational(1)), base = alpha;
  for (std::size_t e = n1 - 1; e > 0; e >>= 1) {
    if (e & 1) u = u * base;
    if (e > 1) base = base * base;
  }
  std::vector<QuadraticSurd> w;
  w.reserve(n1);
  for (std::size_t i = 0; i < n1; ++i) {
    if (i > 0) u = u * sr;
    w.push_back(v[i] == Rational(1) ? u : QuadraticSurd(v[i]) * u);
  }
  return w;
}

BezierResult optimal_integral(const BezierCurve& bz, const Curve& curve, const Options& opt) {
  BezierResult r;
  r.exact = true;
  const BezierMoments m = bezier_moments(bz);
  r.P_exact = -m.A;
  r.Q_exact = m.C;
  r.B_exact = m.B;
  r.mean_square_exact = m.A + m.B + m.C;
  // alpha = 1 / (1 + sqrt(rho)), rho = C / A = Q / (-P) > 0.
  const Rational rho = m.C / m.A;
  const QuadraticSurd sr = QuadraticSurd::make(Rational(0), Rational(1), rho);
  if (sr.is_rational()) {
    r.alpha_exact = QuadraticSurd(Rational(1) / (Rational(1) + sr.rational()));
    r.alpha_algebraic = RealAlgebraic(r.alpha_exact->rational());
  } else {
    // 1 / (1 + y sqrt c) = (1 - y sqrt c) / (1 - y^2 c), y^2 c != 1 (c is not a square)
    const Rational y = sr.y(), den = Rational(1) - y * y * Rational(sr.c());
    r.alpha_exact = QuadraticSurd::make(Rational(1) / den, -y / den, Rational(sr.c()));
    // (Q + P) a^2 - 2 P a + P = (C - A) a^2 + 2 A a - A, cleared of denominators.
    const Rational c2 = m.C - m.A, c1 = Rational(2) * m.A, c0 = -m.A;
    const Integer Lden = lcm(lcm(c2.den(), c1.den()), c0.den());
    const Rational Lq{Lden};
    Poly f(std::vector<Integer>{(c0 * Lq).num(), (c1 * Lq).num(), (c2 * Lq).num()});
    // f(0) = P < 0 < Q = f(1): exactly one root in (0, 1); f is irreducible.
    r.alpha_algebraic = RealAlgebraic(f.primitive(), Rational(0), Rational(1));
  }
  const std::vector<Rational> v = bz.weights();
  r.weights_exact = bilinear_weights(v, *r.alpha_exact, sr);

  const Speed sp(curve, SpeedKind::Parametric);
  const long d = opt.digits + 1;
  for (long bits = digits_to_bits(opt.digits) + 8;; bits += 32) {
    const long prec = 2 * bits + 64;
    r.P = Ball(*r.P_exact, prec);
    r.Q = Ball(*r.Q_exact, prec);
    r.alpha = r.alpha_exact->to_ball(prec);
    r.weights.clear();
    for (const auto& w : r.weights_exact) r.weights.push_back(w.to_ball(prec));
    r.mu = integrate_speed(sp, RealAlgebraic(0), RealAlgebraic(1), bits, opt.max_prec);
    Ball mu2, L(*r.mean_square_exact, prec), A(m.A, prec), B(m.B, prec), C(m.C, prec), M;
    arb_mul(mu2.get(), r.mu.get(), r.mu.get(), prec);
    arb_div(r.u_before.get(), mu2.get(), L.get(), prec);
    arb_mul(M.get(), A.get(), C.get(), prec);
    arb_sqrt(M.get(), M.get(), prec);
    arb_mul_2exp_si(M.get(), M.get(), 1);
    arb_add(M.get(), M.get(), B.get(), prec);
    arb_div(r.u_after.get(), mu2.get(), M.get(), prec);
    if (r.mu.meets_digits(d) && r.u_before.meets_digits(d) && r.u_after.meets_digits(d) && r.alpha.meets_digits(d) &&
        all_meet_digits(r.weights, d))
      return r;
    if (bits > opt.max_prec)
      throw BudgetExceeded("could not certify the arc length and uniformity to " + std::to_string(opt.digits) +
                           " digits within " + std::to_string(opt.max_prec) +
                           " bits of working precision (raise it with --max-prec)");
  }
}

BezierResult optimal_rational(const BezierCurve& bz, const Curve& curve, const Options& opt) {
  const std::vector<Rational> v = bz.weights();
  const long d = opt.digits + 1;
  // The weights lose up to log10(n) digits against alpha: ask for more.
  Options o = opt;
  o.digits = opt.digits + static_cast<long>(std::to_string(v.size()).size()) + 1;
  for (;; o.digits += 10) {
    if (o.digits > kMaxEngineDigits) o.digits = kMaxEngineDigits;
    const MoebiusResult mr = moebius_optimal(curve, SpeedKind::Parametric, o);
    BezierResult r;
    r.exact = false;
    const PieceIntegrals& pi = mr.integrals.at(0);
    arb_neg(r.P.get(), pi.A.get());
    r.Q = pi.C;
    r.alpha = pi.alpha;
    r.mu = mr.mu;
    r.u_before = mr.u_before;
    r.u_after = mr.u_after;
    const long prec = 2 * digits_to_bits(o.digits) + 64;
    r.weights = ball_weights(v, r.alpha, prec);
    if (all_meet_digits(r.weights, d) || o.digits >= kMaxEngineDigits) {
      if (!all_meet_digits(r.weights, d))
        throw BudgetExceeded("could not certify the new weights to " + std::to_string(opt.digits) + " digits");
      return r;
    }
  }
}

}  // namespace

BezierResult bezier_optimal(const BezierCurve& b, const Options& opt) {
  validate(opt);
  if (b.degree() > opt.max_degree)
    throw InvalidArgument("the Bezier curve has degree " + std::to_string(b.degree()) + ", above the limit " +
                          std::to_string(opt.max_degree) + " (raise it with --max-degree)");
  const Curve c = b.to_curve();
  check_degree(c, opt);
  return b.is_rational() ? optimal_rational(b, c, opt) : optimal_integral(b, c, opt);
}

}  // namespace uniparam
