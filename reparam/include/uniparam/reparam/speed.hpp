// uniparam/reparam/speed.hpp -- the angular and the parametric speed of a
// curve, exactly and as certified ball evaluators (docs/math.md section 1).
#pragma once

#include <acb.h>

#include <complex>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/algebra/local_poly.hpp"
#include "uniparam/algebra/squarefree.hpp"
#include "uniparam/core/ball_poly.hpp"
#include "uniparam/core/cdisk.hpp"
#include "uniparam/core/dd_ball.hpp"
#include "uniparam/core/ratfunc.hpp"
#include "uniparam/reparam/curve.hpp"

namespace uniparam {

namespace detail {
struct SpeedDD;  // Speed::eval_dd's double-word components (speed_detail.hpp)
}  // namespace detail
class AcbBox;      // an RAII acb_t (speed_enclosure.hpp)
class CurveModel;  // how the evaluation curve evaluates (curve_model.hpp)
struct SpeedCharts;  // the exact charts of a speed's parts (speed_charts.hpp)
namespace speed_formula {
enum class Form;  // the speed's shape (speed_formula.hpp)
}  // namespace speed_formula

enum class SpeedKind { Angular, Parametric };
/// "angular" / "parametric".
std::string to_string(SpeedKind k);
/// Parses "angular" / "parametric"; InvalidArgument otherwise.
SpeedKind parse_speed_kind(const std::string& s);

/// A zero of the speed in [0, 1]: sigma(t) ~ c |t - gamma|^multiplicity.
struct SpeedZero {
  RealAlgebraic t;
  int multiplicity;
  std::size_t factor = 0;  ///< index in Speed::g_factors().factors of the factor vanishing at t
  std::size_t index = 0;   ///< position in Speed::zeros()
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
///
/// The evaluation curve: the components that the evaluations, the exact
/// signs of piece_signs and component_numerator / component_denominator take
/// are those of the curve itself, except for the angular speed of a curve
/// whose p' numerators X_i share a factor gx of positive degree (a cusp or a
/// higher-order stationary point where gx has a real root). There they are
/// the polynomial curve q with q' = c Y (Y = X / gx, a constant c > 0): omega
/// depends only on the direction of p', so q has the same angular speed with
/// gx cancelled, and no value, sign or zero inside a piece comes from the
/// uncancelled x'y'' - x''y' or |p'|^2 (both vanish at a real root of gx,
/// where omega need not). The parametric speed keeps the curve's own
/// components: there gx divides g, and its real roots are zeros of sigma.
class Speed {
 public:
  /// \throws DomainError if the speed is infinite somewhere in [0, 1]
  ///         (a root of D there), naming the parameter value. Only the
  ///         parametric speed can be: the angular D = sum Y_i^2 has coprime
  ///         Y_i, so it is positive on the whole real line.
  Speed(const Curve& c, SpeedKind kind);

  /// The speed given at construction.
  SpeedKind kind() const { return kind_; }
  /// sigma^2 as a canonical rational function (exact). Computed on the
  /// first call (thread-safe; copies share it).
  const RatFunc& squared() const;
  /// True for the angular speed of a straight line (sigma == 0, mu = 0).
  bool identically_zero() const { return zero_; }
  /// The zeros of sigma in [0, 1], sorted increasingly, with multiplicities.
  const std::vector<SpeedZero>& zeros() const { return zeros_; }

  /// g of the factored form (primitive, positive leading coefficient) and its
  /// squarefree factorisation.
  const Poly& g() const { return g_; }
  const SquarefreeFactorization& g_factors() const { return g_sqf_; }
  /// K_1, ..., K_m and D of the factored form.
  const std::vector<Poly>& cofactors() const { return K_; }
  const Poly& denominator() const { return D_; }
  /// sum K_k^2 (the branch points' polynomial), computed on the first call
  /// (thread-safe; copies share it).
  const Poly& cofactor_square_sum() const;
  /// The local expansions of the evaluation curve's (see above) component i's
  /// numerator and denominator (copies share the caches this speed's
  /// evaluations fill; equal denominators are one). \pre i < component_count() (std::out_of_range otherwise).
  const LocalPoly& component_numerator(std::size_t i) const { return comp_.at(i).N; }
  const LocalPoly& component_denominator(std::size_t i) const { return comp_.at(i).Q; }
  std::size_t component_count() const { return comp_.size(); }

