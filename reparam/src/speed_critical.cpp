// speed_critical.cpp -- the evaluations behind the search for critical
// points and breakpoints: Speed::eval_critical (the critical numerator P
// and P' in Arb's balls) and Speed::squared_double (sigma^2 in IEEE double,
// uncertified).
#include <vector>

#include "curve_model.hpp"
#include "speed_enclosure.hpp"
#include "uniparam/reparam/speed.hpp"

namespace uniparam {

double Speed::squared_double(double t) const {
  if (zero_) return 0;
  const CurveModel& m = *model_;
  const std::size_t n = m.size();
  double buf[16];  // the optimisers call this ~10^5 times: no allocation up to 8 components
  std::vector<double> heap(n > 8 ? 2 * n : 0);
  double* d1 = n > 8 ? heap.data() : buf;
  double* d2 = d1 + n;
  for (std::size_t i = 0; i < n; ++i) {
    double nv, n1, n2, q, q1, q2;
    m.eval_num_double(i, t, &nv, &n1, &n2);
    m.eval_den_double(i, t, &q, &q1, &q2);
    const double a = n1 * q - nv * q1, qq = q * q;
    d1[i] = a / qq;
    d2[i] = (n2 * q - nv * q2) / qq - 2 * q1 * a / (qq * q);
  }
  double S = 0;
  for (std::size_t i = 0; i < n; ++i) S += d1[i] * d1[i];
  if (kind_ == SpeedKind::Parametric) return S;
  double F = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const double e = d1[i] * d2[j] - d2[i] * d1[j];
      F += e * e;
    }
  return F / (S * S);
}

namespace {

// sum_of_squares_d2: s = sum p_i^2, s1 = (sum p_i^2)' = 2 sum p_i p_i' and, when s2 is
// non-null, s2 = (sum p_i^2)'' = 2 sum (p_i'^2 + p_i p_i'').
void sum_of_squares_d2(acb_t s, acb_t s1, acb_t s2, const std::vector<LocalPoly>& ps, const acb_t z, long prec) {
  AcbBox a, a1, a2;
  acb_zero(s);
  acb_zero(s1);
  if (s2) acb_zero(s2);
  for (const auto& p : ps) {
    p.eval(a, a1, s2 ? a2.get() : nullptr, z, prec);
    acb_addmul(s, a, a, prec);
    acb_addmul(s1, a, a1, prec);
    if (s2) {
      acb_addmul(s2, a1, a1, prec);
      acb_addmul(s2, a, a2, prec);
    }
  }
  acb_mul_2exp_si(s1, s1, 1);
  if (s2) acb_mul_2exp_si(s2, s2, 1);
}

}  // namespace

void Speed::eval_critical(acb_t v, acb_t d, const acb_t z, long prec) const {
  if (zero_) {
    acb_zero(v);
    if (d) acb_zero(d);
    return;
  }
  AcbBox g[3], q[3], e[3], t, u;
  g_b_.eval(g[0], g[1], d ? g[2].get() : nullptr, z, prec);
  sum_of_squares_d2(q[0], q[1], d ? q[2].get() : nullptr, K_b_, z, prec);  // Q = sum K^2
  if (Y_b_.empty()) W_b_.eval(e[0], e[1], d ? e[2].get() : nullptr, z, prec);  // D = W
  else sum_of_squares_d2(e[0], e[1], d ? e[2].get() : nullptr, Y_b_, z, prec);                     // D = sum Y^2
  // P = (2 g' Q + g Q') D - 2 g Q D'
  acb_mul(t, g[1], q[0], prec);
  acb_mul_2exp_si(t, t, 1);
  acb_addmul(t, g[0], q[1], prec);
  acb_mul(v, t, e[0], prec);  // (2 g' Q + g Q') D
  acb_mul(t, g[0], q[0], prec);
  acb_mul_2exp_si(t, t, 1);
  acb_submul(v, t, e[1], prec);  // - 2 g Q D'
  if (d) {
    // P' = (2 g'' Q + 3 g' Q' + g Q'') D - g Q' D' - 2 g Q D''
    acb_mul(t, g[2], q[0], prec);
    acb_mul_2exp_si(t, t, 1);
    acb_addmul(t, g[0], q[2], prec);
    acb_mul(u, g[1], q[1], prec);
    acb_mul_ui(u, u, 3, prec);
    acb_add(t, t, u, prec);
    acb_mul(d, t, e[0], prec);  // (2 g'' Q + 3 g' Q' + g Q'') D
    acb_mul(t, g[0], q[1], prec);
    acb_submul(d, t, e[1], prec);  // - g Q' D'
    acb_mul(t, g[0], q[0], prec);
    acb_mul_2exp_si(t, t, 1);
    acb_submul(d, t, e[2], prec);  // - 2 g Q D''
  }
}

}  // namespace uniparam
