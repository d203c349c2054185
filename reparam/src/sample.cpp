// One interface to the reparameterizations, and certified equally spaced
// samples of p o r.
#include "uniparam/reparam/sample.hpp"

#include <acb.h>

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
  if (const auto* x = radical_result()) return radical_eval_r(*x, s, prec);
  return moebius_eval_r(*moebius_result(), s, prec);
}

Ball Reparameterization::eval_speed(const Speed& sp, const Ball& s, long prec) const {
  check_unit(s, "Reparameterization::eval_speed");
  if (acts_as_identity(*this)) {
    acb_t z, w;
    acb_init(z);
    acb_init(w);
    acb_set_arb(z, s.get());
    sp.eval_squared(w, z, prec);
    Ball v;
    arb_sqrtpos(v.get(), acb_realref(w), prec);  // sigma^2 >= 0 mathematically
    acb_clear(z);
    acb_clear(w);
    return v;
  }
  if (const auto* x = radical_result()) return radical_eval_speed(*x, sp, s, prec);
  return moebius_eval_speed(*moebius_result(), sp, s, prec);
}

std::vector<Ball> Reparameterization::eval_point(const Curve& c, const Ball& s, long prec) const {
  const Ball t = eval_r(s, prec);
  return c.eval(t, prec);
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

SamplePoint sample_one(const Curve& c, const Speed& sp, const Reparameterization& r, const Rational& s, long digits,
                       long max_prec) {
  SamplePoint out;
  out.s = s;
  for (std::size_t i = 1; i + 1 < r.joints_s().size(); ++i)
    if (r.joints_s()[i].contains(s)) out.at_joint = true;
  double last = HUGE_VAL;
  for (long prec = digits_to_bits(digits) + 32;; prec *= 2) {
    check_time_budget();  // up to a million samples, each a few precision steps
    const Ball sb(s, prec);
    out.t = r.eval_r(sb, prec);
    out.point = r.eval_point(c, sb, prec);
    out.speed = r.eval_speed(sp, sb, prec);
    bool ok = out.t.meets_digits(digits);
    double worst = rel_rad(out.t);
    for (const auto& b : out.point) {
      ok = ok && b.meets_digits(digits);
      worst = std::max(worst, rel_rad(b));
    }
    if (!out.at_joint) {
      ok = ok && out.speed.meets_digits(digits);
      worst = std::max(worst, rel_rad(out.speed));
    }
    if (ok) return out;
    // Stop when doubling the precision no longer halves the error: the
    // accuracy is then limited by r's data, not by the working precision.
    const bool stalled = prec * 2 > max_prec || !(worst < 0.5 * last);
    if (stalled && out.at_joint) return out;  // enclosures, exempt from `digits` (see SamplePoint)
    if (stalled)
      throw BudgetExceeded("could not certify the sample at s = " + s.str() + " to " + std::to_string(digits) +
                           " digits (working precision " + std::to_string(prec) +
                           " bits); the reparameterization must be computed with more digits than its samples");
    last = worst;
  }
}

}  // namespace

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
  if (digits < 1 || digits > 10000) throw InvalidArgument("sample: digits must be between 1 and 10000");
  const Reparameterization id = Reparameterization::identity(r.mu(), r.u_before());
  Samples out;
  out.before.reserve(static_cast<std::size_t>(K));
  out.after.reserve(static_cast<std::size_t>(K));
  for (long k = 0; k < K; ++k) {
    const Rational s(k, K - 1);
    out.before.push_back(sample_one(c, sp, id, s, digits, max_prec));
    out.after.push_back(sample_one(c, sp, r, s, digits, max_prec));
  }
  return out;
}

double mid_double(const Ball& b) { return arf_get_d(arb_midref(b.get()), ARF_RND_NEAR); }

}  // namespace uniparam
