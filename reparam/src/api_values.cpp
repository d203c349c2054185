// The facade's value types (uniparam/uniparam.hpp): Rational, Ball, Options,
// Curve, Nurbs.
#include <cmath>

#include "api_impl.hpp"
#include "uniparam/reparam/step.hpp"

namespace uniparam {
namespace api {

using detail::guarded;
using detail::unwrap;
using detail::wrap;

// ---- Options ----

namespace detail {

uniparam::SpeedKind kind_of(const Options& o) {
  switch (o.speed) {
    case SpeedKind::Angular: return uniparam::SpeedKind::Angular;
    case SpeedKind::Parametric: return uniparam::SpeedKind::Parametric;
  }
  throw InvalidArgument("Options::speed must be SpeedKind::Angular or SpeedKind::Parametric");
}

namespace {
void in_range(const char* field, long v, long lo, long hi) {
  if (v < lo || v > hi)
    throw InvalidArgument(std::string("Options::") + field + " must be from " + std::to_string(lo) + " to " +
                          std::to_string(hi) + ", got " + std::to_string(v));
}
}  // namespace

uniparam::Options engine_options(const Options& o) {
  kind_of(o);
  in_range("digits", o.digits, 1, kMaxDigits);
  if (o.max_prec != 0) in_range("max_prec", o.max_prec, 64, 1L << 24);
  in_range("max_degree", o.max_degree, 1, 20000);
  if (o.max_input_length < 1 || o.max_input_length > (std::size_t(1) << 30))
    throw InvalidArgument("Options::max_input_length must be from 1 to 1073741824, got " +
                          std::to_string(o.max_input_length));
  if (o.threads > 64)
    throw InvalidArgument("Options::threads must be from 0 (the default) to 64, got " + std::to_string(o.threads));
  if (!(o.time_limit == 0 || (std::isfinite(o.time_limit) && o.time_limit > 0 && o.time_limit <= 1e9)))
    throw InvalidArgument("Options::time_limit must be 0 (none) or positive seconds up to 1e9");
  uniparam::Options io;
  io.digits = o.digits;
  io.max_prec = o.max_prec == 0 ? default_max_prec(o.digits) : o.max_prec;
  io.max_degree = o.max_degree;
  return io;
}

std::string facade_message(std::string m) {
  static const std::pair<const char*, const char*> names[] = {
      {"--timeout SECONDS", "Options::time_limit"},
      {"--timeout", "Options::time_limit"},
      {"--max-prec", "Options::max_prec"},
      {"--max-degree", "Options::max_degree"},
      {"--max-length", "Options::max_input_length"},
      {"--digits", "Options::digits"},
      {"--threads", "Options::threads"},
      {"--speed parametric", "Options::speed = SpeedKind::Parametric"},
      {"--rational-digits", "rational_digits"},
      {"--pieces", "pieces"},
      {"--target", "the target"},
      {"raise it with --max-bits", "a fixed limit of the library"},
      {"raise it with --max-depth", "a fixed limit of the library"},
  };
  for (const auto& [from, to] : names)
    for (std::size_t at = m.find(from); at != std::string::npos; at = m.find(from, at + 1)) {
      const std::size_t end = at + std::string(from).size();
      if (end < m.size() && (std::isalnum(static_cast<unsigned char>(m[end])) || m[end] == '-')) continue;
      m.replace(at, end - at, to);
    }
  return m;
}

}  // namespace detail

// ---- Rational ----

Rational::Rational() : p_(std::make_shared<const Impl>(Impl{uniparam::Rational(0)})) {}
Rational::Rational(long n) : p_(std::make_shared<const Impl>(Impl{uniparam::Rational(n)})) {}
Rational::Rational(long num, long den) : p_(std::make_shared<const Impl>(Impl{uniparam::Rational(num, den)})) {}

Rational Rational::parse(const std::string& text) {
  const auto e = text.find_first_of("eE");
  if (text.size() > 100000 || (e != std::string::npos && text.size() - e > 5))
    throw InvalidArgument("the number '" + text.substr(0, 20) + (text.size() > 20 ? "..." : "") +
                          "' is too large (at most 100000 characters and a decimal exponent below 1000)");
  return wrap(uniparam::Rational::parse(text));
}

std::string Rational::str() const { return p_->v.str(); }
std::string Rational::num() const { return p_->v.num().str(); }
std::string Rational::den() const { return p_->v.den().str(); }
int Rational::sign() const { return p_->v.sign(); }
bool operator==(const Rational& a, const Rational& b) { return unwrap(a) == unwrap(b); }
bool operator<(const Rational& a, const Rational& b) { return unwrap(a) < unwrap(b); }

// ---- Ball ----

Ball::Ball() : p_(std::make_shared<const Impl>(Impl{uniparam::Ball(0)})) {}

namespace {
void check_finite(const uniparam::Ball& b) {
  if (!b.is_finite()) throw DomainError("the ball is not finite");
}
}  // namespace

Rational Ball::mid() const {
  check_finite(p_->v);
  return wrap(mid_rational(p_->v));
}

Rational Ball::rad() const {
  check_finite(p_->v);
  return wrap(rad_rational(p_->v));
}

Rational Ball::lower() const { return wrap(unwrap(mid()) - unwrap(rad())); }
Rational Ball::upper() const { return wrap(unwrap(mid()) + unwrap(rad())); }
bool Ball::is_exact() const { return p_->v.is_exact(); }
bool Ball::contains(const Rational& x) const { return p_->v.contains(unwrap(x)); }
bool Ball::contains(const Ball& b) const { return p_->v.contains(unwrap(b)); }
bool Ball::meets_digits(long digits) const { return p_->v.meets_digits(digits); }
std::string Ball::str(long digits) const { return p_->v.str(digits); }
std::string Ball::mid_decimal(long digits) const { return p_->v.mid_decimal(digits); }
std::string Ball::rad_decimal() const { return p_->v.rad_decimal(); }
double Ball::to_double_uncertified() const { return mid_double(p_->v); }

// ---- Curve ----

namespace {

void check_length(const std::string& what, const std::string& text, const Options& o) {
  if (text.size() > o.max_input_length)
    throw BudgetExceeded(what + ": the text holds " + std::to_string(text.size()) + " characters, more than " +
                         std::to_string(o.max_input_length) + " (raise it with Options::max_input_length)");
}

void check_segments_degree(const CompositeCurve& cc, const uniparam::Options& io) {
  for (std::size_t j = 0; j < cc.size(); ++j) check_degree(cc.segment(j), io);
}

Curve make_curve(CompositeCurve cc, std::optional<BezierCurve> b, const uniparam::Options& io) {
  check_segments_degree(cc, io);
  auto impl = std::make_shared<Curve::Impl>(std::move(cc));
  impl->bezier = std::move(b);
  return Curve(std::shared_ptr<const Curve::Impl>(std::move(impl)));
}

Curve from_path(const PathInput& p, const uniparam::Options& io) {
  std::vector<uniparam::Curve> segs;
  for (const auto& b : p.segments) segs.push_back(b.to_curve());
  std::optional<BezierCurve> b;
  if (p.segments.size() == 1) b = p.segments.front();
  return make_curve(CompositeCurve(std::move(segs), p.knots, p.labels), std::move(b), io);
}

Curve from_bezier(const BezierCurve& b, const uniparam::Options& io) {
  if (b.degree() > io.max_degree)
    throw BudgetExceeded("the Bezier curve has degree " + std::to_string(b.degree()) + ", above the limit " +
                         std::to_string(io.max_degree) + " (raise it with Options::max_degree)");
  return make_curve(CompositeCurve(b.to_curve()), b, io);
}

}  // namespace

Curve Curve::parse(const std::string& text, const Options& o) {
  return guarded(o, [&] {
    const uniparam::Options io = detail::engine_options(o);
    check_length("curve", text, o);
    ParseLimits lim;
    lim.max_length = o.max_input_length;
    lim.max_degree = o.max_degree;
    lim.max_exponent = o.max_degree;
    return make_curve(CompositeCurve(uniparam::Curve::parse(text, lim)), std::nullopt, io);
  });
}

Curve Curve::bezier(const std::vector<std::vector<Rational>>& points, const std::vector<Rational>& weights,
                    const Options& o) {
  return guarded(o, [&] {
    const uniparam::Options io = detail::engine_options(o);
    std::vector<std::vector<uniparam::Rational>> P;
    for (const auto& p : points) {
      P.emplace_back();
      for (const auto& x : p) P.back().push_back(unwrap(x));
    }
    std::vector<uniparam::Rational> W;
    for (const auto& w : weights) W.push_back(unwrap(w));
    return from_bezier(BezierCurve(std::move(P), std::move(W)), io);
  });
}

Curve Curve::bezier(const std::string& control, const std::string& weights, const Options& o) {
  return guarded(o, [&] {
    const uniparam::Options io = detail::engine_options(o);
    check_length("control points", control, o);
    check_length("weights", weights, o);
    BezierCurve b = BezierCurve::parse(control, weights, static_cast<std::size_t>(o.max_degree) + 1);
    if (!weights.empty() && !b.is_rational()) throw InvalidArgument("weights: empty list");
    return from_bezier(b, io);
  });
}

std::vector<Curve> Curve::svg_path(const std::string& d, const Options& o) {
  return guarded(o, [&] {
    const uniparam::Options io = detail::engine_options(o);
    check_length("SVG path data", d, o);
    SvgLimits lim;
    lim.max_length = o.max_input_length;
    std::vector<Curve> out;
    for (const PathInput& p : parse_svg_path(d, lim)) out.push_back(from_path(p, io));
    return out;
  });
}

Curve Curve::nurbs_json(const std::string& json, const Options& o) {
  return guarded(o, [&] {
    const uniparam::Options io = detail::engine_options(o);
    check_length("NURBS JSON", json, o);
    NurbsLimits lim;
    lim.max_degree = o.max_degree;
    return from_path(parse_nurbs(json, lim), io);
  });
}

std::size_t Curve::dimension() const { return p_->cc.dimension(); }
std::size_t Curve::segments() const { return p_->cc.size(); }
long Curve::degree() const { return p_->cc.degree(); }
bool Curve::is_bezier() const { return p_->bezier.has_value(); }

std::vector<Rational> Curve::knots() const {
  std::vector<Rational> out;
  for (const auto& k : p_->cc.knots()) out.push_back(wrap(k));
  return out;
}

std::string Curve::str() const {
  std::string s;
  for (std::size_t j = 0; j < p_->cc.size(); ++j) s += (j ? "; " : "") + p_->cc.segment(j).str();
  return s;
}

// ---- Nurbs ----

long Nurbs::degree() const { return p_->n.degree; }
std::size_t Nurbs::dimension() const { return p_->n.dimension; }
bool Nurbs::exact() const { return p_->n.kind == uniparam::Nurbs::Kind::Exact; }
std::vector<Ball> Nurbs::knots() const { return wrap(p_->n.knots); }
std::vector<Ball> Nurbs::weights() const { return wrap(p_->n.weights); }

std::vector<std::vector<Ball>> Nurbs::points() const {
  std::vector<std::vector<Ball>> out;
  for (const auto& p : p_->n.points) out.push_back(wrap(p));
  return out;
}

std::vector<Rational> Nurbs::knots_exact() const {
  std::vector<Rational> out;
  for (const auto& q : p_->n.knots_exact) out.push_back(wrap(q));
  return out;
}

std::vector<std::vector<Rational>> Nurbs::points_exact() const {
  std::vector<std::vector<Rational>> out;
  for (const auto& p : p_->n.points_exact) {
    out.emplace_back();
    for (const auto& q : p) out.back().push_back(wrap(q));
  }
  return out;
}

std::vector<Rational> Nurbs::weights_exact() const {
  std::vector<Rational> out;
  for (const auto& q : p_->n.weights_exact) out.push_back(wrap(q));
  return out;
}

std::vector<std::string> Nurbs::weights_text() const {
  std::vector<std::string> out;
  for (const auto& w : p_->n.weights_surd) out.push_back(w.str());
  return out;
}

std::string Nurbs::step(const std::string& name) const {
  for (char c : name)
    if (c == '\'' || c == '\\' || static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126)
      throw InvalidArgument("Nurbs::step: the name must be printable ASCII without quotes or backslashes");
  return step_text(p_->n, name);
}

}  // namespace api
}  // namespace uniparam
