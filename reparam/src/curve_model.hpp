// curve_model.hpp -- the plug point through which the speed tiers evaluate
// a curve (internal to uniparam_reparam): how the components x_i = N_i / Q_i
// and their first two derivatives evaluate on each enclosure type. Models:
// the power basis (LocalPoly's local expansions, any rational curve) and
// the Bernstein basis (a (rational) Bezier curve's control points and
// weights, by de Casteljau's algorithm). A new curve form is one more model.
#pragma once

#include <acb.h>

#include <cstddef>
#include <memory>
#include <vector>

#include "uniparam/algebra/local_poly.hpp"
#include "uniparam/core/cdisk.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/reparam/curve.hpp"

namespace uniparam {

/// A curve's components x_i = N_i / Q_i, i < size(), for evaluation.
/// Every evaluation obeys the ball rule: each output encloses the exact
/// value (N_i(t), N_i'(t), N_i''(t); Q_i's) for every t in the ball z; it
/// may be wide or not finite, never wrong. Outputs d1, d2 are nullable
/// (not computed). The double evaluations are UNCERTIFIED (floating-point
/// search only). Thread-safe (const).
class CurveModel {
 public:
  virtual ~CurveModel() = default;
  virtual std::size_t size() const = 0;
  /// Q_i == 1 exactly: x_i' = N_i', x_i'' = N_i''.
  virtual bool unit_den(std::size_t i) const = 0;
  /// The first component whose Q equals Q_i (equal denominators are
  /// evaluated once per ball). \pre i < size().
  virtual std::size_t den_index(std::size_t i) const = 0;
  virtual void eval_num(std::size_t i, acb_ptr v, acb_ptr d1, acb_ptr d2, const acb_t z, long prec) const = 0;
  virtual void eval_den(std::size_t i, acb_ptr v, acb_ptr d1, acb_ptr d2, const acb_t z, long prec) const = 0;
  /// Whether the disc evaluations below are offered: discs in double no
  /// wider than Arb's boxes would be (else the disc tier is skipped).
  virtual bool has_disks() const = 0;
  /// \pre has_disks(). v nullable too.
  virtual void eval_num_disks(std::size_t i, CDisk* v, CDisk* d1, CDisk* d2, const acb_t z, long prec) const = 0;
  virtual void eval_den_disks(std::size_t i, CDisk* v, CDisk* d1, CDisk* d2, const acb_t z, long prec) const = 0;
  virtual void eval_num_double(std::size_t i, double t, double* v, double* d1, double* d2) const = 0;
  virtual void eval_den_double(std::size_t i, double t, double* v, double* d1, double* d2) const = 0;
};

/// One component of the power-basis model: N, Q as local expansions
/// (LocalPoly; copies share their caches), unit_den iff Q == 1, q_index the
/// first component with this Q (whose LocalPoly Q is then a copy).
struct PowerComponent {
  LocalPoly N, Q;
  bool unit_den = false;
  std::size_t q_index = 0;
};

/// The power basis, from the components' canonical numerators and
/// denominators. \pre comps non-empty, q_index <= own index.
std::shared_ptr<const CurveModel> power_curve_model(std::vector<PowerComponent> comps);

/// The Bernstein basis of degree n: N_i = sum_k num[i][k] B_k^n(t), one Q =
/// sum_k den[k] B_k^n(t) for every component (not unit_den). Evaluated from
/// the coefficients (and their differences for the derivatives) by Horner's
/// rule in t / (1 - t) or (1 - t) / t, O(n); on a wide ball (is_wide_ball)
/// in the mean-value form p(m) + (z - m) p'(z) about the midpoint m, p' on
/// the ball by de Casteljau's algorithm where Horner's divisor holds 0. \pre every row of num and den
/// of one length n + 1 >= 2.
std::shared_ptr<const CurveModel> bernstein_curve_model(const BernsteinForm& b);

/// The highest degree of a Bezier curve that Speed evaluates in the Bernstein
/// basis (bernstein_curve_model); higher degrees take the power basis's local
/// expansions (power_curve_model), whose exact Taylor shifts give the same
/// cells whatever basis the curve came in, and whose truncated cells cost
/// O(K) per narrow ball (K ~ 30-55 terms on the narrow cells at degree
/// 50-150) where the Bernstein sum costs O(n) (docs/stable-evaluation.md,
/// "Bezier input: the Bernstein basis", has the measurements).
constexpr long kBernsteinMaxDegree = 16;

/// Whether Speed evaluates a Bezier curve with Bernstein form b in the
/// Bernstein basis: its degree is at most kBernsteinMaxDegree (and b has
/// coefficients). \pre every row of b of one length.
bool bernstein_model_serves(const BernsteinForm& b);

}  // namespace uniparam
