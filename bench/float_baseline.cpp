// bench/float_baseline.cpp -- UNCERTIFIED double-precision baseline (see the header).
#include "float_baseline.hpp"

#include <flint/fmpz.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <queue>

namespace uniparam::fp {

namespace {

// ---------------------------------------------------------------- dual numbers
struct Dual {
  double v = 0, d = 0;
};
inline Dual operator+(Dual a, Dual b) { return {a.v + b.v, a.d + b.d}; }
inline Dual operator-(Dual a, Dual b) { return {a.v - b.v, a.d - b.d}; }
inline Dual operator*(Dual a, Dual b) { return {a.v * b.v, a.d * b.v + a.v * b.d}; }
inline Dual operator/(Dual a, Dual b) { return {a.v / b.v, (a.d * b.v - a.v * b.d) / (b.v * b.v)}; }
inline Dual operator*(double s, Dual a) { return {s * a.v, s * a.d}; }
inline double val(double x) { return x; }
inline double val(Dual x) { return x.v; }

template <class T>
T horner(const std::vector<double>& c, T t) {
  T r{};
  for (std::size_t i = c.size(); i-- > 0;) r = r * t + T{c[i]};
  return r;
}

std::vector<double> derivative(const std::vector<double>& c) {
  std::vector<double> d;
  for (std::size_t i = 1; i < c.size(); ++i) d.push_back(static_cast<double>(i) * c[i]);
  if (d.empty()) d.push_back(0);
  return d;
}

// sum x'^2 and F (angular: sum_{i<j} E_ij^2; plane: E unsquared) at t.
template <class T>
void components(const FloatCurve& c, bool angular, T t, T& S, T& F) {
  std::vector<T> d1, d2;
  for (const auto& k : c.comp) {
    T n = horner(k.N, t), n1 = horner(k.N1, t), q = horner(k.Q, t), q1 = horner(k.Q1, t);
    T a = n1 * q - n * q1, q2v = q * q;
    d1.push_back(a / q2v);
    if (angular) {
      T n2 = horner(k.N2, t), qq2 = horner(k.Q2, t);
      d2.push_back((n2 * q - n * qq2) / q2v - 2.0 * (q1 * a) / (q2v * q));
    }
  }
  S = T{};
  for (const auto& x : d1) S = S + x * x;
  F = T{};
  if (!angular) return;
  const std::size_t n = d1.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      T e = d1[i] * d2[j] - d2[i] * d1[j];
      F = n == 2 ? e : F + e * e;
    }
}

template <class T>
T sigma2_t(const FloatCurve& c, SpeedKind kind, T t) {
  T S, F;
  components(c, kind == SpeedKind::Angular, t, S, F);
  if (kind == SpeedKind::Parametric) return S;
  if (c.comp.size() == 2) F = F * F;
  return F / (S * S);
}

// A signed function whose sign changes are the zeros of sigma (plane angular:
// E / S), or sigma^2 itself (no sign information) otherwise.
double signed_speed(const FloatCurve& c, SpeedKind kind, double t) {
  double S, F;
  components(c, kind == SpeedKind::Angular, t, S, F);
  if (kind == SpeedKind::Angular && c.comp.size() == 2) return F / S;
  return sigma2_t(c, kind, t);
}

double bisect(const std::function<double(double)>& f, double a, double b) {
  double fa = f(a);
  for (int i = 0; i < 200 && b - a > 0; ++i) {
    const double m = 0.5 * (a + b);
    if (m <= a || m >= b) break;
    const double fm = f(m);
    if (fm == 0) return m;
    if ((fm < 0) == (fa < 0)) { a = m; fa = fm; }
    else b = m;
  }
  return 0.5 * (a + b);
}

// ------------------------------------------------------ Gauss-Kronrod G7/K15
const double xgk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                       0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                       0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                       0.207784955007898467600689403773245, 0.0};
const double wgk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                       0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                       0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                       0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
const double wg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                      0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

constexpr double kRelTol = 1e-13;
constexpr int kMaxIntervals = 4000;

template <int K>
struct Seg {
  double a, b;
  std::array<double, K> val, err;
  double key;
  bool operator<(const Seg& o) const { return key < o.key; }
};

