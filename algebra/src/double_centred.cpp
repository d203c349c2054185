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
//     kUnderflowSlack covers gradual underflow. eval_disks needs only the
//     sums sum_k k!/(k-j)! E_k r^(k-j) (j <= 2) of the exact D_k (with
//     |m| <= am): they are 1.01 L u |p|^(j)(am + r), |p| = sum |a_i| t^i,
//     since sum_k D_k r^k = sum_i |a_i| (am + r)^i, and it computes them
//     by Horner's rule (positive terms) without forming the D_k; only
//     eval_deflated's majorants need the D_k themselves (shift's
//     `majorants`);
//   * r >= |t - m| for t in z: the hypot of z's radii (mag_get_d gives
//     upper bounds) plus |mid(z) - m| <= 2^-53 |m| (+ 2^-1075 if
//     subnormal), times 1 + 2^-50 for the roundings;
//   * the sums of positive terms (variation and rounding part), computed in
//     double, are below the exact ones by at most the factor
//     1 - gamma_{3n} > 1 - 2^-44; their sum is multiplied by 1 + 2^-40.
//   * No overflow before the radii: |a_k| < 2^800, so D_k < 2^(800+7+128);
//     the radii's sums are checked for finiteness.
//
// A complex midpoint m = mr + i mi (the quadrature's boxes above the real
// axis): the same synthetic division in complex double, (cr + i ci) +=
// m (cr' + i ci') with the product by the textbook formula. A complex sum
// is (x + y)(1 + d), |d| <= u (each part rounded on its own), and a product
// m c (1 + d) with |d| <= sqrt(5) u (Brent, Percival and Zimmermann, 2007;
// 2u with a fused multiply-add), so each of the j - k moves counts 3 + 1
// units of u, the k + 1 passes 1 each and the rounding of a_j 2:
// L = 4n + 3. D_k (or |p| at am + r) is formed as before with am >= |m|
// rounded upward (hypot is within an ulp, times 1 + 2^-51), so it bounds
// the exact sum_j C(j, k) |a_j| |m|^(j-k) up to the same factor
// 1 - gamma_{2n+1}; E_k = 1.01 L u D_k covers both. |c_k| (cdisk.hpp's abs_up, an upper
// bound; computed once per shift, for the outputs' sums) enters only
// sums of positive terms, whose factor 1 + 2^-40 covers it.
bool DoubleCentredForm::shift(const acb_t z, Shift& sh, bool majorants) const {
  sh.m = arf_get_d(arb_midref(acb_realref(z)), ARF_RND_NEAR);
  sh.mi = arf_get_d(arb_midref(acb_imagref(z)), ARF_RND_NEAR);
  const double am = sh.mi == 0 ? std::fabs(sh.m) : std::hypot(sh.m, sh.mi) * (1 + 0x1p-51);  // >= |m|
  if (!(am <= 2)) return false;
  const double ry = mag_get_d(arb_radref(acb_imagref(z)));  // upper bounds
  const double rx = mag_get_d(arb_radref(acb_realref(z)));
  // |mid(z) - m| <= 2^-53 |m| in each part (+ 2^-1075 if subnormal)
  sh.r = (std::hypot(rx, ry) + am * 0x1p-52 + 0x1p-1000) * (1 + 0x1p-50);
  if (!(sh.r <= 256)) return false;
  const std::size_t n = a_.size() - 1;
  thread_local std::vector<double> c, ci, D;
  c = a_;
  const double m = sh.m, mi = sh.mi;
  sh.am = am;
  if (mi == 0) {
    // Four passes at a time, on a wavefront: pass i + o (o = 0 .. 3) takes
    // position k + o while pass i takes k, from the value pass i + o - 1
    // gave that position one step before (carried in registers, like the
    // pass's own c_{k+1}); only pass i + 3 stores its values, and the four
    // passes end together at positions i .. i + 3 (final from then on).
    // Each position gets the same operations in the same order as in the
    // serial loop (bit for bit its coefficients), but the four chains are
    // independent: the serial loop waits on one multiply-add chain (a shift
    // of degree 31 in ~1.8x the time, complex or real).
    std::size_t i = 0;
    for (; i + 4 <= n; i += 4) {
      double x0 = c[n], x1 = x0, x2 = x0, x3 = x0;
      x0 = c[n - 1] + m * x0;
      x1 = x0 + m * x1;
      x0 = c[n - 2] + m * x0;
      x2 = x1 + m * x2;
      x1 = x0 + m * x1;
      x0 = c[n - 3] + m * x0;
      for (std::size_t k = n - 4;; --k) {  // pass i at k, pass i + o at k + o
        x3 = x2 + m * x3;
        x2 = x1 + m * x2;
        x1 = x0 + m * x1;
        x0 = c[k] + m * x0;
        c[k + 3] = x3;
        if (k == i) break;
      }
      c[i] = x0;
      c[i + 1] = x1;
      c[i + 2] = x2;
    }
    for (; i < n; ++i)
      for (std::size_t k = n; k-- > i;) c[k] += m * c[k + 1];
    sh.eps = 1.01 * static_cast<double>(2 * n + 3) * 0x1p-53;
  } else {
    ci.assign(n + 1, 0.0);
    // c_{k+1} is carried in registers (xr, xi) from the step before: read
    // back from c and ci (which the compiler must assume may alias), it
    // put a store-to-load round trip on the pass's dependency chain (half
    // of the time at degree 31). The same operations in the same order.
    // x = in + m x in complex double, as the serial loop below
    auto step = [m, mi](double& xr, double& xi, double inr, double ini) {
      const double pr = m * xr - mi * xi, pi = m * xi + mi * xr;
      xr = inr + pr;
      xi = ini + pi;
    };
    std::size_t i = 0;
    for (; i + 4 <= n; i += 4) {  // four passes on a wavefront, as in the real case
      double r0 = c[n], r1 = r0, r2 = r0, r3 = r0, j0 = ci[n], j1 = j0, j2 = j0, j3 = j0;
      step(r0, j0, c[n - 1], ci[n - 1]);
      step(r1, j1, r0, j0);
      step(r0, j0, c[n - 2], ci[n - 2]);
      step(r2, j2, r1, j1);
      step(r1, j1, r0, j0);
      step(r0, j0, c[n - 3], ci[n - 3]);
      for (std::size_t k = n - 4;; --k) {
        step(r3, j3, r2, j2);
        step(r2, j2, r1, j1);
        step(r1, j1, r0, j0);
        step(r0, j0, c[k], ci[k]);
        c[k + 3] = r3;
        ci[k + 3] = j3;
        if (k == i) break;
      }
      c[i] = r0;
      ci[i] = j0;
      c[i + 1] = r1;
      ci[i + 1] = j1;
      c[i + 2] = r2;
      ci[i + 2] = j2;
    }
    for (; i < n; ++i) {
      double xr = c[n], xi = ci[n];
      for (std::size_t k = n; k-- > i;) {
        const double pr = m * xr - mi * xi, pi = m * xi + mi * xr;
        xr = c[k] + pr;
        xi = ci[k] + pi;
        c[k] = xr;
        ci[k] = xi;
      }
    }
    sh.eps = 1.01 * static_cast<double>(4 * n + 3) * 0x1p-53;
  }
  sh.D = nullptr;
  if (majorants) {  // the same synthetic division on |a_k| and |m|
    D = abs_a_;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = n; k-- > i;) D[k] += am * D[k + 1];
    sh.D = &D;
  }
  sh.c = &c;
  sh.ci = mi == 0 ? nullptr : &ci;
  return true;
}

