#include "float_quadrature.hpp"

#include <acb.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace uniparam::detail {

double sigma2_double(const Speed& s, double t) {
  // Double evaluation from local expansions (no power-basis cancellation);
  // the ball path below only where it is not finite (cusps, 0/0).
  const double d = s.squared_double(t);
  if (std::isfinite(d) && d >= 0) return d;
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

struct Acc {
  double a = 0, b = 0, c = 0;
};

// A, B, C contributions of [l, r] inside the piece [a, a + h].
Acc panel(const Speed& s, double a, double h, double l, double r) {
  const GaussLegendre20& g = gauss_legendre20();
  Acc out;
  const double m = (l + r) / 2, k = (r - l) / 2;
  for (int i = 0; i < kNodes; ++i) {
    const double t = m + k * g.x[i], u = (t - a) / h, f = sigma2_double(s, t) * g.w[i] * k;
    out.a += f * (1 - u) * (1 - u);
    out.b += f * 2 * u * (1 - u);
    out.c += f * u * u;
  }
  return out;
}

// Refines until the estimate of [l, r] changes by at most 1e-12 of `scale`
// or the budget of panel pairs runs out (an integrand whose double
// evaluation is noisier than the tolerance, e.g. rational space curves, would
// otherwise bisect everywhere to depth 30; the result only steers the
// optimiser, which certifies what it chooses)
// (the size of the whole piece's first estimate), so tiny panels stop early.
Acc adapt(const Speed& s, double a, double h, double l, double r, const Acc& whole, double scale, int depth,
          int& budget) {
  --budget;
  const double m = (l + r) / 2;
  const Acc left = panel(s, a, h, l, m), right = panel(s, a, h, m, r);
  const double diff = std::fabs(left.a + right.a - whole.a) + std::fabs(left.b + right.b - whole.b) +
                      std::fabs(left.c + right.c - whole.c);
  if (depth >= 30 || budget <= 0 || diff <= 1e-12 * scale || r - l < 1e-15) {
    return Acc{left.a + right.a, left.b + right.b, left.c + right.c};
  }
  const Acc x = adapt(s, a, h, l, m, left, scale, depth + 1, budget);
  const Acc y = adapt(s, a, h, m, r, right, scale, depth + 1, budget);
  return Acc{x.a + y.a, x.b + y.b, x.c + y.c};
}

}  // namespace

const GaussLegendre20& gauss_legendre20() {
  static const GaussLegendre20 r = make_rule();
  return r;
}

double FloatABC::M(double h) const { return h * (B + 2 * std::sqrt(A * C)); }

FloatABC float_abc(const Speed& s, double a, double b) {
  const double h = b - a;
  const Acc whole = panel(s, a, h, a, b);
  const double scale = std::fabs(whole.a) + std::fabs(whole.b) + std::fabs(whole.c);
  int budget = 256;  // panel pairs: 10240 evaluations of sigma^2 at most
  const Acc v = adapt(s, a, h, a, b, whole, scale, 0, budget);
  return FloatABC{v.a, v.b, v.c};
}

}  // namespace uniparam::detail
