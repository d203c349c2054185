// speed_eval.cpp -- the speed in Arb's complex balls (Speed::eval,
// eval_squared, eval_squared_over_zero): from the components first, the
// factored form where that is not finite; the arithmetic of
// speed_formula.hpp on AcbArith (RAII temporaries: an exception, e.g. a
// time budget from RealAlgebraic::to_ball, releases them).
#include "curve_model.hpp"
#include "speed_enclosure.hpp"
#include "speed_formula.hpp"
#include "speed_model.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/reparam/speed.hpp"

namespace uniparam {

speed_formula::Form Speed::form() const { return speed_model(kind_).form(comp_.size()); }

void Speed::eval_derivatives(AcbBox* d1, AcbBox* d2, const acb_t z, long prec) const {
  using namespace speed_formula;
  const AcbArith ar{prec};
  AcbBox n, n1, n2, q, q1, q2, a, v, w;
  const CurveModel& m = *model_;
  std::size_t q_done = m.size();  // index of the Q held in q, q1, q2, v, w
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (m.unit_den(i)) {  // a polynomial component: x' = N', x'' = N''
      m.eval_num(i, n, d1[i], d2 ? d2[i].get() : nullptr, z, prec);
      continue;
    }
    m.eval_num(i, n, n1, d2 ? n2.get() : nullptr, z, prec);
    if (m.den_index(i) != q_done) {  // a rational curve's common weight: once
      m.eval_den(i, q, q1, d2 ? q2.get() : nullptr, z, prec);
      ar.inv(v, q);  // v = 1 / Q (one division)
      ar.mul(w, v, v);
      q_done = m.den_index(i);
    }
    scaled_derivatives(ar, a, d2 ? &n2 : nullptr, n, n1, &n2, q, q1, &q2);
    quotient_derivatives(ar, d1[i], d2 ? d2 + i : nullptr, a, d2 ? &n2 : nullptr, q1, v, w);
  }
}

void Speed::eval_components(AcbBox& S, AcbBox& F, const acb_t z, long prec) const {
  using namespace speed_formula;
  const AcbArith ar{prec};
  const CurveModel& m = *model_;
  const std::size_t n = m.size();
  const bool angular = kind_ == SpeedKind::Angular;
  bool common = angular && n > 0 && !m.unit_den(0);
  for (std::size_t i = 0; i < n; ++i) common = common && m.den_index(i) == m.den_index(0);
  std::vector<AcbBox> d(angular ? 2 * n : n);
  AcbBox* d1 = d.data();
  AcbBox* d2 = angular ? d1 + n : nullptr;
  if (common) {
    // One denominator Q (a rational curve's weight): with A_i = N_i' Q -
    // N_i Q' and B_i = N_i'' Q - N_i Q'' in place of x_i' and x_i''
    // (speed_formula.hpp), S and F come scaled by Q^4 and Q^8 (E by Q^4),
    // which sigma's ratios F / S^2, E / S do not see: no division by Q,
    // so its complex zeros (the curve's poles, not sigma's) do not spoil
    // wide balls.
    AcbBox nv, n1, n2, q, q1, q2;
    m.eval_den(0, q, q1, q2, z, prec);
    for (std::size_t i = 0; i < n; ++i) {
      m.eval_num(i, nv, n1, n2, z, prec);
      scaled_derivatives(ar, d1[i], d2 + i, nv, n1, &n2, q, q1, &q2);
    }
  } else {
    eval_derivatives(d1, d2, z, prec);
  }
  sum_of_squares(ar, S, n, [d1](std::size_t i) -> const AcbBox& { return d1[i]; });
  if (d2) cross_terms(ar, F, d1, d2, n);
}

void Speed::eval_g(AcbBox& out, const acb_t z, long prec, std::size_t skip) const {
  const AcbArith ar{prec};
  AcbBox content;
  acb_set_fmpz(content, g_content_.get());
  speed_formula::factored_g(
      ar, out, content, g_h_.size(), [&](std::size_t i, AcbBox& v) { g_h_[i].eval(v, z, prec); },
      [&](std::size_t i) { return g_m_[i]; }, skip);
}

namespace {

// A disc evaluation's outcome (Speed::DiskResult): true when it settled out,
// with its enclosure (Ok) or as indeterminate (Refused: no finite bound
// exists there); false when the next tier must try.
template <class DiskResult>
bool disk_settled(DiskResult r, acb_t out) {
  if (r == DiskResult::Refused) acb_indeterminate(out);
  return r != DiskResult::Unknown;
}

}  // namespace

