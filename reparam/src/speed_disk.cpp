// speed_disk.cpp -- the speed on wide balls (the quadrature's ellipses and
// segments) in complex discs in double (core/cdisk.hpp): the arithmetic of
// speed_formula.hpp on DiskArith, each polynomial's disc from
// LocalPoly::eval_disk.
#include <algorithm>
#include <cmath>

#include "curve_model.hpp"
#include "speed_enclosure.hpp"
#include "speed_formula.hpp"
#include "uniparam/reparam/speed.hpp"

namespace uniparam {

namespace {

// Whether the disc x, which could not be divided by (root: or square-rooted),
// holds 0 (root: or meets the cut (-inf, 0]) with a finite centre and radius
// within 2^400: Arb's balls, holding the same enclosure, would fail there
// too. Otherwise (a magnitude out of the discs' range) Arb may still succeed.
bool holds_singularity(const CDisk& x, bool root) {
  if (!cdisk_is_finite(x) || std::max(std::fabs(x.re), std::fabs(x.im)) > 0x1p400 || x.rad > 0x1p400) return false;
  if (std::hypot(x.re, x.im) <= x.rad) return true;
  return root && x.re <= 0 && std::fabs(x.im) <= x.rad;
}

}  // namespace

Speed::DiskResult Speed::factored_disks(CDisk& g, CDisk& q, CDisk& d, const acb_t z, long prec) const {
  using namespace speed_formula;
  DiskArith ar;
  CDisk v;
  if (Y_b_.empty()) {  // D = W
    d = W_b_.eval_disk(z, prec);
  } else {
    sum_of_squares(ar, d, Y_b_.size(), [&](std::size_t i) -> const CDisk& { return v = Y_b_[i].eval_disk(z, prec); });
  }
  // first: see eval_factored
  if (!cdisk_is_finite(cdisk_inv(d))) return holds_singularity(d, false) ? DiskResult::Refused : DiskResult::Unknown;
  if (K_b_.size() == 1)
    q = K_b_[0].eval_disk(z, prec);
  else
    sum_of_squares(ar, q, K_b_.size(), [&](std::size_t i) -> const CDisk& { return v = K_b_[i].eval_disk(z, prec); });
  // g = content * prod h_i^m_i; fmpz_get_d rounds towards zero (< 2u relative)
  const double content = fmpz_get_d(g_content_.get());
  factored_g(
      ar, g, CDisk{content, 0, cdisk_detail::up(0x1p-52 * std::fabs(content))}, g_h_.size(),
      [&](std::size_t i, CDisk& h) { h = g_h_[i].eval_disk(z, prec); }, [&](std::size_t i) { return g_m_[i]; },
      static_cast<std::size_t>(-1));
  return cdisk_is_finite(q) && cdisk_is_finite(g) ? DiskResult::Ok : DiskResult::Unknown;
}

Speed::DiskResult Speed::eval_factored_disk(acb_t out, const acb_t z, const PieceSigns& p, long prec) const {
  CDisk g, s, d;
  const DiskResult parts = factored_disks(g, s, d, z, prec);
  if (parts != DiskResult::Ok) return parts;
  if (K_b_.size() == 1) {  // a nonzero integer constant: its absolute value
    if (!(s.im == 0 && std::fabs(s.re) > s.rad)) return DiskResult::Unknown;
    if (s.re < 0) s = cdisk_neg(s);
  } else {
    const CDisk q = s;
    s = cdisk_sqrt_analytic(q);
    if (!cdisk_is_finite(s)) return holds_singularity(q, true) ? DiskResult::Refused : DiskResult::Unknown;
  }
  DiskArith ar;
  CDisk r;
  speed_formula::factored_value(ar, r, s, d, [&g](CDisk& v) { v = g; }, p.g);
  if (!cdisk_is_finite(r)) return DiskResult::Unknown;
  cdisk_get_acb(out, r);
  return DiskResult::Ok;
}

bool Speed::components_disk(CDisk& S, CDisk& F, const acb_t z, long prec) const {
  using namespace speed_formula;
  constexpr std::size_t kMax = 8;
  const CurveModel& m = *model_;
  const std::size_t n = m.size();
  const bool angular = kind_ == SpeedKind::Angular;
  if (!m.has_disks() || n == 0 || n > kMax) return false;
  bool poly = true, common = true;
  for (std::size_t i = 0; i < n; ++i) {
    poly = poly && m.unit_den(i);
    common = common && !m.unit_den(i) && m.den_index(i) == m.den_index(0);
  }
  if (!poly && !(common && angular)) return false;
  DiskArith ar;
  CDisk d1[kMax], d2[kMax];
  if (poly) {  // x' = N', x'' = N''
    for (std::size_t i = 0; i < n; ++i) m.eval_num_disks(i, nullptr, d1 + i, angular ? d2 + i : nullptr, z, prec);
  } else {  // A_i and B_i (eval_components)
    CDisk q, q1, q2, v, v1, v2;
    m.eval_den_disks(0, &q, &q1, &q2, z, prec);
    for (std::size_t i = 0; i < n; ++i) {
      m.eval_num_disks(i, &v, &v1, &v2, z, prec);
      scaled_derivatives(ar, d1[i], d2 + i, v, v1, &v2, q, q1, &q2);
    }
  }
  sum_of_squares(ar, S, n, [&d1](std::size_t i) -> const CDisk& { return d1[i]; });
  F = CDisk{0, 0, 0};
  if (angular) cross_terms(ar, F, d1, d2, n);
  return cdisk_is_finite(S) && cdisk_is_finite(F);
}

Speed::DiskResult Speed::eval_disk(acb_t out, const acb_t z, const PieceSigns& p, long prec) const {
  CDisk S, F;
  bool unknown = true;  // the components failed for want of range, not at a singularity
  if (components_disk(S, F, z, prec)) {
    const speed_formula::Form f = form();
    if (f == speed_formula::Form::Parametric) unknown = !holds_singularity(S, true);
    else if (f == speed_formula::Form::Plane) unknown = !holds_singularity(S, false);
    else unknown = !holds_singularity(S, false) && !holds_singularity(F, true);
    DiskArith ar;
    CDisk r;
    speed_formula::speed_value(ar, r, S, F, f, p.component, nullptr);
    if (cdisk_is_finite(r)) {
      cdisk_get_acb(out, r);
      return DiskResult::Ok;
    }
  }
  if (!disk_form_) return DiskResult::Unknown;
  const DiskResult f = eval_factored_disk(out, z, p, prec);
  return f == DiskResult::Refused && unknown ? DiskResult::Unknown : f;
}

Speed::DiskResult Speed::eval_squared_disk(acb_t out, const acb_t z, long prec) const {
  DiskArith ar;
  CDisk S, F, r;
  bool unknown = true;  // as in eval_disk
  if (components_disk(S, F, z, prec)) {
    speed_formula::speed_squared(ar, r, S, F, form(), nullptr);
    if (kind_ == SpeedKind::Angular) unknown = !holds_singularity(S, false);
    if (cdisk_is_finite(r)) {
      cdisk_get_acb(out, r);
      if (arb_is_zero(acb_imagref(z))) arb_zero(acb_imagref(out));  // sigma^2 is real on a real segment
      return DiskResult::Ok;
    }
  }
  // the factored form g^2 sum K^2 / D^2 (p'(z) = 0 in reach: see eval_squared)
  if (!disk_form_) return DiskResult::Unknown;
  CDisk g, q, d, ratio;
  const DiskResult parts = factored_disks(g, q, d, z, prec);
  if (parts != DiskResult::Ok) return parts == DiskResult::Refused && unknown ? DiskResult::Unknown : parts;
  if (K_b_.size() == 1) q = cdisk_mul(q, q);
  speed_formula::factored_ratio_squared(ar, ratio, q, d);
  speed_formula::factored_squared(ar, r, ratio, g);
  if (!cdisk_is_finite(r)) return DiskResult::Unknown;
  cdisk_get_acb(out, r);
  if (arb_is_zero(acb_imagref(z))) arb_zero(acb_imagref(out));
  return DiskResult::Ok;
}

}  // namespace uniparam