// QUADPACK qk15 on [a, b] for K functions evaluated together.
template <int K, class F>
Seg<K> qk15(const F& f, double a, double b) {
  Seg<K> s{a, b, {}, {}, 0};
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  std::array<double, K> fv[15];
  fv[7] = f(c);
  for (int j = 0; j < 7; ++j) {
    fv[j] = f(c - h * xgk[j]);
    fv[14 - j] = f(c + h * xgk[j]);
  }
  for (int k = 0; k < K; ++k) {
    double resk = wgk[7] * fv[7][k], resg = wg[3] * fv[7][k], resabs = std::fabs(resk);
    for (int j = 0; j < 7; ++j) {
      const double s2 = fv[j][k] + fv[14 - j][k];
      resk += wgk[j] * s2;
      resabs += wgk[j] * (std::fabs(fv[j][k]) + std::fabs(fv[14 - j][k]));
      if (j % 2 == 1) resg += wg[j / 2] * s2;
    }
    const double mean = 0.5 * resk;
    double resasc = wgk[7] * std::fabs(fv[7][k] - mean);
    for (int j = 0; j < 7; ++j) resasc += wgk[j] * (std::fabs(fv[j][k] - mean) + std::fabs(fv[14 - j][k] - mean));
    double err = std::fabs((resk - resg) * h);
    resasc *= std::fabs(h);
    resabs *= std::fabs(h);
    if (resasc != 0 && err != 0) err = resasc * std::min(1.0, std::pow(200 * err / resasc, 1.5));
    if (resabs > 2.2250738585072014e-308 / (50 * 2.220446049250313e-16))
      err = std::max(50 * 2.220446049250313e-16 * resabs, err);
    s.val[k] = resk * h;
    s.err[k] = std::isfinite(err) ? err : HUGE_VAL;
  }
  return s;
}

// Global adaptive bisection (QUADPACK qag style) of K integrals at once.
template <int K, class F>
std::array<double, K> adapt(const F& f, double a, double b, bool& converged) {
  std::priority_queue<Seg<K>> q;
  std::array<double, K> tot{}, err{};
  auto push = [&](Seg<K> s) {
    s.key = 0;
    for (int k = 0; k < K; ++k) {
      tot[k] += s.val[k];
      err[k] += s.err[k];
      s.key = std::max(s.key, s.err[k]);
    }
    q.push(s);
  };
  push(qk15<K>(f, a, b));
  for (int n = 1;; ++n) {
    bool done = true;
    for (int k = 0; k < K; ++k) done = done && err[k] <= std::max(kRelTol * std::fabs(tot[k]), 1e-300);
    if (done) { converged = true; break; }
    if (n >= kMaxIntervals || q.empty()) { converged = false; break; }
    Seg<K> s = q.top();
    q.pop();
    for (int k = 0; k < K; ++k) {
      tot[k] -= s.val[k];
      err[k] -= s.err[k];
    }
    const double m = 0.5 * (s.a + s.b);
    push(qk15<K>(f, s.a, m));
    push(qk15<K>(f, m, s.b));
  }
  // re-sum (the running sums drift)
  std::array<double, K> out{};
  while (!q.empty()) {
    for (int k = 0; k < K; ++k) out[k] += q.top().val[k];
    q.pop();
  }
  return out;
}

Piece finish(double A, double B, double C) {
  Piece p{A, B, C, A + B + C, 0, 0};
  p.M = B + 2 * std::sqrt(A * C);
  p.alpha = 1 / (1 + std::sqrt(C / A));
  return p;
}

// A, B, C of one piece [a, b]; side -1 none, 0 zero at the left end, 1 at the right; mu its multiplicity.
Piece piece(const FloatCurve& c, SpeedKind kind, double a, double b, int side, int mu, bool& conv) {
  const double dt = b - a;
  auto f = [&](double t) -> std::array<double, 3> {
    const double tt = (t - a) / dt;
    double s2 = speed_squared(c, kind, t), st = tt;
    if (side < 0) {
      s2 *= dt;
    } else if (side == 0) {  // naive: sigma^2 / t~^mu (Hong, Wang, Yang 2023, section 5)
      s2 *= dt / ((mu + 1) * std::pow(tt, mu));
      st = std::pow(tt, mu + 1);
    } else {
      s2 *= dt / ((mu + 1) * std::pow(1 - tt, mu));
      st = 1 - std::pow(1 - tt, mu + 1);
    }
    return {s2 * (1 - st) * (1 - st), s2 * 2 * st * (1 - st), s2 * st * st};
  };
  bool ok = true;
  auto r = adapt<3>(f, a, b, ok);
  conv = conv && ok;
  return finish(r[0], r[1], r[2]);
}