void Speed::eval(acb_t out, const acb_t z, const PieceSigns& p, bool analytic, long prec, bool double_word) const {
  if (zero_) { acb_zero(out); return; }
  if (!analytic && double_word && eval_double_word(out, z, p, false, prec)) return;
  // Space curves' angular speed on an ellipse (the quadrature's error
  // bounds): F = |p' x p''|^2 from the components reaches 0 there on >= 90%
  // of the benchmark curves' ellipses (any degree), so the factored form
  // alone is tried. Where it fails, sigma's branch points (the complex zeros
  // of sum K^2, which F shares) are in the ellipse or D's enclosure holds 0,
  // and the components rarely do better (they succeed on only 1
  // of 143 ellipses at d = 6, 34 of 352 at d = 150): the ellipse is refused
  // at once (4-14% fewer instructions, same values). Plane curves' ellipses
  // succeed more often from the components, where the factored form costs
  // more.
  if (analytic && kind_ == SpeedKind::Angular && comp_.size() >= 3) {
    // In discs first (cheap); where every factor has its centred form in
    // double there, Arb's balls would not succeed where the discs failed
    // (they hold the same enclosures, in boxes), so they are not tried.
    const DiskResult r = disk_form_ ? eval_factored_disk(out, z, p, prec) : DiskResult::Unknown;
    if (r == DiskResult::Ok) return;
    if (r == DiskResult::Refused || !eval_factored(out, z, p, analytic, prec)) acb_indeterminate(out);
    return;
  }
  // Ellipses in discs first (see eval_disk); Arb's balls only where a
  // factor lacks its centred form in double (see above).
  if (analytic) {
    if (disk_settled(eval_disk(out, z, p, prec), out)) return;
  }
  // From the components first (low degree: cheap); where that is not
  // finite (space curves on wide balls: F = |p' x p''|^2 is a difference of
  // products whose enclosure may reach 0, so sqrt(F) is not certified
  // analytic; or the branch point near a zero of sigma), the factored form
  // g sqrt(sum K^2) / D below, tight but of degree ~4x higher.
  AcbBox S, F, r;
  eval_components(S, F, z, prec);
  // A real segment where holomorphy is not asked (Arb's direct bound on a
  // subinterval): sigma is real there, F = |p' x p''|^2 and S = |p'|^2 are
  // >= 0 at every real point, so sqrt may be taken of [max(0, lo), hi]
  // (arb_sqrtpos) instead of failing where the enclosure reaches below 0.
  const bool real = !analytic && acb_is_real(z) && acb_is_real(F) && acb_is_real(S);
  const AcbArith ar{prec, analytic, real};
  speed_formula::speed_value(ar, r, S, F, form(), p.component, nullptr);
  acb_swap(out, r);
  if (!acb_is_finite(out)) {
    // Near a zero of sigma the square root's branch point is in reach:
    // the factored form s g R is analytic there.
    eval_factored(out, z, p, analytic, prec);
  }
  // sigma is real at real points: on a real segment Re(out) holds it
  if (!analytic && acb_is_real(z)) arb_zero(acb_imagref(out));
}

bool Speed::eval_factored(acb_t out, const acb_t z, const PieceSigns& p, bool analytic, long prec) const {
  AcbBox d, s, r;
  // D first: where its enclosure holds 0 the quotient is not finite anyway,
  // and the K_k (degree ~4x the curve's) need not be expanded there.
  eval_D(d, z, prec);
  if (acb_contains_zero(d)) {
    acb_indeterminate(out);
    return false;
  }
  // s = sqrt(sum K^2); a single cofactor is a nonzero integer constant: |K|.
  if (K_b_.size() == 1) {
    K_b_[0].eval(s, z, prec);
    if (arb_is_negative(acb_realref(s.get())) && arb_is_zero(acb_imagref(s.get()))) acb_neg(s, s);
  } else {
    eval_sumK2(s, z, prec);
    // on a real segment (not analytic) sum K^2 >= 0: arb_sqrtpos
    const AcbArith root{prec, analytic, !analytic && acb_is_real(s)};
    root.sqrt(s, s);
  }
  const AcbArith ar{prec};
  speed_formula::factored_value(ar, r, s, d, [&](AcbBox& g) { eval_g(g, z, prec); }, p.g);
  acb_swap(out, r);
  return acb_is_finite(out);
}