namespace {

// out = centre + i centre_im +- rad, real (zero imaginary part) or with the
// same imaginary radius (a box holding the disc of radius rad).
void set_out(acb_t out, double centre, double centre_im, double rad, bool real) {
  arf_set_d(arb_midref(acb_realref(out)), centre);
  mag_set_d(arb_radref(acb_realref(out)), rad);
  arb_zero(acb_imagref(out));
  if (!real) {
    arf_set_d(arb_midref(acb_imagref(out)), centre_im);
    mag_set_d(arb_radref(acb_imagref(out)), rad);
  }
}

}  // namespace

bool DoubleCentredForm::eval_disks(CDisk* v, CDisk* d1, CDisk* d2, const acb_t z, double max_error) const {
  Shift sh;
  if (!shift(z, sh, false)) return false;
  const std::vector<double>& c = *sh.c;
  const std::vector<double>* ci = sh.ci;  // null: a real midpoint
  const double r = sh.r, eps = sh.eps;
  const std::size_t n = a_.size() - 1;
  thread_local std::vector<double> ac;  // |c_k|, upper bounds
  ac.resize(n + 1);
  for (std::size_t k = 0; k <= n; ++k) ac[k] = ci ? cdisk_detail::abs_up(c[k], (*ci)[k]) : std::fabs(c[k]);
  // The rounding parts sum_{k>=j} k!/(k-j)! E_k r^(k-j) need no D_k: with
  // s = |m| + r, sum_k D_k r^k = sum_i |a_i| s^i (the binomial theorem), so
  // they are eps |p|^(j)(s), |p| = sum |a_i| t^i, by Horner (positive terms,
  // s rounded upward: the factor 1 + 2^-40 below covers the sums' roundings)
  // plus the slack's own sums.
  const double s = (sh.am + r) * (1 + 0x1p-52);
  double h0 = 0, h1 = 0, h2 = 0;  // |p|(s), |p|'(s), |p|''(s) / 2
  for (std::size_t k = n + 1; k-- > 0;) {
    h2 = h2 * s + h1;
    h1 = h1 * s + h0;
    h0 = h0 * s + abs_a_[k];
  }
  const double hj[3] = {h0, h1, 2 * h2};
  CDisk* outs[3] = {v, d1, d2};
  for (std::size_t j = 0; j <= 2; ++j) {
    CDisk* out = outs[j];
    if (!out) continue;
    // sum_{k>j} k!/(k-j)! |c_k| r^(k-j) (the variation) and the same with
    // the underflow slack, by Horner
    double var = 0, err = 0;
    for (std::size_t k = n; k > j; --k) {
      const double f = j == 0 ? 1.0 : j == 1 ? static_cast<double>(k) : static_cast<double>(k * (k - 1));
      var = (var + f * ac[k]) * r;
      err = (err + f * kUnderflowSlack) * r;
    }
    const double fj = j == 2 ? 2 : 1;
    const double centre = j <= n ? fj * c[j] : 0, centre_im = j <= n && ci ? fj * (*ci)[j] : 0;
    if (j <= n) err += fj * kUnderflowSlack;
    err += eps * hj[j];
    const double rad = (var + err) * (1 + 0x1p-40) + kUnderflowSlack;
    if (!std::isfinite(rad) || !std::isfinite(centre) || !std::isfinite(centre_im)) return false;
    if (err > max_error * (std::hypot(centre, centre_im) + var)) return false;
    *out = CDisk{centre, centre_im, rad};
  }
  return true;
}

