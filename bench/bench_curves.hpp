// bench/bench_curves.hpp -- deterministic benchmark curves of any degree,
// built exactly (power-basis rational components with integer coefficients).
//
// Families (the name is what the benchmark table prints):
// * "bez-plane":     polynomial Bezier curve of degree d whose control points
//                    follow a wavy path (several inflections), plane;
// * "bez-rat-space": rational Bezier curve of degree d (positive weights),
//                    control points on a wavy space path;
// * "dense-plane":   random dense integer coefficients in [-9, 9] (both
//                    components, degree d), plane.
// Bezier control points are converted to the power basis exactly:
//     sum_k P_k C(d,k) t^k (1-t)^(d-k) = sum_j t^j C(d,j) sum_{k<=j} (-1)^(j-k) C(j,k) P_k.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "uniparam/reparam/all.hpp"

namespace uniparam::bench {

/// Power-basis coefficients (low to high) of sum_k P_k B_{k,d}(t) for
/// integer control values P_0..P_d (exact).
inline std::vector<Integer> bernstein_to_power(const std::vector<long>& P) {
  const long d = static_cast<long>(P.size()) - 1;
  std::vector<Integer> out;
  Integer cdj(1);  // C(d, j)
  for (long j = 0; j <= d; ++j) {
    if (j > 0) {
      fmpz_mul_ui(cdj.get(), cdj.get(), static_cast<ulong>(d - j + 1));
      fmpz_divexact_ui(cdj.get(), cdj.get(), static_cast<ulong>(j));
    }
    Integer sum(0), cjk(1);  // C(j, k)
    for (long k = 0; k <= j; ++k) {
      if (k > 0) {
        fmpz_mul_ui(cjk.get(), cjk.get(), static_cast<ulong>(j - k + 1));
        fmpz_divexact_ui(cjk.get(), cjk.get(), static_cast<ulong>(k));
      }
      Integer term;
      fmpz_mul_si(term.get(), cjk.get(), P[static_cast<std::size_t>(k)]);
      if ((j - k) % 2) fmpz_sub(sum.get(), sum.get(), term.get());
      else fmpz_add(sum.get(), sum.get(), term.get());
    }
    Integer c;
    fmpz_mul(c.get(), sum.get(), cdj.get());
    out.push_back(c);
  }
  return out;
}

/// Integer samples round(amp * sin(2 pi waves k / d + phase)), k = 0..d.
inline std::vector<long> wave(long d, double amp, double waves, double phase) {
  std::vector<long> v;
  for (long k = 0; k <= d; ++k)
    v.push_back(std::lround(amp * std::sin(2 * M_PI * waves * static_cast<double>(k) / static_cast<double>(d) + phase)));
  return v;
}

/// Number of waves of the control path: several inflections at every degree.
inline double waves_for(long d) { return d < 12 ? 1.5 : d < 50 ? 2.5 : 3.5; }

/// Polynomial plane Bezier curve of degree d >= 2, control points
/// (100 k, wave) (exact integer control points; the scale does not matter).
inline Curve bezier_plane(long d) {
  std::vector<long> x;
  for (long k = 0; k <= d; ++k) x.push_back(100 * k);
  const auto y = wave(d, 40.0 * static_cast<double>(d) / 6.0, waves_for(d), 0.3);
  return Curve({RatFunc(Poly(bernstein_to_power(x))), RatFunc(Poly(bernstein_to_power(y)))});
}

/// Rational space Bezier curve of degree d >= 2: control points
/// (100 k, wave, second wave) with integer weights w_k in {3..7} (positive,
/// so no pole on [0, 1]); components sum w_k P_k B_k / sum w_k B_k.
inline Curve bezier_rat_space(long d) {
  std::vector<long> w, wx, wy, wz;
  const auto y = wave(d, 40.0 * static_cast<double>(d) / 6.0, waves_for(d), 0.3);
  const auto z = wave(d, 30.0 * static_cast<double>(d) / 6.0, waves_for(d) - 1.0, 1.1);
  for (long k = 0; k <= d; ++k) {
    const long wk = 3 + (k * 7) % 5;
    w.push_back(wk);
    wx.push_back(wk * 100 * k);
    wy.push_back(wk * y[static_cast<std::size_t>(k)]);
    wz.push_back(wk * z[static_cast<std::size_t>(k)]);
  }
  const Poly W(bernstein_to_power(w));
  return Curve({RatFunc(Poly(bernstein_to_power(wx)), W), RatFunc(Poly(bernstein_to_power(wy)), W),
                RatFunc(Poly(bernstein_to_power(wz)), W)});
}

/// The curves of bezier_plane (rational: bezier_rat_space) as Bezier input
/// (BezierCurve::to_curve): the same curves, which also keep their Bernstein
/// coefficients (Curve::bernstein), so Speed may evaluate them in the
/// Bernstein basis.
inline Curve bezier_input(long d, bool rational) {
  std::vector<std::vector<Rational>> pts;
  std::vector<Rational> w;
  const auto y = wave(d, 40.0 * static_cast<double>(d) / 6.0, waves_for(d), 0.3);
  const auto z = wave(d, 30.0 * static_cast<double>(d) / 6.0, waves_for(d) - 1.0, 1.1);
  for (long k = 0; k <= d; ++k) {
    std::vector<Rational> p{Rational(100 * k), Rational(y[static_cast<std::size_t>(k)])};
    if (rational) {
      p.push_back(Rational(z[static_cast<std::size_t>(k)]));
      w.push_back(Rational(3 + (k * 7) % 5));
    }
    pts.push_back(std::move(p));
  }
  return BezierCurve(std::move(pts), std::move(w)).to_curve();
}

/// Plane polynomial curve with random dense integer coefficients in [-9, 9]
/// (a fixed linear congruential sequence; no zero coefficient), degree d.
inline Curve dense_plane(long d) {
  unsigned long s = 0x9e3779b97f4a7c15UL ^ static_cast<unsigned long>(d);
  auto next = [&s]() {
    s = s * 6364136223846793005UL + 1442695040888963407UL;
    long c = static_cast<long>((s >> 33) % 19) - 9;
    return c == 0 ? 1L : c;
  };
  std::vector<long> x{0}, y{0};
  for (long k = 1; k <= d; ++k) {
    x.push_back(next());
    y.push_back(next());
  }
  x[1] = 40;  // keep x' away from 0 on [0, 1] at low degree (a regular curve)
  return Curve({RatFunc(Poly(x)), RatFunc(Poly(y))});
}

/// The family by name ("bez-plane", "bez-rat-space", "dense-plane"; and
/// "bern-plane", "bern-rat-space": bezier_input).
inline Curve make_curve(const std::string& family, long d) {
  if (family == "bez-plane") return bezier_plane(d);
  if (family == "bez-rat-space") return bezier_rat_space(d);
  if (family == "dense-plane") return dense_plane(d);
  if (family == "bern-plane") return bezier_input(d, false);
  if (family == "bern-rat-space") return bezier_input(d, true);
  throw InvalidArgument("unknown benchmark curve family '" + family + "'");
}

inline const std::vector<std::string>& families() {
  static const std::vector<std::string> f{"bez-plane", "bez-rat-space", "dense-plane"};
  return f;
}

}  // namespace uniparam::bench
