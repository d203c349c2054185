// speed_formula.hpp -- the speed's arithmetic, written once for every
// enclosure type (docs/math.md section 1; internal to uniparam_reparam).
//
// A curve's components x_i = N_i / Q (one denominator Q; Q = 1 for a
// polynomial curve) give
//     A_i = N_i' Q - N_i Q',   B_i = A_i' = N_i'' Q - N_i Q'',
//     x_i' = A_i / Q^2,        x_i' x_j'' - x_i'' x_j' = C_ij / Q^4,
//     S = sum A_i^2,           C_ij = A_i B_j - A_j B_i,
// so the angular speed is sqrt(sum_{i<j} C_ij^2) / S (a plane curve's:
// C_12 / S, times the piece's sign) and the parametric one sqrt(S) / Q^2.
// The factored form (speed.hpp) is sigma = s g sqrt(sum K_k^2) / D.
//
// Every function below is a template over an enclosure arithmetic Ar
// (speed_enclosure.hpp: double-word balls, complex discs in double, Arb's
// complex balls at one precision), which provides
//     using T = ...;                     the enclosure (default-constructible, copyable)
//     zero(r)                            r = 0 exactly
//     mul(r, a, b), sub(r, a, b), neg(r, a), mul_2exp(r, a, e)
//     addmul(r, a, b), submul(r, a, b)   r += a b, r -= a b
//     inv(r, a), div(r, a, b)            not finite where the divisor's enclosure holds 0
//     sqrt(r, a)                         the arithmetic's square root (analytic
//                                        principal branch, or of a non-negative real)
//     mul_pow(r, h, m)                   r *= h^m (m >= 1)
//     finite(a)                          a certainly finite ("unknown" otherwise)
// with the ball rule: each result encloses the exact result for every choice
// of exact values in the operands' enclosures (or is not finite). Arguments
// may alias. The enclosures here therefore hold the exact A_i, S, C_ij,
// sigma, sigma^2 for every point of the evaluation ball.
#pragma once

#include <cstddef>
#include <type_traits>

