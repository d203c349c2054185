// approx_roots.cpp -- UNCERTIFIED complex root approximations
// (approx_roots.hpp): the Aberth-Ehrlich iteration in IEEE double.
#include "uniparam/algebra/approx_roots.hpp"

#include <flint/fmpz.h>
#include <flint/fmpz_poly.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "uniparam/core/error.hpp"
#include "uniparam/core/horner_loss.hpp"

namespace uniparam {
namespace {

using C = std::complex<double>;

// A root is settled (no longer updated) once its correction is below this
// fraction of max(|z|, 1): hints need a few digits, not all 15.
constexpr double kSettled = 0x1p-30;
// approximate_roots_near_unit_interval: a root is also settled once its
// correction is below this fraction of its distance from [-1, 1] (where
// the centred basis is not made for them, roots far out may never reach
// kSettled: on dense-plane d = 50's D, 70 of 98 roots of the centred basis
// were still moving after 60 sweeps; hints far out need a few digits).
constexpr double kFarSettled = 0x1p-12;

constexpr double kPi = 3.14159265358979323846;  // M_PI is POSIX, not C++

// Plain complex products and quotients: std::complex's operators call
// __muldc3 / __divdc3 (C99 Annex G's infinity and NaN recovery), several
// times slower, and this iteration discards non-finite steps anyway.
inline C mul(C a, C b) { return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()}; }
inline C inv(C a) {  // one division: the sum over the other roots takes one per pair
  const double d = 1 / (a.real() * a.real() + a.imag() * a.imag());
  return {a.real() * d, -a.imag() * d};
}
inline C div(C a, C b) { return mul(a, inv(b)); }

/// p(z_i) / p'(z_i) for the coefficients c (low to high, c.back() != 0) at
/// L points at once (their Horner chains interleaved: one chain alone waits
/// on its multiply-adds), all with |z_i| <= 1 (Horner's rule on p) or all
/// with |z_i| > 1 (on the reversal r(y) = y^n p(1 / y) at y = 1 / z, where
/// p / p' = z r / (n r - y r')). Each point gets the operations one chain of
/// its own would: the results do not depend on the grouping.
template <int L>
void newton_ratios(const std::vector<double>& c, const C* z, C* out, bool reversed) {
  const std::size_t n = c.size() - 1;
  C x[L], b[L], d[L];
#pragma GCC unroll 4
  for (int i = 0; i < L; ++i) {
    x[i] = reversed ? inv(z[i]) : z[i];
    b[i] = reversed ? c[0] : c[n];
    d[i] = 0;
  }
  if (!reversed) {
    for (std::size_t k = n; k-- > 0;) {
#pragma GCC unroll 4
      for (int i = 0; i < L; ++i) {
        d[i] = mul(d[i], x[i]) + b[i];
        b[i] = mul(b[i], x[i]) + c[k];
      }
    }
#pragma GCC unroll 4
    for (int i = 0; i < L; ++i) out[i] = div(b[i], d[i]);
  } else {  // r's coefficients are c reversed: r_k = c[n - k]
    for (std::size_t k = 1; k <= n; ++k) {
#pragma GCC unroll 4
      for (int i = 0; i < L; ++i) {
        d[i] = mul(d[i], x[i]) + b[i];
        b[i] = mul(b[i], x[i]) + c[k];
      }
    }
#pragma GCC unroll 4
    for (int i = 0; i < L; ++i) out[i] = div(mul(z[i], b[i]), static_cast<double>(n) * b[i] - mul(x[i], d[i]));
  }
}

// Points per newton_ratios call: two chains fill the registers (x, b and d
// of four complex points spill; bez-rat-space d = 12's hints were no
// faster with three or four).
constexpr int kLanes = 2;

/// ratio[k] = p(z_k) / p'(z_k) for every k not done, kLanes points at a time
/// (newton_ratios), the points inside and outside the unit circle apart.
void all_newton_ratios(const std::vector<double>& c, const std::vector<C>& z, const std::vector<char>& done,
                       std::vector<C>& ratio) {
  for (const bool reversed : {false, true}) {
    std::size_t idx[kLanes];
    C pts[kLanes], out[kLanes];
    int m = 0;
    auto flush = [&] {
      if (m == kLanes) newton_ratios<kLanes>(c, pts, out, reversed);
      else
        for (int i = 0; i < m; ++i) newton_ratios<1>(c, pts + i, out + i, reversed);
      for (int i = 0; i < m; ++i) ratio[idx[i]] = out[i];
      m = 0;
    };
    for (std::size_t k = 0; k < z.size(); ++k) {
      if (done[k] || (std::norm(z[k]) > 1) != reversed) continue;  // norm: |z|^2, no hypot
      idx[m] = k;
      pts[m++] = z[k];
      if (m == kLanes) flush();
    }
    flush();
  }
}

/// The Aberth-Ehrlich iteration of approximate_complex_roots. With
/// near_unit, a root is also settled once its correction is below
/// kFarSettled times its distance from [-1, 1] (see
/// approximate_roots_near_unit_interval).
std::vector<C> aberth(const Poly& p, bool* converged, int max_sweeps, bool near_unit) {
  if (converged) *converged = false;
  const long deg = p.degree();
  const fmpz* a = p.get()->coeffs;
  long v = 0;  // roots at 0
  while (fmpz_is_zero(a + v)) ++v;
  std::vector<C> out(static_cast<std::size_t>(v), C(0));
  const long n = deg - v;
  if (n == 0) {
    if (converged) *converged = true;
    return out;
  }
  std::vector<double> c = scaled_doubles(p);
  c.erase(c.begin(), c.begin() + v);  // p / t^v
  if (c[n] == 0 || c[0] == 0) return {};  // a leading or trailing coefficient underflowed
  // Start on the circles of the Newton polygon (Bini's choice): the upper
  // convex hull of the points (k, log2 |c_k|); an edge from i to j holds
  // j - i roots of modulus about (|c_i| / |c_j|)^(1/(j-i)), placed evenly on
  // that circle, turned off the axes. One circle of the geometric mean
  // modulus took ~5 sweeps more on the speeds' polynomials, whose roots
  // spread over several moduli.
  std::vector<C> z(static_cast<std::size_t>(n));
  std::vector<char> done(static_cast<std::size_t>(n), 0);
  {
    std::vector<long> hull;  // indices of the hull's vertices, from 0 to n
    std::vector<double> lg(static_cast<std::size_t>(n + 1));
    for (long k = 0; k <= n; ++k) lg[k] = c[k] == 0 ? -1e300 : std::log2(std::fabs(c[k]));
    for (long k = 0; k <= n; ++k) {
      if (c[k] == 0) continue;
      while (hull.size() >= 2) {  // pop while the last vertex is not above the chord
        const long i = hull[hull.size() - 2], j = hull.back();
        if ((lg[j] - lg[i]) * static_cast<double>(k - i) <= (lg[k] - lg[i]) * static_cast<double>(j - i)) hull.pop_back();
        else break;
      }
      hull.push_back(k);
    }
    long at = 0;
    for (std::size_t h = 0; h + 1 < hull.size(); ++h) {
      const long i = hull[h], j = hull[h + 1], m = j - i;
      const double r = std::exp2((lg[i] - lg[j]) / static_cast<double>(m));
      for (long q = 0; q < m; ++q, ++at)
        z[at] = std::polar(r, 0.4 + 0.7 * static_cast<double>(h) + 2 * kPi * static_cast<double>(q) / static_cast<double>(m));
    }
  }
  bool all = false;
  std::vector<C> ratios(static_cast<std::size_t>(n));
  for (int sweep = 0; sweep < max_sweeps && !all; ++sweep) {
    all = true;
    // z[k] changes only at its own update below (Gauss-Seidel: the others'
    // new values enter its sum), so its ratio can be taken first
    all_newton_ratios(c, z, done, ratios);
    for (long k = 0; k < n; ++k) {
      if (done[k]) continue;
      const C ratio = ratios[k];
      C s = 0;
      for (long j = 0; j < n; ++j)
        if (j != k) s += inv(z[k] - z[j]);
      const C w = div(ratio, 1.0 - mul(ratio, s));
      if (!std::isfinite(w.real()) || !std::isfinite(w.imag())) {
        // p'(z) = 0 or two iterates met: nudge the iterate and go on
        z[k] += C(0x1p-20, 0x1p-21) * std::max(1.0, std::abs(z[k]));
        all = false;
        continue;
      }
      z[k] -= w;
      const double nw = std::norm(w);
      if (nw <= kSettled * kSettled * std::max(std::norm(z[k]), 1.0)) {  // |w| <= kSettled max(|z|, 1)
        done[k] = 1;
      } else if (near_unit) {  // |w| <= kFarSettled |z - [-1, 1]|
        const C gap = z[k] - std::clamp(z[k].real(), -1.0, 1.0);
        if (nw <= kFarSettled * kFarSettled * std::norm(gap)) done[k] = 1;
      }
      if (!done[k]) all = false;
    }
  }
  for (const C& r : z)
    if (!std::isfinite(r.real()) || !std::isfinite(r.imag())) return {};
  if (converged) *converged = all;
  out.insert(out.end(), z.begin(), z.end());
  return out;
}

}  // namespace

double power_basis_loss(const Poly& p) {
  if (p.is_zero()) throw InvalidArgument("power_basis_loss: the zero polynomial");
  return horner_loss_bits(p, 0, 1, 0);
}

std::vector<C> approximate_complex_roots(const Poly& p, bool* converged, int max_sweeps) {
  if (p.is_zero()) throw InvalidArgument("approximate_complex_roots: the zero polynomial has no finite root set");
  return aberth(p, converged, max_sweeps, false);
}

std::vector<C> approximate_roots_near_unit_interval(const Poly& p, double max_loss, double* loss, bool* converged) {
  if (p.is_zero()) throw InvalidArgument("approximate_roots_near_unit_interval: the zero polynomial has no finite root set");
  if (converged) *converged = false;
  const Poly q = centred_at_half(p);  // q(s) = 2^n p((1 + s) / 2)
  const double l = horner_loss_bits(q, -1, 1, 0);
  if (loss) *loss = l;
  if (!(l <= max_loss)) return {};
  std::vector<C> z = aberth(q, converged, 60, true);
  for (C& w : z) w = (1.0 + w) * 0.5;
  return z;
}

}  // namespace uniparam
