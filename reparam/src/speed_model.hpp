// speed_model.hpp -- the plug point for a kind of speed (internal to
// uniparam_reparam): what Speed's construction and the evaluation tiers
// need to know of the angular or the parametric speed. A new speed is one
// more model (speed_model.cpp) and, if its shape is new, one more
// speed_formula::Form.
#pragma once

#include <cstddef>
#include <vector>

#include "speed_formula.hpp"
#include "uniparam/core/poly.hpp"
#include "uniparam/reparam/curve.hpp"
#include "uniparam/reparam/speed.hpp"

namespace uniparam {

/// A speed sigma = |g| sqrt(sum K_k^2) / |D| (speed.hpp's factored form),
/// described from the curve's derivative p' = X / W and its primitive
/// direction Y = X / gcd(X).
class SpeedModel {
 public:
  virtual ~SpeedModel() = default;
  virtual SpeedKind kind() const = 0;
  /// sigma depends on the direction of p' only (then Y is asked for, and
  /// the evaluation curve may be the direction curve: speed.hpp).
  virtual bool direction_only() const = 0;
  /// The products g K_k (the zero ones left out; none for a speed that
  /// vanishes identically). Y is empty unless direction_only().
  virtual std::vector<Poly> numerators(const std::vector<Poly>& X, const std::vector<Poly>& Y) const = 0;
  /// D, exactly.
  virtual Poly denominator(const Curve& c, const std::vector<Poly>& Y) const = 0;
  /// Whether D may vanish on [0, 1] (Speed's construction checks it).
  virtual bool denominator_may_vanish() const = 0;
  /// The polynomials whose squares sum to D (the evaluations take D from
  /// them), or empty where D is evaluated itself.
  virtual std::vector<Poly> denominator_squares(const std::vector<Poly>& Y) const = 0;
  /// The formula's shape for an evaluation curve of n components.
  virtual speed_formula::Form form(std::size_t n) const = 0;
};

/// The model of a speed kind (static, thread-safe).
const SpeedModel& speed_model(SpeedKind kind);

}  // namespace uniparam