  /// Signs that fix sigma's analytic continuation on one piece (a, b) free of
  /// zeros of sigma, taken exactly at one rational point inside from g, D and
  /// (plane angular) the evaluation curve's x'y'' - x''y', which vanish on
  /// [0, 1] only at zeros of sigma: so they are the same on every (a, b)
  /// inside one interval between consecutive zeros (or 0, 1), and are
  /// computed once per such interval and remembered (thread-safe; copies
  /// share them).
  /// \pre 0 <= a < b <= 1; a < b checked (DomainError); (a, b) holds no
  ///      zero of sigma (checked: DomainError).
  struct PieceSigns {
    int g = 1;          ///< sigma = g_sign * g * sqrt(sum K^2) / D on (a, b)
    int component = 1;  ///< plane angular: sigma = component * (x'y'' - x''y') / (x'^2 + y'^2),
                        ///< x, y the evaluation curve's components
  };
  PieceSigns piece_signs(const RealAlgebraic& a, const RealAlgebraic& b) const;

  /// out = an enclosure of the analytic continuation of sigma from a piece
  /// with signs `p`, at every point of the complex ball z. Evaluated from the
  /// components x_i = N_i / Q_i and their derivatives (low degree, small
  /// coefficients); where that cannot certify analyticity (the square root
  /// near a zero of sigma), from the factored form g * R. With analytic, out
  /// is indeterminate unless holomorphy on z is certified. double_word =
  /// false skips the double-word attempt on narrow real balls
  /// (eval_double_word): for the Integrand behind a
  /// QuadratureOptions::node_fast, which the quadrature asks first at every
  /// such point (so the Integrand gets only the points it refused).
  void eval(acb_t out, const acb_t z, const PieceSigns& p, bool analytic, long prec, bool double_word = true) const;
  /// out = sigma(z)^2 (a rational function of the components' derivatives:
  /// analytic wherever the curve has no pole and, for the angular speed,
  /// p'(z) . p'(z) != 0).
  /// double_word as in eval.
  void eval_squared(acb_t out, const acb_t z, long prec, bool double_word = true) const;
  /// A ball containing sigma(t) for every t in the real ball t (in [0, 1]
  /// or wherever sigma^2 is defined): the square root of eval_squared's
  /// real part, its part below 0 cut off (sigma^2 >= 0). Indeterminate
  /// (not finite) where eval_squared is, e.g. at a pole; never throws.
  Ball eval_real(const Ball& t, long prec) const;
  /// UNCERTIFIED: sigma(t)^2 in IEEE double from the evaluation curve's
  /// components' local expansions (LocalPoly::eval_double). For
  /// floating-point search only (the optimiser's breakpoints); NaN or inf
  /// where the evaluation curve's q'(t) = 0 (the parametric speed's zeros,
  /// never at a cusp of the angular speed: see the evaluation curve above).
  double squared_double(double t) const;
  /// out = sigma(z)^2 / (side * (z - gamma))^power for a zero (gamma, mu) of
  /// sigma and 0 <= power <= 2 mu; side = +1 when the zero is the left end of
  /// the piece (z > gamma), -1 when it is the right end. The removable
  /// singularity is removed exactly (docs/math.md section 4): g = c h^mu g_1 with
  /// h(t) = (t - gamma) h_gamma(t), h_gamma deflated in local Taylor bases
  /// (LocalPoly::eval_deflated: no division by t - gamma), so
  ///     out = (side (z - gamma))^(2 mu - power) h_gamma(z)^(2 mu) c^2 g_1(z)^2 sum K^2 / D^2,
  /// analytic on the piece; no numerical cancellation near gamma.
  /// double_word as in eval (the far branch's eval_squared).
  void eval_squared_over_zero(acb_t out, const acb_t z, const SpeedZero& zero, int side, int power, long prec,
                              bool double_word = true) const;
  /// v = P(z) and, when d is non-null, d = P'(z) for the critical numerator
  ///     P = 2 g' Q D + g Q' D - 2 g Q D',  Q = sum K_k^2,
  /// so that (sigma^2)' = g P / D^3: its roots are the critical points of
  /// sigma that are not zeros. From the local expansions of g, K_k and Y_i
  /// (or W), never from P's power basis (degree ~12d for a space curve's
  /// angular speed, with huge coefficients). P is 0 for a straight line's
  /// angular speed.
  /// \post v (and d) contain P(t) (P'(t)) for every t in z; may be wide or
  ///       infinite, never wrong.
  void eval_critical(acb_t v, acb_t d, const acb_t z, long prec) const;
  /// The double-word path that eval (squared = false, with signs p) and
  /// eval_squared (squared = true; p unused) take first on the quadrature's
  /// nodes: the components over their common denominator, x_i = M_i / L,
  /// and their derivatives by Horner's rule in double-word ball arithmetic
  /// (core/dd_ball.hpp, inlined from core/dd_inline.hpp), ~100 bits,
  /// several times cheaper than Arb's balls at low degree; L cancels from
  /// the angular speed (speed_dd.cpp; the arithmetic of speed_formula.hpp).
  /// \return true and out = a real ball that contains sigma(t) (sigma(t)^2)
  ///         for every t in z, with a relative radius of at most
  ///         2^-(prec - kNodeFastSlackBits) (quadrature.hpp's
  ///         NodeIntegrand contract: rel_goal + 4 bits at the start
  ///         precision rel_goal + 32); false, out untouched, when the path does not apply (z
  ///         not a real ball of radius < 2^-30; prec > 110; more than 3
  ///         components; M_i or L not double words, of degree above 64, or
  ///         losing more than 24 bits in Horner's rule on [0, 1]) or cannot
  ///         reach that accuracy at this point.
  bool eval_double_word(acb_t out, const acb_t z, const PieceSigns& p, bool squared, long prec) const;
  /// eval_double_word on a double-word ball x (radius < 2^-30): the same
  /// path, guarantees and refusals, without Arb balls at either end (the
  /// quadrature's NodeIntegrand). \return false, out unspecified, where
  /// eval_double_word would.
  bool eval_dd(DDBall& out, const DDBall& x, const PieceSigns& p, bool squared, long prec) const;
  /// UNCERTIFIED approximations (approximate_roots_near_unit_interval) of
  /// the complex points where sigma (squared = false) or sigma^2 (squared =
  /// true) is not analytic: the zeros of D (poles) and, for sigma with a
  /// square root (space curves' angular speed, the parametric speed), of
  /// sum K^2 (branch points). For QuadratureOptions::singularity_hints only.
  /// Computed on the first call (thread-safe; copies share them; the two
  /// root sets on up to two workers); empty when D or sum K^2 has degree
  /// above 128 (the hints would cost more than they save), when neither
  /// its power basis nor the one centred at 1/2 loses at most 30 bits near
  /// [0, 1] (the hints would mislead: sigma's are then empty, sigma^2's may
  /// hold the poles) or the approximation failed.
  const std::vector<std::complex<double>>& singularity_hints(bool squared) const;
  /// A certified d >= 0 such that every nonzero complex root of g, of D and
  /// of sum K_k^2 (sigma's zeros, poles and branch points) lies at least
  /// 2^-d from 0 and from 1 (root_depth_bits, algebra/newton_polygon.hpp,
  /// of each polynomial and of its Taylor shift to 1; roots at 0 or 1
  /// themselves are not counted): sigma varies on no finer scale than about
  /// 2^-d next to an end. Computed on the first call (thread-safe; copies
  /// share it); 0 for an identically zero speed.
  long scale_bits() const;

