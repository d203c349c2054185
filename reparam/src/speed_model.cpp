// speed_model.cpp -- the angular and the parametric speed as SpeedModels
// (speed_model.hpp; docs/math.md section 1).
#include "speed_model.hpp"

namespace uniparam {

namespace {

// omega = |x' x''| / |x'|^2: g K_ij = Y_i' Y_j - Y_i Y_j' (i < j), D = sum Y_i^2.
class AngularModel final : public SpeedModel {
 public:
  SpeedKind kind() const override { return SpeedKind::Angular; }
  bool direction_only() const override { return true; }
  std::vector<Poly> numerators(const std::vector<Poly>&, const std::vector<Poly>& Y) const override {
    std::vector<Poly> N;
    for (std::size_t i = 0; i < Y.size(); ++i)
      for (std::size_t j = i + 1; j < Y.size(); ++j) {
        Poly e = Y[i].derivative() * Y[j] - Y[i] * Y[j].derivative();
        if (!e.is_zero()) N.push_back(std::move(e));
      }
    return N;
  }
  Poly denominator(const Curve&, const std::vector<Poly>& Y) const override {
    Poly D(0);
    for (const auto& y : Y) D = D + y * y;
    return D;
  }
  // The Y_i = X_i / gcd(X) are coprime, so they have no common complex zero
  // and D = sum Y_i^2 > 0 on the whole real line.
  bool denominator_may_vanish() const override { return false; }
  std::vector<Poly> denominator_squares(const std::vector<Poly>& Y) const override { return Y; }
  speed_formula::Form form(std::size_t n) const override {
    return n == 2 ? speed_formula::Form::Plane : speed_formula::Form::Space;
  }
};

// |p'| = sqrt(sum X_i^2) / |W|: g K_i = X_i, D = W.
class ParametricModel final : public SpeedModel {
 public:
  SpeedKind kind() const override { return SpeedKind::Parametric; }
  bool direction_only() const override { return false; }
  std::vector<Poly> numerators(const std::vector<Poly>& X, const std::vector<Poly>&) const override {
    std::vector<Poly> N;
    for (const auto& x : X)
      if (!x.is_zero()) N.push_back(x);
    return N;
  }
  Poly denominator(const Curve& c, const std::vector<Poly>&) const override { return c.derivative_denominator(); }
  bool denominator_may_vanish() const override { return true; }
  std::vector<Poly> denominator_squares(const std::vector<Poly>&) const override { return {}; }
  speed_formula::Form form(std::size_t) const override { return speed_formula::Form::Parametric; }
};

}  // namespace

const SpeedModel& speed_model(SpeedKind kind) {
  static const AngularModel angular;
  static const ParametricModel parametric;
  if (kind == SpeedKind::Angular) return angular;
  return parametric;
}

}  // namespace uniparam