std::vector<double> cumulative(const std::vector<double>& w) {
  double tot = 0;
  for (double x : w) tot += x;
  std::vector<double> out{0};
  double acc = 0;
  for (std::size_t k = 0; k + 1 < w.size(); ++k) {
    acc += w[k];
    out.push_back(acc / tot);
  }
  out.push_back(1);
  return out;
}

}  // namespace

FloatCurve to_float(const Curve& c) {
  FloatCurve out;
  out.degree = c.degree();
  auto conv = [](const Poly& p) {
    std::vector<double> v;
    for (long i = 0; i <= p.degree(); ++i) v.push_back(fmpz_get_d(p.coeff(i).get()));
    if (v.empty()) v.push_back(0);
    return v;
  };
  for (const auto& x : c.components()) {
    FloatCurve::Component k;
    k.N = conv(x.num());
    k.Q = conv(x.den());
    k.N1 = derivative(k.N);
    k.N2 = derivative(k.N1);
    k.Q1 = derivative(k.Q);
    k.Q2 = derivative(k.Q1);
    out.comp.push_back(std::move(k));
  }
  return out;
}

double speed_squared(const FloatCurve& c, SpeedKind kind, double t) { return sigma2_t(c, kind, t); }

double speed(const FloatCurve& c, SpeedKind kind, double t) {
  double S, F;
  components(c, kind == SpeedKind::Angular, t, S, F);
  if (kind == SpeedKind::Parametric) return std::sqrt(S);
  if (c.comp.size() == 2) return std::fabs(F) / S;
  return std::sqrt(F) / S;
}

double correct_digits(double x, const Ball& ref) {
  if (!std::isfinite(x)) return 0;
  arb_t d;
  arb_init(d);
  arb_set_d(d, x);
  arb_sub(d, d, ref.get(), 128);
  arb_abs(d, d);
  arb_div(d, d, ref.get(), 128);
  arb_abs(d, d);
  const double rel = arf_get_d(arb_midref(d), ARF_RND_UP) + mag_get_d(arb_radref(d));
  arb_clear(d);
  if (!(rel > 1e-17)) return 17;
  if (!std::isfinite(rel)) return 0;
  return std::max(0.0, std::min(17.0, -std::log10(rel)));
}

double integrate(double (*f)(double, const void*), const void* ctx, double a, double b, bool* converged) {
  bool ok = true;
  auto r = adapt<1>([&](double t) { return std::array<double, 1>{f(t, ctx)}; }, a, b, ok);
  if (converged) *converged = ok;
  return r[0];
}

Uniformity uniformity(const FloatCurve& c, SpeedKind kind) {
  Uniformity u;
  bool ok1 = true, ok2 = true;
  u.mu = adapt<1>([&](double t) { return std::array<double, 1>{speed(c, kind, t)}; }, 0.0, 1.0, ok1)[0];
  u.mean_square =
      adapt<1>([&](double t) { return std::array<double, 1>{speed_squared(c, kind, t)}; }, 0.0, 1.0, ok2)[0];
  u.u = u.mu * u.mu / u.mean_square;
  u.converged = ok1 && ok2;
  return u;
}

