// reparam/src/breakpoints.cpp -- the floating-point search for the breakpoints
// of a C0 piecewise Moebius map (ImUp's ReparameterizationN; docs/math.md
// section 3). UNCERTIFIED: see the header.
#include "uniparam/reparam/breakpoints.hpp"

#include <algorithm>
#include <cmath>

#include "uniparam/core/error.hpp"

namespace uniparam {

namespace {

struct PhiEval {
  double phi = 0;
  std::vector<double> grad;  ///< dPhi/dt_j, j = 0..N (ends 0)
};

// Phi(T) and its gradient in closed form. For a piece [a, b], h = b - a, with
// A, B, C the integrals over dt (docs/math.md (2.2)) and M = h (B + 2 sqrt(AC)), the
// envelope theorem (alpha* is optimal) gives
//   dM/db =   sqrt(C/A) B + 2 C + h sigma(b)^2 sqrt(A/C),
//   dM/da = -(sqrt(A/C) B + 2 A + h sigma(a)^2 sqrt(C/A)).
using Moments = std::function<PieceMoments(double, double)>;
using Sigma2 = std::function<double(double)>;

PhiEval phi_eval(const Moments& moments, const Sigma2& sigma2, const std::vector<double>& t) {
  const std::size_t N = t.size() - 1;
  std::vector<PieceMoments> abc(N);
  std::vector<double> sqrtM(N);
  PhiEval e;
  for (std::size_t i = 0; i < N; ++i) {
    abc[i] = moments(t[i], t[i + 1]);
    const double M = (t[i + 1] - t[i]) * (abc[i].B + 2 * std::sqrt(abc[i].A * abc[i].C));
    sqrtM[i] = std::sqrt(std::max(M, 1e-300));
    e.phi += sqrtM[i];
  }
  e.grad.assign(N + 1, 0.0);
  for (std::size_t j = 1; j < N; ++j) {
    const double s2 = sigma2(t[j]);
    const PieceMoments& L = abc[j - 1];
    const PieceMoments& R = abc[j];
    const double hl = t[j] - t[j - 1], hr = t[j + 1] - t[j];
    const double rl = std::sqrt(std::max(L.C, 1e-300) / std::max(L.A, 1e-300));
    const double rr = std::sqrt(std::max(R.A, 1e-300) / std::max(R.C, 1e-300));
    const double dMb = rl * L.B + 2 * L.C + hl * s2 / rl;
    const double dMa = -(rr * R.B + 2 * R.A + hr * s2 / rr);
    e.grad[j] = dMb / (2 * sqrtM[j - 1]) + dMa / (2 * sqrtM[j]);
  }
  return e;
}

// Breakpoints from gap logits y (softmax): t_j = sum_{i<j} e^{y_i} / sum e^y.
std::vector<double> from_logits(const std::vector<double>& y) {
  double mx = y[0];
  for (double v : y) mx = std::max(mx, v);
  std::vector<double> g(y.size());
  double z = 0;
  for (std::size_t i = 0; i < y.size(); ++i) z += (g[i] = std::exp(y[i] - mx));
  std::vector<double> t(y.size() + 1, 0.0);
  for (std::size_t i = 0; i < y.size(); ++i) t[i + 1] = t[i] + g[i] / z;
  t.back() = 1.0;
  return t;
}

// dPhi/dy_k = g_k sum_j G_j ([k < j] - t_j), g the normalised gaps.
std::vector<double> logit_grad(const std::vector<double>& t, const std::vector<double>& G) {
  const std::size_t N = t.size() - 1;
  std::vector<double> out(N, 0.0);
  double tot = 0;
  for (std::size_t j = 1; j < N; ++j) tot += G[j] * t[j];
  double suffix = 0;  // sum_{j > k} G_j
  for (std::size_t k = N; k-- > 0;) {
    out[k] = (t[k + 1] - t[k]) * (suffix - tot);
    suffix += G[k];  // G_k joins the sum for k - 1 (j > k - 1 means j >= k)
  }
  return out;
}

double stationarity(const std::vector<double>& t, const PhiEval& e) {
  double worst = 0;
  for (std::size_t j = 1; j + 1 < t.size(); ++j)
    worst = std::max(worst, std::fabs(e.grad[j]) * (t[j + 1] - t[j - 1]) / e.phi);
  return worst;
}

}  // namespace

BreakpointChoice optimise_breakpoints(long N, const Moments& moments, const Sigma2& sigma2) {
  if (N < 1) throw InvalidArgument("optimise_breakpoints: the number of pieces must be at least 1");
  std::vector<double> y(N, 0.0);
  std::vector<double> t = from_logits(y);
  PhiEval e = phi_eval(moments, sigma2, t);
  BreakpointChoice best{t, e.phi, e.phi, stationarity(t, e), 0};
  if (N == 1) return best;
  std::vector<double> gy = logit_grad(t, e.grad);
  // inverse Hessian approximation, dense (N is small)
  std::vector<double> H(N * N, 0.0);
  for (long i = 0; i < N; ++i) H[i * N + i] = 1.0;
  bool scaled = false;
  for (long it = 0; it < 200; ++it) {
    if (best.stationarity < 1e-9) break;
    std::vector<double> d(N, 0.0);
    for (long i = 0; i < N; ++i)
      for (long k = 0; k < N; ++k) d[i] -= H[i * N + k] * gy[k];
    double slope = 0, dmax = 0;
    for (long i = 0; i < N; ++i) {
      slope += d[i] * gy[i];
      dmax = std::max(dmax, std::fabs(d[i]));
    }
    if (!(slope < 0)) {  // lost descent: restart from the steepest direction
      std::fill(H.begin(), H.end(), 0.0);
      for (long i = 0; i < N; ++i) H[i * N + i] = 1.0;
      scaled = false;
      for (long i = 0; i < N; ++i) d[i] = -gy[i];
      slope = 0;
      dmax = 0;
      for (long i = 0; i < N; ++i) {
        slope += d[i] * gy[i];
        dmax = std::max(dmax, std::fabs(d[i]));
      }
      if (!(slope < 0)) break;
    }
    double step = dmax > 1.0 ? 1.0 / dmax : 1.0;  // at most a factor e in any gap per step
    std::vector<double> y2(N), t2;
    PhiEval e2;
    bool accepted = false;
    for (int ls = 0; ls < 40; ++ls, step /= 2) {
      for (long i = 0; i < N; ++i) y2[i] = y[i] + step * d[i];
      t2 = from_logits(y2);
      bool ordered = true;
      for (long j = 0; j < N; ++j) ordered = ordered && t2[j + 1] - t2[j] > 1e-12;
      if (!ordered) continue;
      e2 = phi_eval(moments, sigma2, t2);
      if (e2.phi <= e.phi + 1e-4 * step * slope) {
        accepted = true;
        break;
      }
    }
    if (!accepted) break;
    std::vector<double> gy2 = logit_grad(t2, e2.grad), sv(N), yv(N);
    // Extrapolation (the curvature half of the Wolfe conditions): where the
    // slope along d is still at least 0.9 of the first, Phi is not convex
    // along d (sigma^2 with a sharp peak makes such valleys), the BFGS update
    // would be skipped (s.y <= 0) and the steps stay tiny for ever (seen:
    // 200 iterations moving one breakpoint 3e-2). Double the step while Phi
    // falls and the slope stays steep, up to a factor e^4 in any gap.
    auto dir_slope = [&](const std::vector<double>& g) {
      double v = 0;
      for (long i = 0; i < N; ++i) v += d[i] * g[i];
      return v;
    };
    while (dir_slope(gy2) < 0.9 * slope && 2 * step * dmax <= 4.0) {
      std::vector<double> y3(N);
      for (long i = 0; i < N; ++i) y3[i] = y[i] + 2 * step * d[i];
      const std::vector<double> t3 = from_logits(y3);
      bool ordered = true;
      for (long j = 0; j < N; ++j) ordered = ordered && t3[j + 1] - t3[j] > 1e-12;
      if (!ordered) break;
      const PhiEval e3 = phi_eval(moments, sigma2, t3);
      if (!(e3.phi < e2.phi)) break;
      step *= 2;
      y2 = y3;
      t2 = t3;
      e2 = e3;
      gy2 = logit_grad(t2, e2.grad);
    }
    double sy = 0, yy = 0;
    for (long i = 0; i < N; ++i) {
      sv[i] = y2[i] - y[i];
      yv[i] = gy2[i] - gy[i];
      sy += sv[i] * yv[i];
      yy += yv[i] * yv[i];
    }
    if (sy > 1e-300) {
      if (!scaled) {  // Shanno's scaling of the first approximation
        for (long i = 0; i < N; ++i) H[i * N + i] = sy / yy;
        scaled = true;
      }
      // BFGS update of the inverse Hessian
      std::vector<double> Hy(N, 0.0);
      for (long i = 0; i < N; ++i)
        for (long k = 0; k < N; ++k) Hy[i] += H[i * N + k] * yv[k];
      double yHy = 0;
      for (long i = 0; i < N; ++i) yHy += yv[i] * Hy[i];
      const double rho = 1.0 / sy;
      for (long i = 0; i < N; ++i)
        for (long k = 0; k < N; ++k)
          H[i * N + k] += rho * ((1 + rho * yHy) * sv[i] * sv[k] - Hy[i] * sv[k] - sv[i] * Hy[k]);
    }
    // Stalled at double precision (the gradient's noise keeps stationarity
    // above its threshold; seen: 160 iterations that moved nothing by 1e-12)
    double moved = 0;
    for (long j = 1; j < N; ++j) moved = std::max(moved, std::fabs(t2[j] - t[j]));
    const bool stalled = moved <= 1e-12 && e.phi - e2.phi <= 1e-15 * e.phi;
    y = y2;
    t = t2;
    e = e2;
    gy = gy2;
    best.t = t;
    best.phi = e.phi;
    best.stationarity = stationarity(t, e);
    best.iterations = it + 1;
    if (stalled) break;
  }
  return best;
}

}  // namespace uniparam
