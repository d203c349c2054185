// uniparam/reparam/speed.hpp -- the angular and the parametric speed of a
// curve, exactly and as certified ball evaluators (MATH.md section 1).
#pragma once

#include <acb.h>

#include <string>
#include <vector>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/algebra/squarefree.hpp"
#include "uniparam/core/ball_poly.hpp"
#include "uniparam/core/ratfunc.hpp"
#include "uniparam/reparam/curve.hpp"

namespace uniparam {

enum class SpeedKind { Angular, Parametric };
/// "angular" / "parametric".
std::string to_string(SpeedKind k);
/// Parses "angular" / "parametric"; InvalidArgument otherwise.
SpeedKind parse_speed_kind(const std::string& s);

/// A zero of the speed in [0, 1]: sigma(t) ~ c |t - gamma|^multiplicity.
struct SpeedZero {
  RealAlgebraic t;
  int multiplicity;
};

/// The speed sigma of a curve, in the factored form
///
///     sigma(t) = |g(t)| * sqrt(K_1(t)^2 + ... + K_m(t)^2) / |D(t)|
///
/// with g, K_k, D in Z[t], gcd(K_1, ..., K_m) = 1 (so sum K_k^2 > 0 on R) and
/// D != 0 on [0, 1]:
/// * angular:    with p' = X / W and Y = X / gcd(X) (the primitive direction),
///               g K_ij = Y_i' Y_j - Y_i Y_j' (i < j), D = sum Y_i^2 (> 0 on R);
/// * parametric: g K_i = X_i, D = W.
/// The zeros of sigma in [0, 1] are exactly the real roots of g there, with
/// the multiplicities of g. sigma^2 = g^2 sum K^2 / D^2 is also kept exactly.
/// Evaluations use the factors (g's squarefree factors, K_k, Y_i or W), never
/// the expanded sigma^2.
class Speed {
 public:
  /// \throws DomainError if the speed is infinite somewhere in [0, 1]
  ///         (a root of D there), naming the parameter value.
  Speed(const Curve& c, SpeedKind kind);

  SpeedKind kind() const { return kind_; }
  /// sigma^2 as a canonical rational function (exact).
  const RatFunc& squared() const { return squared_; }
  /// True for the angular speed of a straight line (sigma == 0, mu = 0).
  bool identically_zero() const { return zero_; }
  /// The zeros of sigma in [0, 1], sorted increasingly, with multiplicities.
  const std::vector<SpeedZero>& zeros() const { return zeros_; }

  /// g of the factored form (primitive, positive leading coefficient) and its
  /// squarefree factorisation.
  const Poly& g() const { return g_; }
  const SquarefreeFactorization& g_factors() const { return g_sqf_; }

  /// The sign s in {-1, +1} such that sigma = s * g * sqrt(sum K^2) / D on the
  /// open interval (a, b), which must hold no zero of g and of D
  /// (\pre a < b and no zero of sigma in (a, b); checked: DomainError).
  int piece_sign(const RealAlgebraic& a, const RealAlgebraic& b) const;

  /// out = s * g(z) * R(z) with R = sqrt(sum K(z)^2) / D(z): an enclosure of the
  /// analytic continuation of sigma from a piece with sign s. With analytic,
  /// out is indeterminate unless holomorphy on z is certified.
  void eval(acb_t out, const acb_t z, int s, bool analytic, long prec) const;
  /// out = sigma(z)^2 = g^2 sum K^2 / D^2 (analytic wherever D(z) != 0).
  void eval_squared(acb_t out, const acb_t z, long prec) const;
  /// out = R(z) = sqrt(sum K(z)^2) / D(z), the factor that never vanishes on
  /// [0, 1] (sign of D included). Used with deflated g near zeros.
  void eval_cofactor(acb_t out, const acb_t z, bool analytic, long prec) const;
  /// out = g(z), evaluated from its squarefree factors.
  void eval_g(acb_t out, const acb_t z, long prec) const;

 private:
  SpeedKind kind_;
  RatFunc squared_;
  bool zero_ = false;
  std::vector<SpeedZero> zeros_;
  Poly g_;
  SquarefreeFactorization g_sqf_;
  std::vector<Poly> K_;       // cofactors, gcd 1
  Poly D_;                    // exact D (for root checks and sign)
  // ball versions for evaluation
  Integer g_content_;          // g = content * prod h^m; content is 1 here but kept general
  std::vector<BallPoly> g_h_;  // squarefree factors of g
  std::vector<int> g_m_;
  std::vector<BallPoly> K_b_;
  std::vector<BallPoly> Y_b_;  // angular: D = sum Y^2; parametric: empty
  BallPoly W_b_;               // parametric: D = W
};

}  // namespace uniparam