bool DoubleCentredForm::eval(acb_t v, acb_t d1, acb_t d2, const acb_t z, double max_error) const {
  CDisk o[3];
  if (!eval_disks(v ? &o[0] : nullptr, d1 ? &o[1] : nullptr, d2 ? &o[2] : nullptr, z, max_error)) return false;
  // a real z gives real values: the disc's real segment
  const bool real = arb_is_zero(acb_imagref(z));
  acb_ptr outs[3] = {v, d1, d2};
  for (int j = 0; j < 3; ++j)
    if (outs[j]) set_out(outs[j], o[j].re, o[j].im, o[j].rad, real);
  return true;
}

// The quotient's proof, on top of eval's (same u, c_k, E_k = eps D_k + slack
// >= |c_k - d_k|, r): with g = gamma - m, the exact quotient
// p(m + w) / (w - g) = sum b_k w^k has b_{n-1} = d_n and
// b_{k-1} = d_k + g b_k (synthetic division from the top; exact, as
// p(gamma) = 0). It is computed from c and h = gamma_mid - m rounded, with
// |g - h| <= e = (gamma_rad + 2^-52 |h| + 2^-1070) (1 + 2^-50). With
// G >= |h| + e >= max(|g|, |h|) and the majorants (recurrences of positive
// terms from the top)
//     B_{k-1} = (|c_k| + E_k) + G B_k      >= the b_k of any d, g in range,
//     C_{k-1} = E_k + G C_k                >= sum_{j>k} |c_j - d_j| G^(j-k-1),
//     P_{k-1} = B_k + G P_k                >= |d b_{k-1} / d g| over g in range,
// the computed coefficients err from the exact ones by at most
//     C_k (the c's errors) + e P_k (h for g: mean value theorem)
//     + 1.01 (2n + 1) u B_k (at most 2n roundings per coefficient),
// plus the underflow slack per step; the positive recurrences, computed in
// double, lose at most a factor 1 - gamma_{3n} (covered by 1 + 2^-40 on the
// radius). Then the centred form of the quotient as in eval. A complex
// midpoint (shift's note): h = gamma_mid - m is complex (its imaginary part
// exact), the majorants take |h| rounded upward and |c_k| by hypot (within
// an ulp, in sums of positive terms: the factor 1 + 2^-40), the mean value
// bound holds along the segment from h to g in the disc |g - h| <= e, and
// each product h b_k counts 3 units of u: 4n + 1 roundings per coefficient.
bool DoubleCentredForm::eval_deflated(acb_t v, const acb_t z, double gamma_mid, double gamma_rad,
                                      double max_error) const {
  if (a_.size() < 2 || !(std::fabs(gamma_mid) <= 4) || !(gamma_rad >= 0 && gamma_rad <= 1)) return false;
  Shift sh;
  if (!shift(z, sh, true)) return false;
  const std::vector<double>& c = *sh.c;
  const std::vector<double>* ci = sh.ci;  // null: a real midpoint
  const std::vector<double>& D = *sh.D;
  const std::size_t n = a_.size() - 1;  // >= 1: the quotient has n coefficients
  // h = gamma_mid - m: its real part rounded once, its imaginary part exact
  const double h = gamma_mid - sh.m, hi = -sh.mi;
  const double ah = hi == 0 ? std::fabs(h) : std::hypot(h, hi) * (1 + 0x1p-51);  // >= |h|
  const double e = (gamma_rad + ah * 0x1p-52 + 0x1p-1070) * (1 + 0x1p-50);
  const double G = (ah + e) * (1 + 0x1p-50);
  // roundings per coefficient: 2n (real), or 4n (complex: 3 units of u a
  // product, see shift), each step a product and a sum
  const double eps2 = 1.01 * static_cast<double>((ci ? 4 : 2) * n + 1) * 0x1p-53;
  thread_local std::vector<double> b, bi, err;
  b.assign(n, 0);
  bi.assign(n, 0);
  err.assign(n, 0);
  double B = 0, C = 0, P = 0;  // the majorants of the coefficient being formed
  double bk = 0, bki = 0;
  for (std::size_t k = n; k >= 1; --k) {  // b[k-1] from c[k] and b[k]
    const double Ek = sh.eps * D[k] + kUnderflowSlack;
    P = B + G * P;
    C = Ek + G * C;
    B = (std::hypot(c[k], ci ? (*ci)[k] : 0.0) + Ek) + G * B;
    const double pr = h * bk - hi * bki, pi = h * bki + hi * bk;  // h b_k
    bk = c[k] + pr;
    bki = (ci ? (*ci)[k] : 0.0) + pi;
    b[k - 1] = bk;
    bi[k - 1] = bki;
    err[k - 1] = C + e * P + eps2 * B + kUnderflowSlack;
  }
  double var = 0, rerr = 0;
  for (std::size_t k = n - 1; k >= 1; --k) {
    var = (var + std::hypot(b[k], bi[k])) * sh.r;
    rerr = (rerr + err[k]) * sh.r;
  }
  rerr += err[0];
  const double rad = (var + rerr) * (1 + 0x1p-40) + kUnderflowSlack;
  if (!std::isfinite(rad) || !std::isfinite(b[0]) || !std::isfinite(bi[0])) return false;
  if (rerr > max_error * (std::hypot(b[0], bi[0]) + var)) return false;
  set_out(v, b[0], bi[0], rad, arb_is_zero(acb_imagref(z)));
  return true;
}

}  // namespace uniparam
