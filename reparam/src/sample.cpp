// One interface to the reparameterizations, and certified equally spaced
// samples of p o r.
#include "uniparam/reparam/sample.hpp"

#include <algorithm>
#include <cmath>

#include "uniparam/core/ball_poly.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {

Reparameterization Reparameterization::identity(const Ball& mu, const Ball& u) {
  Reparameterization r;
  r.s_ = {Ball(0), Ball(1)};
  r.t_ = {RealAlgebraic(0), RealAlgebraic(1)};
  r.mu_ = mu;
  r.u_before_ = u;
  r.u_after_ = u;
  return r;
}

namespace {

// The joints (T in t, `joints` in the new parameter) and the summary of a
// radical or Moebius result.
template <class R>
void take_summary(const R& x, const std::vector<Ball>& joints, std::vector<Ball>& s, std::vector<RealAlgebraic>& t,
                  Ball& mu, Ball& u_before, Ball& u_after) {
  s = joints;
  for (const auto& b : x.T) t.push_back(b.t);
  mu = x.mu;
  u_before = x.u_before;
  u_after = x.u_after;
}

}  // namespace

Reparameterization::Reparameterization(RadicalResult r) : result_(std::move(r)) {
  const auto& x = std::get<RadicalResult>(result_);
  take_summary(x, x.Z, s_, t_, mu_, u_before_, u_after_);
  init_common();
}

Reparameterization::Reparameterization(MoebiusResult r) : result_(std::move(r)) {
  const auto& x = std::get<MoebiusResult>(result_);
  take_summary(x, x.S, s_, t_, mu_, u_before_, u_after_);
  init_common();
}

void Reparameterization::init_common() {
  if (s_.size() != t_.size() || s_.size() < 2)
    throw InvalidArgument("Reparameterization: the result has inconsistent joints");
  s_.front() = Ball(0);
  s_.back() = Ball(1);
}

std::string Reparameterization::method() const {
  if (radical_result()) return "radical";
  if (const auto* m = moebius_result()) return std::string(to_string(m->continuity)) + " piecewise Moebius";
  return "none";
}

bool Reparameterization::is_identity() const { return std::holds_alternative<std::monostate>(result_); }

const RadicalResult* Reparameterization::radical_result() const { return std::get_if<RadicalResult>(&result_); }

const MoebiusResult* Reparameterization::moebius_result() const { return std::get_if<MoebiusResult>(&result_); }

namespace {

void check_unit(const Ball& s, const char* what) {
  Ball zero(0), one(1);
  if (arb_lt(s.get(), zero.get()) || arb_gt(s.get(), one.get()))
    throw InvalidArgument(std::string(what) + ": s must lie in [0, 1]");
}

// r = id: both methods document r = id for an identically zero speed (the
// angular speed of a line), where their alpha is 0/0.
bool acts_as_identity(const Reparameterization& r) {
  if (r.is_identity()) return true;
  if (const auto* x = r.radical_result()) return x->identically_zero;
  return r.moebius_result()->identically_zero;
}

}  // namespace

Ball Reparameterization::eval_r(const Ball& s, long prec) const {
  check_unit(s, "Reparameterization::eval_r");
  if (acts_as_identity(*this)) return s;
  if (const auto* x = radical_result()) return uniparam::eval_r(*x, s, prec);
  return uniparam::eval_r(*moebius_result(), s, prec);
}

Ball Reparameterization::eval_speed(const Speed& sp, const Ball& s, long prec) const {
  check_unit(s, "Reparameterization::eval_speed");
  if (acts_as_identity(*this)) {
    return sp.eval_real(s, prec);
  }
  if (const auto* x = radical_result()) return uniparam::eval_speed(*x, sp, s, prec);
  return uniparam::eval_speed(*moebius_result(), sp, s, prec);
}

namespace {

// The exact rational r(s) when s is an exact ball equal to an exact joint
// s_i whose t_i is rational (s = 0 and s = 1 always are: t = 0 and 1).
const Rational* exact_image(const Reparameterization& r, const Ball& s) {
  if (!s.is_exact()) return nullptr;
  for (std::size_t i = 0; i < r.joints_s().size(); ++i) {
    const Ball& si = r.joints_s()[i];
    if (si.is_exact() && arb_equal(si.get(), s.get()) && r.joints_t()[i].is_rational())
      return &r.joints_t()[i].rational();
  }
  return nullptr;
}

}  // namespace

std::vector<Ball> Reparameterization::eval_point(const Curve& c, const Ball& s, long prec) const {
  if (const Rational* t = exact_image(*this, s)) {
    check_unit(s, "Reparameterization::eval_point");
    std::vector<Ball> out;
    for (const RatFunc& f : c.components()) out.emplace_back(f(*t), prec);
    return out;
  }
  const Ball t = eval_r(s, prec);
  return c.eval(t, prec);
}

Reparameterization Reparameterization::refined(const Speed& sp, long digits, long max_prec) const {
  if (digits < 1) throw InvalidArgument("Reparameterization::refined: digits must be at least 1");
  if (acts_as_identity(*this)) return *this;
  if (const auto* x = radical_result()) {
    return Reparameterization(refine_radical_data(sp, *x, digits, max_prec));
  }
  return Reparameterization(refine_moebius_data(sp, *moebius_result(), digits, max_prec));
}

