// The work of exact_samples_each, counted: the certified integrals of sigma
// it asks for per located point (through the internal Track interface of
// reparam/src/track.hpp, wrapped to count). Each integral decides one sign
// of G(x) - T; on a smooth arc the safeguarded Newton iteration should
// shrink the bracket by one Newton step per integral, so from the previous
// point to 15 digits a point takes a handful of integrals, whatever K.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../../reparam/src/track.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

// A Track for one curve (as locate.cpp's own) that counts integral().
class CountingTrack final : public Track {
 public:
  CountingTrack(const Curve& c, const Speed& s) : c_(c), s_(s) {}
  bool identically_zero() const override { return s_.identically_zero(); }
  SpeedKind kind() const override { return s_.kind(); }
  Ball mu(long bits, const Options& opt) const override { return mean_speed(s_, bits, opt); }
  Ball integral(const Rational& a, const Rational& b, long bits) const override {
    ++count;
    return integrate_speed(s_, RealAlgebraic(a), RealAlgebraic(b), bits, Options{}.max_prec);
  }
  double sigma_estimate(const Rational& x) const override { return uniparam::sigma_estimate(s_, x); }
  std::vector<Ball> eval(const Ball& t, long prec) const override { return c_.eval(t, prec); }
  mutable long count = 0;

 private:
  const Curve& c_;
  const Speed& s_;
};

// Integrals per interior point of K exact samples at 15 digits on the chain
// of certified integrals (a track without segments: no Taylor models),
// checking on the way that its balls overlap the library's (both contain
// the exact parameters).
double integrals_per_point(const std::string& curve, long K) {
  const Curve c = Curve::parse(curve);
  const Speed s(c, SpeedKind::Parametric);
  Options opt;
  opt.digits = 15;
  CountingTrack tr(c, s);
  Ball mu;
  std::vector<Ball> ts;
  exact_samples_on(tr, K, opt, mu, [&](long, const LocatedPoint& p) { ts.push_back(p.t); });
  const ExactSamples lib = exact_samples(c, s, K, opt);
  EXPECT_EQ(ts.size(), static_cast<std::size_t>(K));
  for (std::size_t k = 0; k < ts.size() && k < lib.points.size(); ++k)
    EXPECT_TRUE(arb_overlaps(ts[k].get(), lib.points[k].t.get())) << curve << " point " << k;
  return static_cast<double>(tr.count) / static_cast<double>(K - 2);
}

}  // namespace

// Smooth arcs without zeros of sigma: the parabola, a TrueType quadratic of
// DejaVu Sans, a cubic with an inflection, a rational arc. At K = 101 the
// Newton iteration from the previous point (~1/100 away) reaches 15 digits
// in at most 7 integrals a point on average: each decided sign is a Newton
// step (error d -> ~d^2) from 10^-2 to 2^-51, and the bracket needs one
// probe on each side of t (at least 2).
TEST(LocateWork, FewIntegralsPerPointOnSmoothArcs) {
  const std::vector<std::string> curves = {
      "(t, t^2)",
      "((1-t)^2*170 + 2*t*(1-t)*272 + t^2*753/2, (1-t)^2*272 + 2*t*(1-t)*208 + t^2*351/2)",
      "(t, t^3 - t/2)",
      "((1 - t^2)/(1 + t^2), 2*t/(1 + t^2))",
  };
  for (const auto& c : curves) {
    const double per_point = integrals_per_point(c, 101);
    EXPECT_LE(per_point, 7.0) << c;
    EXPECT_GE(per_point, 2.0) << c;
  }
}

// Speed::piece_signs is remembered per interval between zeros of sigma, so
// it must know which interval (a, b) is in: (a, b) holding a zero is
// refused, wherever the zero lies (here 1/3, not the middle point the
// signs are taken at), and pieces on either side of it get their own signs.
TEST(LocateWork, PieceSignsRefuseAPieceAcrossAZero) {
  const Curve c = Curve::parse("((3*t - 1)^2, (3*t - 1)^3)");
  const Speed s(c, SpeedKind::Parametric);
  ASSERT_EQ(s.zeros().size(), 1u);
  EXPECT_THROW(s.piece_signs(RealAlgebraic(Rational(0)), RealAlgebraic(Rational(1))), DomainError);
  EXPECT_THROW(s.piece_signs(RealAlgebraic(Rational(1, 4)), RealAlgebraic(Rational(1, 2))), DomainError);
  const Speed::PieceSigns left = s.piece_signs(RealAlgebraic(Rational(0)), RealAlgebraic(Rational(1, 3)));
  const Speed::PieceSigns right = s.piece_signs(RealAlgebraic(Rational(1, 3)), RealAlgebraic(Rational(1)));
  // sigma = 3 |3t - 1| sqrt(4 + 9 (3t - 1)^2): g = 3t - 1 changes sign at 1/3.
  EXPECT_EQ(left.g, -right.g);
  // The same interval again, asked differently, gives the same signs.
  EXPECT_EQ(s.piece_signs(RealAlgebraic(Rational(1, 10)), RealAlgebraic(Rational(1, 5))).g, left.g);
  EXPECT_EQ(s.piece_signs(RealAlgebraic(Rational(1, 2)), RealAlgebraic(Rational(9, 10))).g, right.g);
}
