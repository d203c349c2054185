// G(t) / mu along increasing t by short integrals (ArcFraction), and the
// deviation of a reparameterization's points from the exact steps.
#include <arb.h>

#include <memory>
#include <string>

#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"
#include "locate_detail.hpp"

namespace uniparam {

using namespace locate_detail;

ArcFraction::ArcFraction(const Speed& s, long bits, const Options& opt)
    : track_(std::make_shared<SpeedTrack>(s, opt.max_prec)), bits_(bits), max_prec_(opt.max_prec), last_(0),
      G_last_(0) {
  check_not_zero_speed(s.identically_zero());
  mu_ = mean_speed(s, bits, opt);
}

ArcFraction::ArcFraction(const CompositeCurve& c, const std::vector<Speed>& speeds, long bits, const Options& opt)
    : track_(composite_track(c, speeds, opt.max_prec)), bits_(bits), max_prec_(opt.max_prec), last_(0), G_last_(0) {
  check_not_zero_speed(track_->identically_zero());
  mu_ = track_->mu(bits, opt);
}

Ball ArcFraction::G(const Rational& x) {
  const long prec = 2 * bits_ + 64;
  if (x == last_) return G_last_;
  Ball g;
  if (last_ < x) {
    const Ball piece = track_->integral(last_, x, bits_);
    arb_add(g.get(), G_last_.get(), piece.get(), prec);
  } else {
    const Ball piece = track_->integral(x, last_, bits_);
    arb_sub(g.get(), G_last_.get(), piece.get(), prec);
  }
  last_ = x;
  G_last_ = g;
  return g;
}

Ball ArcFraction::at(const Ball& t) {
  if (!t.is_finite()) throw DomainError("ArcFraction::at: the parameter's enclosure is not finite");
  const long prec = 2 * bits_ + 64;
  Ball tc = t;
  clamp_unit(tc.get(), prec);
  arf_t lo, hi;
  arf_init(lo);
  arf_init(hi);
  arb_get_lbound_arf(lo, tc.get(), prec);
  arb_get_ubound_arf(hi, tc.get(), prec);
  fmpq_t q;
  fmpq_init(q);
  arf_get_fmpq(q, lo);
  Rational ql(q);
  arf_get_fmpq(q, hi);
  Rational qh(q);
  fmpq_clear(q);
  arf_clear(lo);
  arf_clear(hi);
  if (ql.sign() < 0) ql = Rational(0);
  if (Rational(1) < qh) qh = Rational(1);
  // G is increasing: G(t) lies in [G(ql), G(qh)] (G(qh) last, so that the
  // next, larger t starts from the upper end).
  const Ball gl = G(ql), gh = G(qh);
  Ball a, b, u;
  arb_div(a.get(), gl.get(), mu_.get(), prec);
  arb_div(b.get(), gh.get(), mu_.get(), prec);
  arb_union(u.get(), a.get(), b.get(), prec);
  return u;
}

Ball fraction_deviation(const Speed& s, const Reparameterization& r, long K, const Options& opt) {
  validate(opt);
  if (K < 2 || K > 1000000)
    throw InvalidArgument("the number of points must be between 2 and 1000000, got " + std::to_string(K));
  check_not_zero_speed(s.identically_zero());
  const long bits = digits_to_bits(opt.digits) + 8;
  const long prec = 2 * bits + 64;
  ArcFraction frac(s, bits, opt);
  Ball worst(0);
  for (long k = 0; k < K; ++k) {
    check_time_budget();
    const Ball sk(Rational(k, K - 1), prec);
    Ball d = frac.at(r.eval_r(sk, prec));
    arb_sub(d.get(), d.get(), sk.get(), prec);
    arb_abs(d.get(), d.get());
    arb_max(worst.get(), worst.get(), d.get(), prec);
  }
  return worst;
}

}  // namespace uniparam