void Speed::eval_squared(acb_t out, const acb_t z, long prec, bool double_word) const {
  if (zero_) { acb_zero(out); return; }
  if (double_word && eval_double_word(out, z, PieceSigns{}, true, prec)) return;
  // Wide balls in discs first, as eval's ellipses.
  if (is_wide_ball(z)) {  // (its enclosures only bound sigma^2)
    if (disk_settled(eval_squared_disk(out, z, prec), out)) return;
  }
  AcbBox S, F, r;
  eval_components(S, F, z, prec);
  const AcbArith ar{prec};
  speed_formula::speed_squared(ar, r, S, F, form(), nullptr);
  if (kind_ == SpeedKind::Angular && !acb_is_finite(r)) {
    // p'(z) = 0 in reach (a cusp): F / S^2 is 0/0 there, while the
    // factored form g^2 sum K^2 / D^2 has the common factor cancelled.
    AcbBox g, ratio;
    eval_g(g, z, prec);
    eval_sumK2_over_D2(ratio, z, prec);
    speed_formula::factored_squared(ar, r, ratio, g);
  }
  acb_swap(out, r);
}

void Speed::eval_sumK2(AcbBox& out, const acb_t z, long prec) const {
  const AcbArith ar{prec};
  AcbBox v;
  speed_formula::sum_of_squares(ar, out, K_b_.size(), [&](std::size_t i) -> const AcbBox& {
    K_b_[i].eval(v, z, prec);
    return v;
  });
}

void Speed::eval_D(AcbBox& out, const acb_t z, long prec) const {
  if (Y_b_.empty()) {  // D = W
    W_b_.eval(out, z, prec);
    return;
  }
  const AcbArith ar{prec};
  AcbBox v;
  speed_formula::sum_of_squares(ar, out, Y_b_.size(), [&](std::size_t i) -> const AcbBox& {  // D = sum Y_i^2
    Y_b_[i].eval(v, z, prec);
    return v;
  });
}

void Speed::eval_sumK2_over_D2(AcbBox& out, const acb_t z, long prec) const {
  AcbBox d, q;
  eval_D(d, z, prec);  // first: see eval_factored
  if (acb_contains_zero(d)) {
    acb_indeterminate(out);
    return;
  }
  eval_sumK2(q, z, prec);
  const AcbArith ar{prec};
  speed_formula::factored_ratio_squared(ar, out, q, d);
}

void Speed::eval_squared_over_zero(acb_t out, const acb_t z, const SpeedZero& zero, int side, int power, long prec,
                                   bool double_word) const {
  if (zero_) { acb_zero(out); return; }
  const std::size_t j = zero.factor;
  const int mu = zero.multiplicity;
  if (power < 0 || power > 2 * mu) throw InvalidArgument("eval_squared_over_zero: power out of range");
  if (zero.index >= zeros_.size() || zeros_[zero.index].factor != j)
    throw InvalidArgument("eval_squared_over_zero: not a zero of this speed");
  AcbBox w, h, r;
  // w = side (z - gamma)
  const Ball gb = zero.t.to_ball(prec + 16);
  acb_sub_arb(w, z, gb.get(), prec);
  if (side < 0) acb_neg(w, w);
  // Away from gamma relative to the ball's size (|w| > 8 rad w), dividing is
  // harmless: sigma^2 from the components, divided by w^power.
  mag_t lo, rad;
  mag_init(lo);
  mag_init(rad);
  acb_get_mag_lower(lo, w);
  mag_hypot(rad, arb_radref(acb_realref(w.get())), arb_radref(acb_imagref(w.get())));
  mag_mul_2exp_si(rad, rad, 3);
  const bool far = mag_cmp(lo, rad) > 0;
  mag_clear(lo);
  mag_clear(rad);
  if (far) {
    eval_squared(out, z, prec, double_word);
    acb_pow_ui(w, w, static_cast<ulong>(power), prec);
    acb_div(out, out, w, prec);
  } else {
    // Near gamma: out = w^(2 mu - power) h_gamma(z)^(2 mu) (c g_1(z))^2 sum K^2 / D^2.
    acb_pow_ui(w, w, static_cast<ulong>(2 * mu - power), prec);
    g_h_[j].eval_deflated(h, z, zero.t, prec);
    acb_pow_ui(h, h, static_cast<ulong>(2 * mu), prec);
    acb_mul(w, w, h, prec);
    eval_g(h, z, prec, j);  // c g_1(z): g without the factor vanishing at gamma
    acb_mul(w, w, h, prec);
    acb_mul(w, w, h, prec);
    eval_sumK2_over_D2(r, z, prec);
    acb_mul(out, r, w, prec);
  }
}

Ball Speed::eval_real(const Ball& t, long prec) const {
  acb_t z, w;
  acb_init(z);
  acb_init(w);
  acb_set_arb(z, t.get());
  eval_squared(w, z, prec);
  Ball v;
  arb_sqrtpos(v.get(), acb_realref(w), prec);
  acb_clear(z);
  acb_clear(w);
  return v;
}

}  // namespace uniparam