namespace uniparam {
namespace speed_formula {

/// The three shapes of the speed: parametric |p'|, a plane curve's angular
/// speed (no square root: C_12 / S), a space curve's angular speed.
enum class Form { Parametric, Plane, Space };

/// A = N' Q - N Q' and, when B is non-null, B = N'' Q - N Q''.
template <class Ar, class T = typename Ar::T>
inline void scaled_derivatives(Ar& ar, T& A, T* B, const T& n, const T& n1, const T* n2, const T& q, const T& q1,
                               const T* q2) {
  ar.mul(A, n1, q);
  ar.submul(A, n, q1);
  if (B) {
    ar.mul(*B, *n2, q);
    ar.submul(*B, n, *q2);
  }
}

/// The quotient rule from A and B (clobbered): with v = 1 / Q and w = v^2,
/// d1 = x' = A w and, when d2 is non-null, d2 = x'' = B w - 2 Q' A w v.
template <class Ar, class T = typename Ar::T>
inline void quotient_derivatives(Ar& ar, T& d1, T* d2, T& A, T* B, const T& q1, const T& v, const T& w) {
  ar.mul(d1, A, w);
  if (d2) {
    ar.mul(*B, *B, w);
    ar.mul(A, A, q1);
    ar.mul(A, A, w);
    ar.mul(A, A, v);
    ar.mul_2exp(A, A, 1);
    ar.sub(*d2, *B, A);
  }
}

/// S = sum_{i < n} x_i^2 (0 for n = 0), x(i) giving x_i (a const T&).
template <class Ar, class X, class T = typename Ar::T>
inline void sum_of_squares(Ar& ar, T& S, std::size_t n, X&& x) {
  ar.zero(S);
  for (std::size_t i = 0; i < n; ++i) {
    const T& v = x(i);
    ar.addmul(S, v, v);
  }
}

/// C_ij = a_i b_j - b_i a_j; F = C_12 for n = 2 (Form::Plane), else
/// F = sum_{i<j} C_ij^2 (Form::Space).
template <class Ar, class T = typename Ar::T>
inline void cross_terms(Ar& ar, T& F, const T* a, const T* b, std::size_t n) {
  T e;
  ar.zero(F);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      ar.mul(e, a[i], b[j]);
      ar.submul(e, b[i], a[j]);
      if (n == 2) F = e;
      else ar.addmul(F, e, e);
    }
}

/// sigma from S and F (cross_terms): Parametric sqrt(S) / L2, Plane
/// sign F / S, Space sqrt(F) / S. L2 (nullable) is Q^2 where S was formed
/// from A_i (scaled_derivatives) of a rational curve's parametric speed;
/// null where S is sum x_i'^2 itself or Q = 1. F may be clobbered.
template <class Ar, class T = typename Ar::T>
inline void speed_value(Ar& ar, T& r, const T& S, T& F, Form form, int sign, const typename std::remove_const_t<Ar>::T* L2) {
  switch (form) {
    case Form::Parametric:
      ar.sqrt(r, S);
      if (L2) ar.div(r, r, *L2);
      return;
    case Form::Plane:
      ar.div(r, F, S);
      if (sign < 0) ar.neg(r, r);
      return;
    case Form::Space:
      ar.sqrt(F, F);
      ar.div(r, F, S);
      return;
  }
}

/// sigma^2 from S and F, as speed_value: Parametric S / L2^2, Plane
/// (F / S)^2, Space F / S^2.
template <class Ar, class T = typename Ar::T>
inline void speed_squared(Ar& ar, T& r, const T& S, const T& F, Form form, const typename std::remove_const_t<Ar>::T* L2) {
  switch (form) {
    case Form::Parametric:
      if (!L2) {
        r = S;
        return;
      }
      {
        T l4;
        ar.mul(l4, *L2, *L2);
        ar.div(r, S, l4);
      }
      return;
    case Form::Plane:
      ar.div(r, F, S);
      ar.mul(r, r, r);
      return;
    case Form::Space: {
      T s2;
      ar.mul(s2, S, S);
      ar.div(r, F, s2);
      return;
    }
  }
}

/// g = content * prod_{i != skip} h_i^{m_i}, with h(i, out) evaluating
/// factor i and m(i) its multiplicity, for i < count.
template <class Ar, class H, class M, class T = typename Ar::T>
inline void factored_g(Ar& ar, T& g, const T& content, std::size_t count, H&& h, M&& m, std::size_t skip) {
  T v;
  g = content;
  for (std::size_t i = 0; i < count; ++i) {
    if (i == skip) continue;
    h(i, v);
    ar.mul_pow(g, v, m(i));
  }
}

/// The factored form sigma = sign * s / D * g, with s = sqrt(sum K^2) (or
/// |K| for one constant cofactor); g(out) evaluates g, asked only where
/// s / D is finite (r is left not finite otherwise).
template <class Ar, class G, class T = typename Ar::T>
inline void factored_value(Ar& ar, T& r, const T& s, const T& D, G&& g, int sign) {
  ar.div(r, s, D);
  if (!ar.finite(r)) return;
  T gv;
  g(gv);
  ar.mul(r, r, gv);
  if (sign < 0) ar.neg(r, r);
}

/// sum K^2 / D^2 (from sq = sum K^2).
template <class Ar, class T = typename Ar::T>
inline void factored_ratio_squared(Ar& ar, T& r, const T& sq, const T& D) {
  ar.div(r, sq, D);
  ar.div(r, r, D);
}

/// The factored form squared: sigma^2 = (sum K^2 / D^2) g g, from
/// ratio = factored_ratio_squared.
template <class Ar, class T = typename Ar::T>
inline void factored_squared(Ar& ar, T& r, const T& ratio, const T& g) {
  ar.mul(r, ratio, g);
  ar.mul(r, r, g);
}

}  // namespace speed_formula
}  // namespace uniparam
