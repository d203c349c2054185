#include "uniparam/algebra/double_centred.hpp"

#include <arf.h>
#include <flint/fmpz_poly.h>
#include <mag.h>

#include <cmath>

namespace uniparam {

namespace {

// Slack covering gradual underflow, above its possible effect: a subnormal
// result is off by at most 2^-1075; there are at most 2 n^2 <= 2^13
// operations, each error reaches a coefficient along at most 2^64 paths,
// each multiplying it by at most |m|^n (1 + u)^L <= 2^65;
// 2^13 2^64 2^65 2^-1075 = 2^-933.
constexpr double kUnderflowSlack = 0x1p-900;

}  // namespace

DoubleCentredForm::DoubleCentredForm(const Poly& p) {
  const long n = p.degree();
  const slong bits = n >= 0 ? fmpz_poly_max_bits(p.get()) : 0;
  if (n < 0 || n > kMaxDegree || bits >= kMaxBits || bits <= -kMaxBits) return;
  for (long k = 0; k <= n; ++k) {
    a_.push_back(fmpz_get_d(p.get()->coeffs + k));  // towards zero
    abs_a_.push_back(std::fabs(a_.back()));
  }
}

// The bound's proof (u = 2^-53):
//   * a_k: p's integer coefficients rounded towards zero (fmpz_get_d), so
//     |a_k - exact| <= 2u |exact|;
//   * the Taylor coefficients c_k at m by repeated synthetic division
//     (c_k += m c_{k+1}, k = n-1 .. i, for i = 0 .. n-1), and alongside, on
//     |a_k| and |m|, the bounds D_k of sum_j C(j, k) |a_j| |m|^(j-k). Every
//     term C(j, k) a_j m^(j-k) of the exact coefficient d_k reaches c_k
//     through at most 2n + 1 roundings (one per pass while it stays at a
//     position, two more per move down: the product and the sum; k + 1
//     passes, j - k moves; a fused multiply-add only removes roundings), so
//     with the rounding of a_j, |c_k - d_k| <= gamma_L D_k, L = 2n + 3,
//     gamma_L = L u / (1 - L u); the computed D_k (positive terms along the
//     same paths) is below the exact one by at most the factor 1 - gamma_L.
//     E_k = 1.01 L u D_k covers both for n <= 64, and the rounding of E_k;
//     kUnderflowSlack covers gradual underflow;
//   * r >= |t - m| for t in z: the hypot of z's radii (mag_get_d gives
//     upper bounds) plus |mid(z) - m| <= 2^-53 |m| (+ 2^-1075 if
//     subnormal), times 1 + 2^-50 for the roundings;
//   * the sums of positive terms (variation and rounding part), computed in
//     double, are below the exact ones by at most the factor
//     1 - gamma_{3n} > 1 - 2^-44; their sum is multiplied by 1 + 2^-40.
//   * No overflow before the radii: |a_k| < 2^800, so D_k < 2^(800+7+128);
//     the radii's sums are checked for finiteness.
bool DoubleCentredForm::eval(acb_t v, acb_t d1, acb_t d2, const acb_t z, double max_error) const {
  if (!arf_is_zero(arb_midref(acb_imagref(z)))) return false;
  const double m = arf_get_d(arb_midref(acb_realref(z)), ARF_RND_NEAR);
  if (!(std::fabs(m) <= 2)) return false;
  const double ry = mag_get_d(arb_radref(acb_imagref(z)));  // upper bounds
  const double rx = mag_get_d(arb_radref(acb_realref(z)));
  const double r = (std::hypot(rx, ry) + std::fabs(m) * 0x1p-52 + 0x1p-1000) * (1 + 0x1p-50);
  if (!(r <= 256)) return false;
  const std::size_t n = a_.size() - 1;
  thread_local std::vector<double> c, D;
  c = a_;
  D = abs_a_;
  const double am = std::fabs(m);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = n; k-- > i;) {
      c[k] += m * c[k + 1];
      D[k] += am * D[k + 1];
    }
  const double eps = 1.01 * static_cast<double>(2 * n + 3) * 0x1p-53;
  acb_ptr outs[3] = {v, d1, d2};
  for (std::size_t j = 0; j <= 2; ++j) {
    acb_ptr out = outs[j];
    if (!out) continue;
    // sum_{k>j} k!/(k-j)! |c_k| r^(k-j) (the variation) and the same with
    // E_k (the rounding part), by Horner
    double var = 0, err = 0;
    for (std::size_t k = n; k > j; --k) {
      const double f = j == 0 ? 1.0 : j == 1 ? static_cast<double>(k) : static_cast<double>(k * (k - 1));
      var = (var + f * std::fabs(c[k])) * r;
      err = (err + f * (eps * D[k] + kUnderflowSlack)) * r;
    }
    const double fj = j == 2 ? 2 : 1;
    const double centre = j <= n ? fj * c[j] : 0;
    if (j <= n) err += fj * (eps * D[j] + kUnderflowSlack);
    const double rad = (var + err) * (1 + 0x1p-40) + kUnderflowSlack;
    if (!std::isfinite(rad) || !std::isfinite(centre)) return false;
    if (err > max_error * (std::fabs(centre) + var)) return false;
    arf_set_d(arb_midref(acb_realref(out)), centre);
    mag_set_d(arb_radref(acb_realref(out)), rad);
    arb_zero(acb_imagref(out));
    if (ry != 0) mag_set_d(arb_radref(acb_imagref(out)), rad);
  }
  return true;
}

}  // namespace uniparam
