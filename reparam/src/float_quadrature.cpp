#include "float_quadrature.hpp"

#include <acb.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "uniparam/core/budget.hpp"

namespace uniparam::detail {

double sigma2_double(const Speed& s, double t, long scale_exp) {
  // Double evaluation from local expansions (no power-basis cancellation);
  // the ball path below only where it is not finite (cusps, 0/0) or, with a
  // scale, not a normal double (beyond double's range before the scaling).
  const double d = s.squared_double(t);
  if (scale_exp == 0 && std::isfinite(d) && d >= 0) return d;
  if (scale_exp != 0 && std::isfinite(d) && d >= 0x1p-900 && d <= 0x1p900)
    return std::ldexp(d, static_cast<int>(-2 * scale_exp));
  acb_t z, w;
  acb_init(z);
  acb_init(w);
  acb_set_d(z, t);
  double v = 0;
  // Start at the precision that sufficed for the previous point of the same
  // speed (high degrees lose 100+ bits to cancellation everywhere, and every
  // failed attempt costs a full evaluation); only a hint, per thread.
  thread_local const Speed* last_speed = nullptr;
  thread_local long last_prec = 64;
  long prec = last_speed == &s ? last_prec : 64;
  for (; prec <= 1024; prec *= 2) {
    s.eval_squared(w, z, prec);
    acb_mul_2exp_si(w, w, -2 * scale_exp);
    v = arf_get_d(arb_midref(acb_realref(w)), ARF_RND_NEAR);
    const double r = mag_get_d(arb_radref(acb_realref(w)));
    if (std::isfinite(v) && r <= 1e-14 * std::fabs(v) + 1e-300) break;
  }
  last_speed = &s;
  last_prec = std::min(prec, 1024L);
  acb_clear(z);
  acb_clear(w);
  return std::isfinite(v) && v > 0 ? v : 0.0;
}

namespace {

constexpr int kNodes = GaussLegendre20::kNodes;

// The C1 draft's budget of panel pairs per piece part (FloatPieces::get):
// a smooth sigma settles within a few dozen; an integrand whose double
// evaluation is noisier than the tolerance somewhere (a near-pole of the
// components that sigma itself does not have, as on a curve balanced by a
// Moebius map) would otherwise bisect there to depth 30 in every piece
// that reaches it. Its estimate then holds what the budget reached, which
// only steers the draft: the C1 method certifies what it chooses.
constexpr long kDraftPanelPairs = 1024;

GaussLegendre20 make_rule() {
  // Gauss-Legendre nodes on [-1, 1] by Newton's method on P_n.
  GaussLegendre20 r{};
  for (int i = 0; i < kNodes; ++i) {
    double z = std::cos(M_PI * (i + 0.75) / (kNodes + 0.5)), dp = 0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= kNodes; ++k) {
        const double p2 = ((2.0 * k - 1) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = kNodes * (z * p1 - p0) / (z * z - 1);
      const double dz = p1 / dp;
      z -= dz;
      if (std::fabs(dz) < 1e-16) break;
    }
    r.x[i] = z;
    r.w[i] = 2 / ((1 - z * z) * dp * dp);
  }
  return r;
}

// The FloatPiece integrals of one 20-point panel [l, r] of the piece
// [a, a + h]: the moments of sigma^2 (float_abc, the C1 draft) and, with
// kLength, the length (the C1 draft; float_abc leaves it 0).
template <bool kLength>
FloatPiece panel(const Speed& s, double a, double h, double l, double r, long scale_exp) {
  const GaussLegendre20& g = gauss_legendre20();
  FloatPiece out;
  const double m = (l + r) / 2, k = (r - l) / 2;
  for (int i = 0; i < kNodes; ++i) {
    const double t = m + k * g.x[i], u = (t - a) / h, s2 = sigma2_double(s, t, scale_exp), f = s2 * g.w[i] * k;
    out.A += f * (1 - u) * (1 - u);
    out.B += f * 2 * u * (1 - u);
    out.C += f * u * u;
    if (kLength) out.len += std::sqrt(s2) * g.w[i] * k;
  }
  return out;
}

// Adaptive bisection of [l, r] within the piece [a, a + h], from `whole`,
// its panel's estimate: stops where the two halves change the sigma^2
// moments by at most tol * scale2 and, with kLength, the length by at most
// tol * scale1; at 30 levels, at panels narrower than 1e-15, or when the
// budget of panel pairs runs out (the halves' estimate is returned). The
// left half is refined before the right, so the budget goes left to right.
// The time budget is checked every 4 levels: at most 31 calls between checks.
template <bool kLength>
FloatPiece refine(const Speed& s, long scale_exp, double a, double h, double l, double r, const FloatPiece& whole,
                  double tol, double scale2, double scale1, int depth, long& budget) {
  if (depth % 4 == 0) check_time_budget();
  --budget;
  const double m = (l + r) / 2;
  const FloatPiece left = panel<kLength>(s, a, h, l, m, scale_exp), right = panel<kLength>(s, a, h, m, r, scale_exp),
                   both = left + right;
  const double d2 = std::fabs(both.A - whole.A) + std::fabs(both.B - whole.B) + std::fabs(both.C - whole.C);
  const bool settled = d2 <= tol * scale2 && (!kLength || std::fabs(both.len - whole.len) <= tol * scale1);
  if (depth >= 30 || budget <= 0 || r - l < 1e-15 || settled) return both;
  const FloatPiece x = refine<kLength>(s, scale_exp, a, h, l, m, left, tol, scale2, scale1, depth + 1, budget);
  const FloatPiece y = refine<kLength>(s, scale_exp, a, h, m, r, right, tol, scale2, scale1, depth + 1, budget);
  return x + y;
}

}  // namespace

const GaussLegendre20& gauss_legendre20() {
  static const GaussLegendre20 r = make_rule();
  return r;
}

double FloatABC::M(double h) const { return h * (B + 2 * std::sqrt(A * C)); }

FloatABC float_abc(const Speed& s, double a, double b) {
  const double h = b - a;
  const FloatPiece whole = panel<false>(s, a, h, a, b, 0);
  const double scale = std::fabs(whole.A) + std::fabs(whole.B) + std::fabs(whole.C);
  // Tolerance 1e-12 and at most 256 panel pairs (10240 evaluations of
  // sigma^2): an integrand whose double evaluation is noisier than the
  // tolerance (e.g. rational space curves) would otherwise bisect everywhere
  // to depth 30; the result only steers the optimiser, which certifies what
  // it chooses.
  long budget = 256;
  const FloatPiece v = refine<false>(s, 0, a, h, a, b, whole, 1e-12, scale, 0, 0, budget);
  return FloatABC{v.A, v.B, v.C};
}

FloatPiece operator+(const FloatPiece& x, const FloatPiece& y) {
  return FloatPiece{x.A + y.A, x.B + y.B, x.C + y.C, x.len + y.len};
}

double midpoint_double(const RealAlgebraic& x) {
  return arf_get_d(arb_midref(x.to_ball(64).get()), ARF_RND_NEAR);
}

FloatPieces::FloatPieces(const Speed& s, long scale_exp) : s_(s), scale_exp_(scale_exp) {
  for (const auto& z : s.zeros()) zeros_.push_back(midpoint_double(z.t));
}

const FloatPiece& FloatPieces::get(double a, double b) {
  const auto key = std::make_pair(a, b);
  auto it = cache_.find(key);
  if (it != cache_.end()) return it->second;
  const double h = b - a;
  FloatPiece total;
  // split at the zeros of sigma inside (a, b): sigma = |g| ... is not smooth there
  std::vector<double> ends{a};
  for (double z : zeros_)
    if (z > a && z < b) ends.push_back(z);
  ends.push_back(b);
  FloatPiece first;
  for (std::size_t j = 0; j + 1 < ends.size(); ++j)
    first = first + panel<true>(s_, a, h, ends[j], ends[j + 1], scale_exp_);
  const double scale2 = std::fabs(first.A) + std::fabs(first.B) + std::fabs(first.C) + 1e-300;
  const double scale1 = std::fabs(first.len) + 1e-300;
  for (std::size_t j = 0; j + 1 < ends.size(); ++j) {
    const FloatPiece w = panel<true>(s_, a, h, ends[j], ends[j + 1], scale_exp_);
    long budget = kDraftPanelPairs;
    total = total + refine<true>(s_, scale_exp_, a, h, ends[j], ends[j + 1], w, 1e-13, scale2, scale1, 0, budget);
  }
  return cache_.emplace(key, total).first->second;
}

}  // namespace uniparam::detail