  /// Where sigma has narrow features inside (0, 1) (peak_split in
  /// scaling.hpp: a peak of width 1/(2C) at 1/2 in the angular speed of
  /// (t, C (t - 1/2)^2) for a huge C): the parts of [0, 1] between the split's
  /// knots, each with the exact affine chart t = k0 + (k1 - k0) u of its
  /// restriction, run from its feature's end, and that curve's speed
  /// (speed_charts.hpp, internal). The integrals of sigma and of sigma^2
  /// times a weight are taken part by part in the charts: the power basis of
  /// an affine chart is p's Taylor expansion about the feature, accurate at
  /// every distance from it inside the part, so the cost does not depend on
  /// the feature's widths, also where it has several (the bump
  /// (t, 1/(1 + C (t - c)^2)) has structure at 1/C, 1/sqrt(C) and C^(-1/3)).
  /// Null where the speed has no such features (every curve below
  /// peak_split's coefficient size, at once).
  /// The split is found on the first call (thread-safe; copies share it);
  /// each copy of the speed makes its own copies of the parts' speeds on its
  /// first call, so copies may be used on different threads as before.
  /// The charts' own speeds have no charts.
  /// \throws BudgetExceeded from the root isolation's budgets only.
  const SpeedCharts* charts() const;
  /// The same parts, each chart balanced where balance() does (t = k0 +
  /// (k1 - k0) m(u), m the balancing map of scaling.hpp), so that the
  /// feature is spread over u in [0, 1]: for locating points (locate,
  /// exact samples), where the cumulative integral must vary evenly in u.
  /// A part whose feature has several scales is cut into a ladder of
  /// smaller parts first, each zooming by about 2^16. Null exactly where
  /// charts() is; the same contract otherwise.
  const SpeedCharts* balanced_charts() const;

