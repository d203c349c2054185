// The speed formula (reparam/src/speed_formula.hpp) on each enclosure
// arithmetic (Arb's balls, complex discs, double-word balls) against an
// exact rational evaluation at random rational data: every result must
// enclose the exact value, and be tight.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#define UNIPARAM_SPEED_DD_ARITH
#include "../../reparam/src/speed_enclosure.hpp"
#include "../../reparam/src/speed_formula.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"

using namespace uniparam;
using speed_formula::Form;

namespace {

// One component's N, N', N'' and the common Q, Q', Q'' at a point, exactly.
struct Data {
  std::vector<Rational> n, n1, n2;
  Rational q, q1, q2;
};

Rational formula_rational(std::mt19937& rng, bool dyadic) {
  std::uniform_int_distribution<long> num(-40, 40), den(1, 9), exp(0, 4);
  if (dyadic) return Rational(num(rng), 1L << exp(rng));
  return Rational(num(rng), den(rng));
}

Data formula_data(std::mt19937& rng, std::size_t n, bool dyadic) {
  Data d;
  for (std::size_t i = 0; i < n; ++i) {
    d.n.push_back(formula_rational(rng, dyadic));
    d.n1.push_back(formula_rational(rng, dyadic));
    d.n2.push_back(formula_rational(rng, dyadic));
  }
  do d.q = formula_rational(rng, dyadic);
  while (d.q == Rational(0));
  d.q1 = formula_rational(rng, dyadic);
  d.q2 = formula_rational(rng, dyadic);
  return d;
}

// The exact A_i, B_i, S, F (plane: C_12; space: sum C_ij^2).
struct Exact {
  std::vector<Rational> A, B;
  Rational S, F;
};

Exact exact_parts(const Data& d) {
  Exact e;
  const std::size_t n = d.n.size();
  for (std::size_t i = 0; i < n; ++i) {
    e.A.push_back(d.n1[i] * d.q - d.n[i] * d.q1);
    e.B.push_back(d.n2[i] * d.q - d.n[i] * d.q2);
  }
  e.S = Rational(0);
  for (const auto& a : e.A) e.S = e.S + a * a;
  e.F = Rational(0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const Rational c = e.A[i] * e.B[j] - e.B[i] * e.A[j];
      e.F = n == 2 ? c : e.F + c * c;
    }
  return e;
}

// sigma^2 exactly, for S formed from A_i (parametric: scaled by Q^4).
Rational exact_squared(const Exact& e, Form f, const Rational& q) {
  if (f == Form::Parametric) return e.S / (q * q * q * q);
  if (f == Form::Plane) return (e.F / e.S) * (e.F / e.S);
  return e.F / (e.S * e.S);
}

// Whether the real ball x (imaginary part im, null for a real type) holds
// v; with root, whether x^2 holds v (x encloses sqrt(v)).
bool holds(const arb_t x, const arb_t im, const Rational& v, bool root) {
  if (im && !arb_contains_zero(im)) return false;
  Ball t;
  if (root) arb_sqr(t.get(), x, 256);
  else arb_set(t.get(), x);
  return arb_contains_fmpq(t.get(), v.get());
}

// The enclosure arithmetics with a conversion from and to Arb.
struct AcbSide {
  AcbArith ar{128};
  using T = AcbBox;
  T from(const Rational& v) const {
    T r;
    acb_set_fmpq(r, v.get(), 128);  // a ball of radius ~2^-128 |v| where v is not dyadic
    return r;
  }
  bool check(const T& x, const Rational& v, bool root, long bits) const {
    return holds(acb_realref(x.get()), acb_imagref(x.get()), v, root) &&
           (v == Rational(0) || acb_rel_accuracy_bits(x.get()) >= bits);
  }
};

struct DiskSide {
  DiskArith ar;
  using T = CDisk;
  T from(const Rational& v) const {
    AcbBox b;
    acb_set_fmpq(b, v.get(), 128);
    return cdisk_set_acb(b);
  }
  bool check(const T& x, const Rational& v, bool root, long bits) const {
    AcbBox b;
    cdisk_get_acb(b, x);
    return holds(acb_realref(b.get()), acb_imagref(b.get()), v, root) &&
           (v == Rational(0) || acb_rel_accuracy_bits(b.get()) >= bits / 3);
  }
};

struct DDSide {
  DDArith<false> ar;
  using T = DDBall;
  T from(const Rational& v) const {
    Ball b(v, 128);
    DDBall r;
    EXPECT_TRUE(dd_set_arb(r, b.get()));
    return r;
  }
  bool check(const T& x, const Rational& v, bool root, long bits) const {
    if (!dd_is_finite(x)) return false;
    Ball b;
    dd_get_arb(b.get(), x);
    return holds(b.get(), nullptr, v, root) && (v == Rational(0) || arb_rel_accuracy_bits(b.get()) >= bits * 3 / 4);
  }
};

template <class Side>
void check_formula(bool dyadic) {
  Side side;
  std::mt19937 rng(20261203);
  int tried = 0;
  for (int round = 0; round < 200; ++round) {
    const std::size_t n = 2 + static_cast<std::size_t>(round % 2);
    const Data d = formula_data(rng, n, dyadic);
    const Exact e = exact_parts(d);
    if (e.S == Rational(0) || e.F == Rational(0)) continue;
    ++tried;
    using T = typename Side::T;
    std::vector<T> nv, n1, n2, A(n), B(n);
    for (std::size_t i = 0; i < n; ++i) {
      nv.push_back(side.from(d.n[i]));
      n1.push_back(side.from(d.n1[i]));
      n2.push_back(side.from(d.n2[i]));
    }
    const T q = side.from(d.q), q1 = side.from(d.q1), q2 = side.from(d.q2);
    for (std::size_t i = 0; i < n; ++i) {
      speed_formula::scaled_derivatives(side.ar, A[i], &B[i], nv[i], n1[i], &n2[i], q, q1, &q2);
      ASSERT_TRUE(side.check(A[i], e.A[i], false, 60)) << "A_" << i << " round " << round;
      ASSERT_TRUE(side.check(B[i], e.B[i], false, 60)) << "B_" << i;
    }
    T S, F, r, l2;
    speed_formula::sum_of_squares(side.ar, S, n, [&A](std::size_t i) -> const T& { return A[i]; });
    ASSERT_TRUE(side.check(S, e.S, false, 60));
    speed_formula::cross_terms(side.ar, F, A.data(), B.data(), n);
    ASSERT_TRUE(side.check(F, e.F, false, 40));
    side.ar.mul(l2, q, q);
    const Form form = n == 2 ? Form::Plane : Form::Space;
    for (Form f : {form, Form::Parametric}) {
      const T* scale = f == Form::Parametric ? &l2 : nullptr;
      speed_formula::speed_squared(side.ar, r, S, F, f, scale);
      EXPECT_TRUE(side.check(r, exact_squared(e, f, d.q), false, 40)) << "sigma^2, round " << round;
      T Fc = F;
      speed_formula::speed_value(side.ar, r, S, Fc, f, -1, scale);
      if (f == Form::Plane) {  // sigma = -C_12 / S exactly, no root
        EXPECT_TRUE(side.check(r, Rational(0) - e.F / e.S, false, 40)) << "sigma, round " << round;
      } else {
        EXPECT_TRUE(side.check(r, exact_squared(e, f, d.q), true, 40)) << "sigma, round " << round;
      }
    }
    // the factored form: s / D * g and (sum K^2 / D^2) g^2, with s^2 = S
    T s, ratio;
    side.ar.sqrt(s, S);
    speed_formula::factored_value(side.ar, r, s, q, [&](T& g) { g = q1; }, 1);
    EXPECT_TRUE(side.check(r, e.S * d.q1 * d.q1 / (d.q * d.q), true, 40));
    speed_formula::factored_ratio_squared(side.ar, ratio, S, q);
    speed_formula::factored_squared(side.ar, r, ratio, q1);
    EXPECT_TRUE(side.check(r, e.S * d.q1 * d.q1 / (d.q * d.q), false, 40));
  }
  EXPECT_GT(tried, 150);
}

}  // namespace