namespace {

// Relative error measure of a ball: rad / max(1, |mid|) as a double (only to
// decide whether more precision still helps; the contract itself is checked
// with Ball::meets_digits).
double rel_rad(const Ball& b) {
  if (!b.is_finite()) return HUGE_VAL;
  const double rad = mag_get_d(arb_radref(b.get()));
  const double mid = std::fabs(arf_get_d(arb_midref(b.get()), ARF_RND_NEAR));
  return rad / std::max(1.0, mid);
}

}  // namespace

Sampler::Sampler(const Curve& c, const Speed& sp, Reparameterization r, long digits, long max_prec)
    : c_(c), sp_(sp), r_(std::move(r)), digits_(digits), max_prec_(max_prec) {
  if (digits < 1 || digits > kMaxEngineDigits)
    throw InvalidArgument("sample: digits must be between 1 and " + std::to_string(kMaxDigits));
  if (max_prec < 64) throw InvalidArgument("sample: the precision limit must be at least 64 bits");
}

SamplePoint Sampler::at(const Rational& s) {
  if (s < Rational(0) || s > Rational(1)) throw InvalidArgument("sample: s must lie in [0, 1], got " + s.str());
  SamplePoint out;
  out.s = s;
  const long start = digits_to_bits(digits_) + 32;
  long prec = start;
  double last = HUGE_VAL;
  for (;;) {
    check_time_budget();  // up to a million samples, each a few precision steps
    out.at_joint = false;
    for (std::size_t i = 1; i + 1 < r_.joints_s().size(); ++i)
      if (r_.joints_s()[i].contains(s)) out.at_joint = true;
    const Ball sb(s, prec);
    out.point = r_.eval_point(c_, sb, prec);
    if (const Rational* t = exact_image(r_, sb)) out.t = Ball(*t, prec);
    else out.t = r_.eval_r(sb, prec);
    out.speed = r_.eval_speed(sp_, sb, prec);
    bool ok = out.t.meets_digits(digits_);
    double worst = rel_rad(out.t);
    for (const auto& b : out.point) {
      ok = ok && b.meets_digits(digits_);
      worst = std::max(worst, rel_rad(b));
    }
    if (!out.at_joint) {
      ok = ok && out.speed.meets_digits(digits_);
      worst = std::max(worst, rel_rad(out.speed));
    }
    if (ok) return out;
    // More working precision while it still halves the error; once it does
    // not, r's data limit the accuracy: refine them (twice the digits each
    // time) and go on at the same working precision.
    if ((worst < 0.5 * last || worst == HUGE_VAL) && prec * 2 <= max_prec_) {
      last = worst;
      prec *= 2;
      continue;
    }
    const long next = data_digits_ ? 2 * data_digits_ : 2 * digits_ + 8;
    if (digits_to_bits(next) > max_prec_)
      throw BudgetExceeded("could not certify the sample at s = " + s.str() + " to " + std::to_string(digits_) +
                           " digits: r's data would need more than " + std::to_string(max_prec_) +
                           " bits (raise --max-prec)");
    r_ = r_.refined(sp_, next, max_prec_);
    data_digits_ = next;
    ++refinements_;
    last = HUGE_VAL;
  }
}

void sample_each(const Curve& c, const Speed& sp, const Reparameterization& r, long K, long digits, long max_prec,
                 const SampleSink& sink) {
  if (K < 2 || K > 1000000) throw InvalidArgument("sample: the number of points must be between 2 and 1000000");
  Sampler smp(c, sp, r, digits, max_prec);
  for (long k = 0; k < K; ++k) sink(k, smp.at(Rational(k, K - 1)));
}

bool meets_digits(const Samples& s, long digits) {
  for (const auto* v : {&s.before, &s.after})
    for (const SamplePoint& p : *v) {
      if (!p.t.meets_digits(digits)) return false;
      for (const auto& b : p.point)
        if (!b.meets_digits(digits)) return false;
      if (!p.at_joint && !p.speed.meets_digits(digits)) return false;
    }
  return true;
}

Samples sample(const Curve& c, const Speed& sp, const Reparameterization& r, long K, long digits, long max_prec) {
  if (K < 2 || K > 1000000) throw InvalidArgument("sample: the number of points must be between 2 and 1000000");
  if (digits < 1 || digits > kMaxEngineDigits)
    throw InvalidArgument("sample: digits must be between 1 and " + std::to_string(kMaxDigits));
  const Reparameterization id = Reparameterization::identity(r.mu(), r.u_before());
  Samples out;
  out.before.reserve(static_cast<std::size_t>(K));
  out.after.reserve(static_cast<std::size_t>(K));
  sample_each(c, sp, id, K, digits, max_prec, [&](long, const SamplePoint& p) { out.before.push_back(p); });
  sample_each(c, sp, r, K, digits, max_prec, [&](long, const SamplePoint& p) { out.after.push_back(p); });
  return out;
}

double mid_double(const Ball& b) { return arf_get_d(arb_midref(b.get()), ARF_RND_NEAR); }

}  // namespace uniparam