 private:
  // piece_signs() at one rational point inside (a, b), not remembered.
  PieceSigns piece_signs_at(const RealAlgebraic& a, const RealAlgebraic& b) const;
  SpeedKind kind_;
  struct Lazy {
    std::once_flag once;
    RatFunc squared;
    std::once_flag sumK2_once;
    Poly sumK2;
    std::once_flag hints_once;
    std::vector<std::complex<double>> hints_sigma, hints_squared;
    std::once_flag scale_once;
    long scale_bits = 0;
    // the curve, kept where peak_split searches it; the charts' prototypes
    std::shared_ptr<const Curve> curve;
    std::once_flag charts_once, balanced_once;
    std::shared_ptr<const SpeedCharts> charts, balanced;
    std::mutex signs_mutex;  // guards signs
    // piece_signs() of the interval between zeros i - 1 and i, once known
    std::vector<std::pair<bool, PieceSigns>> signs;
  };
  std::shared_ptr<Lazy> lazy_;  // squared(), shared by copies
  // This object's own copy of the charts' prototypes (their speeds are used
  // by one thread at a time, as this one): a copy of the Speed starts empty.
  struct OwnCharts {
    OwnCharts() = default;
    OwnCharts(const OwnCharts&) noexcept {}
    OwnCharts& operator=(const OwnCharts&) noexcept {
      charts.reset();
      balanced.reset();
      return *this;
    }
    std::shared_ptr<const SpeedCharts> charts, balanced;
  };
  mutable OwnCharts own_charts_;
  friend struct SpeedCharts;
  bool zero_ = false;
  std::vector<SpeedZero> zeros_;
  Poly g_;
  SquarefreeFactorization g_sqf_;
  std::vector<Poly> K_;       // cofactors, gcd 1
  Poly D_;                    // exact D (for root checks and sign)
  void eval_sumK2_over_D2(AcbBox& out, const acb_t z, long prec) const;
  void eval_sumK2(AcbBox& out, const acb_t z, long prec) const;  // sum K_k(z)^2
  void eval_D(AcbBox& out, const acb_t z, long prec) const;      // D(z), from Y_i or W
  // g(z) from its squarefree factors (leaving out factor `skip`, if given)
  void eval_g(AcbBox& out, const acb_t z, long prec, std::size_t skip = static_cast<std::size_t>(-1)) const;
  // Parametric, Plane (angular, 2 components) or Space (speed_formula.hpp)
  speed_formula::Form form() const;
  // sigma = s g R (the sign s from p); false (out not finite) where D's
  // enclosure holds 0 or the square root is not certified analytic
  bool eval_factored(acb_t out, const acb_t z, const PieceSigns& p, bool analytic, long prec) const;
  // Wide balls (the quadrature's ellipses and segments) in complex discs
  // in double (core/cdisk.hpp), each polynomial's disc from
  // LocalPoly::eval_disk. Ok: out holds the value on z. Refused: a disc
  // that has every factor's centred form in double holds a pole or (for a
  // root) meets the branch cut: Arb's balls, holding the same enclosures,
  // would fail too, so the caller answers "not finite". Unknown (out
  // untouched): anything else (a factor without the centred form in double,
  // magnitudes out of the discs' range): the caller tries Arb's balls.
  enum class DiskResult { Ok, Refused, Unknown };
  // eval_factored (analytic) in discs: g sqrt(sum K^2) / D
  DiskResult eval_factored_disk(acb_t out, const acb_t z, const PieceSigns& p, long prec) const;
  // the factored form's parts: g, sum K^2 (a single cofactor: K itself), D
  // (Refused or Unknown where 1 / D is not finite)
  DiskResult factored_disks(CDisk& g, CDisk& q, CDisk& d, const acb_t z, long prec) const;
  // eval_components' S and F in discs; false for components that are not
  // all polynomials or (angular speed) over one common denominator, that
  // lack their centred forms in double (their discs would only be Arb's
  // boxes, wider), or where a disc is not finite
  bool components_disk(CDisk& S, CDisk& F, const acb_t z, long prec) const;
  // sigma (analytic: principal roots) and sigma^2 in discs, from the
  // components, else the factored form (where disk_form_)
  DiskResult eval_disk(acb_t out, const acb_t z, const PieceSigns& p, long prec) const;
  DiskResult eval_squared_disk(acb_t out, const acb_t z, long prec) const;
  // x_i'(z) (and x_i''(z) when d2 is non-null) from the components
  void eval_derivatives(AcbBox* d1, AcbBox* d2, const acb_t z, long prec) const;
  // sum x_i'^2 and, for the angular speed, F = sum_{i<j} (x_i' x_j'' - x_i'' x_j')^2
  // (plane: F is returned unsquared as E = x_1' x_2'' - x_1'' x_2'); for the
  // angular speed of a curve with one denominator Q, both times Q^4 and Q^8
  // (E times Q^4), without dividing by Q: the ratios sigma is made of are
  // the same
  void eval_components(AcbBox& S, AcbBox& F, const acb_t z, long prec) const;
  struct Component {
    LocalPoly N, Q;                 // numerator, denominator (with p', p'')
    RatFunc d1, d2;                 // exact x', x'' (plane angular only: for signs)
    bool unit_den = false;          // Q == 1: x' = N', x'' = N'' (no quotient rule)
    std::size_t q_index = 0;        // first component with this Q (evaluated once per ball)
  };
  std::vector<Component> comp_;
  // eval_dd's components (speed_dd.cpp), shared by copies; null where that
  // path does not apply to this curve
  std::shared_ptr<const detail::SpeedDD> dd_;
  // ball versions for evaluation
  LocalPoly g_b_;               // g itself (eval_critical: g, g', g'')
  Integer g_content_;          // g = content * prod h^m; content is 1 here but kept general
  std::vector<LocalPoly> g_h_;  // squarefree factors of g
  std::vector<int> g_m_;
  std::vector<LocalPoly> K_b_;
  std::vector<LocalPoly> Y_b_;  // D = sum Y^2 (SpeedModel::denominator_squares; angular)
  LocalPoly W_b_;               // D itself where Y_b_ is empty (parametric: D = W)
  bool disk_form_ = false;      // every factor of eval_factored has LocalPoly::has_disk_form
  // the evaluation curve's components for the evaluation tiers (the
  // Bernstein basis for a Bezier curve's own components, else comp_'s
  // power basis); shared by copies
  std::shared_ptr<const CurveModel> model_;
};

}  // namespace uniparam