TEST(SpeedFormula, ArbBallsEncloseTheExactValues) {
  check_formula<AcbSide>(false);
  check_formula<AcbSide>(true);
}

TEST(SpeedFormula, DiscsEncloseTheExactValues) { check_formula<DiskSide>(true); }

TEST(SpeedFormula, DoubleWordBallsEncloseTheExactValues) {
  check_formula<DDSide>(false);
  check_formula<DDSide>(true);
}

TEST(SpeedFormula, QuotientRuleEnclosesTheExactDerivatives) {
  std::mt19937 rng(7);
  AcbSide side;
  for (int round = 0; round < 100; ++round) {
    const Data d = formula_data(rng, 1, false);
    const Rational a = d.n1[0] * d.q - d.n[0] * d.q1, b = d.n2[0] * d.q - d.n[0] * d.q2;
    const Rational x1 = a / (d.q * d.q);
    const Rational x2 = b / (d.q * d.q) - Rational(2) * d.q1 * a / (d.q * d.q * d.q);
    AcbBox n = side.from(d.n[0]), n1 = side.from(d.n1[0]), n2 = side.from(d.n2[0]);
    AcbBox q = side.from(d.q), q1 = side.from(d.q1), q2 = side.from(d.q2), A, v, w, d1, d2;
    side.ar.inv(v, q);
    side.ar.mul(w, v, v);
    speed_formula::scaled_derivatives(side.ar, A, &n2, n, n1, &n2, q, q1, &q2);
    speed_formula::quotient_derivatives(side.ar, d1, &d2, A, &n2, q1, v, w);
    EXPECT_TRUE(holds(acb_realref(d1.get()), acb_imagref(d1.get()), x1, false)) << round;
    EXPECT_TRUE(holds(acb_realref(d2.get()), acb_imagref(d2.get()), x2, false)) << round;
  }
}