Radical radical(const FloatCurve& c, SpeedKind kind) {
  Radical r;
  const Uniformity base = uniformity(c, kind);
  r.mu = base.mu;
  r.u_before = base.u;
  r.converged = base.converged;
  const long n = 8 * c.degree + 64;
  const double h = 1.0 / static_cast<double>(n);
  // zeros of sigma: sign changes of the signed speed (plane angular), or tiny
  // local minima of sigma^2 (refined by bisection on its derivative).
  const bool signed_ok = kind == SpeedKind::Angular && c.comp.size() == 2;
  std::vector<double> grid(static_cast<std::size_t>(n + 1)), dg(static_cast<std::size_t>(n + 1));
  double smax = 0;
  for (long i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) * h;
    grid[static_cast<std::size_t>(i)] = signed_speed(c, kind, t);
    dg[static_cast<std::size_t>(i)] = sigma2_t(c, kind, Dual{t, 1}).d;
    smax = std::max(smax, speed_squared(c, kind, t));
  }
  auto dsig2 = [&](double t) { return sigma2_t(c, kind, Dual{t, 1}).d; };
  std::vector<double> zeros, crit;
  for (long i = 0; i < n; ++i) {
    const double a = static_cast<double>(i) * h, b = static_cast<double>(i + 1) * h;
    const double ga = grid[static_cast<std::size_t>(i)], gb = grid[static_cast<std::size_t>(i + 1)];
    const double da = dg[static_cast<std::size_t>(i)], db = dg[static_cast<std::size_t>(i + 1)];
    if (signed_ok && ((ga < 0 && gb > 0) || (ga > 0 && gb < 0))) {
      zeros.push_back(bisect([&](double t) { return signed_speed(c, kind, t); }, a, b));
    } else if (da < 0 && db > 0) {  // a minimum of sigma^2: a zero when (near) 0
      const double t = bisect(dsig2, a, b);
      if (speed_squared(c, kind, t) <= 1e-20 * smax) zeros.push_back(t);
      else crit.push_back(t);
    } else if (da > 0 && db < 0) {
      crit.push_back(bisect(dsig2, a, b));
    }
  }
  // drop critical points that are zeros (sigma^2 has a minimum at each zero)
  std::vector<double> ts{0.0, 1.0};
  std::vector<int> mults{0, 0};
  auto add = [&](double t, int m) {
    if (t <= 0 || t >= 1) return;
    ts.push_back(t);
    mults.push_back(m);
  };
  for (double z : zeros) {
    // multiplicity from the growth sigma(z + 2e) / sigma(z + e) ~ 2^mu
    const double e = 1e-4;
    const double zz = z + e < 1 ? z : z - 3 * e, sgn = z + e < 1 ? 1 : -1;
    const double q = speed(c, kind, zz + 2 * sgn * e) / speed(c, kind, zz + sgn * e);
    add(z, std::max(1, static_cast<int>(std::lround(std::log2(q)))));
  }
  for (double t : crit) {
    bool near = false;
    for (double z : zeros) near = near || std::fabs(t - z) < 4 * h;
    if (!near) add(t, 0);
  }
  std::vector<std::size_t> idx(ts.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](std::size_t x, std::size_t y) { return ts[x] < ts[y]; });
  for (std::size_t i : idx) {
    if (!r.T.empty() && r.mult.back() > 0 && mults[i] > 0) {
      r.T.push_back(0.5 * (r.T.back() + ts[i]));
      r.mult.push_back(0);
    }
    r.T.push_back(ts[i]);
    r.mult.push_back(mults[i]);
  }
  const std::size_t N = r.T.size() - 1;
  std::vector<double> sL, sM;
  double sumL = 0, sumM = 0;
  for (std::size_t i = 0; i < N; ++i) {
    const int side = r.mult[i] > 0 ? 0 : r.mult[i + 1] > 0 ? 1 : -1;
    const int mu = side == 0 ? r.mult[i] : side == 1 ? r.mult[i + 1] : 0;
    r.pieces.push_back(piece(c, kind, r.T[i], r.T[i + 1], side, mu, r.converged));
    sL.push_back(std::sqrt(r.pieces.back().L));
    sM.push_back(std::sqrt(r.pieces.back().M));
    sumL += sL.back();
    sumM += sM.back();
  }
  r.S = cumulative(sL);
  r.Z = cumulative(sM);
  r.u_radical = r.mu * r.mu / (sumL * sumL);
  r.u_after = r.mu * r.mu / (sumM * sumM);
  return r;
}

Moebius moebius_c0(const FloatCurve& c, SpeedKind kind, const std::vector<double>& T) {
  Moebius m;
  const Uniformity base = uniformity(c, kind);
  m.mu = base.mu;
  m.u_before = base.u;
  m.converged = base.converged;
  m.T = T;
  std::vector<double> sM;
  double sum = 0;
  for (std::size_t i = 0; i + 1 < T.size(); ++i) {
    m.pieces.push_back(piece(c, kind, T[i], T[i + 1], -1, 0, m.converged));
    m.alpha.push_back(m.pieces.back().alpha);
    sM.push_back(std::sqrt(m.pieces.back().M));
    sum += sM.back();
  }
  m.S = cumulative(sM);
  m.u_after = m.mu * m.mu / (sum * sum);
  return m;
}

Moebius reparam_c0(const FloatCurve& c, SpeedKind kind, int N) {
  // The library's breakpoint search (the same BFGS on Phi as the certified
  // reparam_c0) on this baseline's own double quadrature and speed.
  bool conv = true;
  const BreakpointChoice ch = optimise_breakpoints(
      N,
      [&](double a, double b) {
        const Piece p = piece(c, kind, a, b, -1, 0, conv);  // over du: h times the integrals over dt
        const double h = b - a;
        return PieceMoments{p.A / h, p.B / h, p.C / h};
      },
      [&](double t) { return speed_squared(c, kind, t); });
  Moebius m = moebius_c0(c, kind, ch.t);
  m.converged = m.converged && conv;
  m.iterations = ch.iterations;
  return m;
}

}  // namespace uniparam::fp
