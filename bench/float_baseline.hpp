// bench/float_baseline.hpp -- UNCERTIFIED double-precision baseline.
//
// *** Nothing here is certified. *** This is "what a user would write
// instead" of uniparam: the same pipeline (uniformity, piecewise radical,
// C0 piecewise Moebius) in IEEE double precision, with
// * the curve's exact power-basis coefficients rounded to double and the
//   speed evaluated by Horner from the components (x_i', x_i''), as the
//   certified code does in ball arithmetic;
// * zeros and critical points of the speed by a standard numerical method:
//   sign changes on a uniform grid (8 d + 64 points) refined by bisection to
//   full double precision; derivatives by forward-mode dual numbers; the
//   multiplicity of a zero estimated from the speed's growth next to it;
// * adaptive Gauss-Kronrod G7/K15 quadrature with QUADPACK's error estimate
//   (relative tolerance 1e-13, at most 4000 subintervals);
// * the radical pieces' integrands sigma^2 / t~^mu evaluated naively (the
//   instability of Hong, Wang, Yang 2023, section 5), since the zero is only known to
//   double precision;
// * the breakpoints of `reparam --pieces N` chosen by the library's own
//   floating-point search (optimise_breakpoints, uniparam/reparam/
//   breakpoints.hpp) fed with this file's quadrature and speed, so that both
//   sides run the same optimiser and differ only in evaluation and
//   certification.
// Every result carries `converged`: false when the quadrature hit its
// interval limit. A converged result can still be wrong: the benchmark
// measures its correct digits against the certified balls.
// The library never links this file: it lives in bench/ only.
#pragma once

#include <vector>

#include "uniparam/core/ball.hpp"
#include "uniparam/reparam/breakpoints.hpp"
#include "uniparam/reparam/curve.hpp"
#include "uniparam/reparam/speed.hpp"

namespace uniparam::fp {

/// The curve's components num_i / den_i with coefficients rounded to double
/// (low to high degree), and their first two derivatives.
struct FloatCurve {
  struct Component {
    std::vector<double> N, N1, N2, Q, Q1, Q2;
  };
  std::vector<Component> comp;
  long degree = 0;
};

/// Rounds the exact coefficients to double (the only input the baseline sees).
FloatCurve to_float(const Curve& c);

/// sigma(t) and sigma(t)^2 in double (UNCERTIFIED).
double speed(const FloatCurve& c, SpeedKind kind, double t);
double speed_squared(const FloatCurve& c, SpeedKind kind, double t);

struct Uniformity {
  double mu = 0, mean_square = 0, u = 0;
  bool converged = true;
};
/// mu = int sigma, int sigma^2 and u by adaptive G7/K15 on [0, 1] (UNCERTIFIED).
Uniformity uniformity(const FloatCurve& c, SpeedKind kind);

struct Piece {
  double A = 0, B = 0, C = 0, L = 0, M = 0, alpha = 0;
};

struct Radical {
  std::vector<double> T;  ///< breakpoints found numerically
  std::vector<int> mult;  ///< estimated multiplicity of the speed's zero (0: none)
  std::vector<Piece> pieces;
  std::vector<double> S, Z;
  double mu = 0, u_before = 0, u_radical = 0, u_after = 0;
  bool converged = true;
};
/// Algorithm 1 of Hong, Wang, Yang 2023 in double (UNCERTIFIED).
Radical radical(const FloatCurve& c, SpeedKind kind);

struct Moebius {
  std::vector<double> T, S, alpha;
  std::vector<Piece> pieces;
  double mu = 0, u_before = 0, u_after = 0;
  long iterations = 0;  ///< reparam_c0: the breakpoint search's accepted steps
  bool converged = true;
};
/// C0 piecewise Moebius on the given breakpoints (UNCERTIFIED).
Moebius moebius_c0(const FloatCurve& c, SpeedKind kind, const std::vector<double>& T);
/// N pieces, the breakpoints chosen by the library's optimise_breakpoints (the
/// search uniparam::reparam_c0 runs) on this baseline's double quadrature of
/// A, B, C and its double sigma^2, then moebius_c0 on them (UNCERTIFIED).
/// `converged` is false when any quadrature of the search or of the final
/// pieces hit its interval limit.
Moebius reparam_c0(const FloatCurve& c, SpeedKind kind, int N);

/// Correct decimal digits (0 to 17) of the double x measured against the
/// certified ball ref: -log10(|x - mid| / |mid| + rad / |mid|).
double correct_digits(double x, const Ball& ref);

/// Adaptive G7/K15 of a scalar function on [a, b] (exposed for the self-test).
double integrate(double (*f)(double, const void*), const void* ctx, double a, double b, bool* converged);

}  // namespace uniparam::fp
