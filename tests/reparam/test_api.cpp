// The public facade (uniparam/uniparam.hpp) against the engine it wraps:
// the same balls and exact values on random curves, its errors (types and
// messages naming Options fields), results that own their curve, the thread
// count and the time limit of Options.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "support/curves.hpp"
#include "uniparam/core/parallel.hpp"
#include "uniparam/reparam/all.hpp"
#include "uniparam/uniparam.hpp"

namespace {

namespace up = uniparam::api;
using uniparam::test_support::random_poly;

/// The facade's ball is the engine's, bit for bit.
::testing::AssertionResult same(const up::Ball& a, const uniparam::Ball& b) {
  const std::string am = a.mid().str(), ar = a.rad().str();
  const std::string bm = uniparam::mid_rational(b).str(), br = uniparam::rad_rational(b).str();
  if (am == bm && ar == br) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a.str(30) << " != " << b.str(30);
}

::testing::AssertionResult same(const up::Ball& a, const up::Ball& b) {
  if (a.mid() == b.mid() && a.rad() == b.rad()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a.str(30) << " != " << b.str(30);
}

/// Random plane curves (t + a t^2, b t^2 + c t^3)-like: random cubics.
std::vector<std::string> random_curves(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::string> out;
  while (static_cast<int>(out.size()) < n) {
    const uniparam::Poly x = random_poly(rng, 2, 4), y = random_poly(rng, 3, 4);
    if (x.degree() < 1 && y.degree() < 1) continue;
    const std::string text = "(" + uniparam::RatFunc(x).str() + ", " + uniparam::RatFunc(y).str() + ")";
    try {
      uniparam::Curve c = uniparam::Curve::parse(text);
      uniparam::Speed s(c, uniparam::SpeedKind::Angular);
      if (uniparam::uniformity(s).identically_zero) continue;  // a line: nothing to compare
    } catch (const uniparam::Error&) {
      continue;  // constant
    }
    out.push_back(text);
  }
  return out;
}

uniparam::Options engine(const up::Options& o) {
  uniparam::Options e;
  e.digits = o.digits;
  e.max_prec = uniparam::default_max_prec(o.digits);
  e.max_degree = o.max_degree;
  return e;
}

TEST(Api, RandomCurvesGiveTheEngineBalls) {
  for (const std::string& text : random_curves(4, 35)) {
    SCOPED_TRACE(text);
    up::Options o;
    const up::Curve c = up::Curve::parse(text, o);
    const uniparam::Curve ec = uniparam::Curve::parse(text);
    const uniparam::Options eo = engine(o);
    const uniparam::Speed sp(ec, uniparam::SpeedKind::Angular);
    EXPECT_EQ(c.str(), ec.str());

    const up::Uniformity u = up::uniformity(c, o);
    const uniparam::UniformityResult eu = uniparam::uniformity(ec, uniparam::SpeedKind::Angular, eo);
    EXPECT_TRUE(same(u.mu, eu.mu));
    EXPECT_TRUE(same(u.mean_square, eu.mean_square));
    EXPECT_TRUE(same(u.u, eu.u));
    ASSERT_EQ(u.zeros.size(), eu.zeros.size());
    for (std::size_t i = 0; i < u.zeros.size(); ++i) {
      EXPECT_EQ(u.zeros[i].multiplicity, eu.zeros[i].multiplicity);
      EXPECT_TRUE(u.zeros[i].t.meets_digits(o.digits));
      if (eu.zeros[i].t.is_rational()) EXPECT_TRUE(u.zeros[i].t.contains(up::Rational::parse(eu.zeros[i].t.rational().str())));
    }

    const up::Reparameterization r = up::radical(c, o);
    const uniparam::RadicalResult er = uniparam::radical(ec, uniparam::SpeedKind::Angular, eo);
    EXPECT_EQ(r.method(), "radical");
    EXPECT_EQ(r.pieces(), er.pieces());
    EXPECT_TRUE(same(r.u_before(), er.u_before));
    EXPECT_TRUE(same(r.u_after(), er.u_after));
    EXPECT_TRUE(same(r.mu(), er.mu));
    uniparam::Sampler es(ec, sp, uniparam::Reparameterization(er), eo.digits, eo.max_prec);
    const uniparam::SamplePoint ep = es.at(uniparam::Rational(1, 3));
    const up::Reparameterization::Sample p = r.at(up::Rational(1, 3));
    EXPECT_TRUE(same(p.t, ep.t));
    EXPECT_TRUE(same(r.eval_r(up::Rational(1, 3)), ep.t));
    ASSERT_EQ(p.point.size(), ep.point.size());
    for (std::size_t k = 0; k < p.point.size(); ++k) EXPECT_TRUE(same(p.point[k], ep.point[k]));
    EXPECT_TRUE(same(p.speed, ep.speed));

    const up::Reparameterization c0 = up::moebius_pieces(c, 3, o);
    const uniparam::MoebiusResult e0 = uniparam::reparam_c0(ec, uniparam::SpeedKind::Angular, 3, eo);
    EXPECT_EQ(c0.method(), "C0 piecewise Moebius");
    EXPECT_TRUE(same(c0.u_after(), e0.u_after));
    const auto joints = c0.breakpoints();
    ASSERT_EQ(joints.size(), e0.T.size());
    for (std::size_t i = 0; i < joints.size(); ++i) {
      EXPECT_TRUE(same(joints[i].s, e0.S[i]));
      EXPECT_TRUE(joints[i].t.contains(up::Rational::parse(e0.T[i].t.rational().str())));
    }
    const up::Reparameterization q = c0.rational(8);
    const uniparam::MoebiusResult eq = uniparam::make_rational(ec, e0, 8, eo);
    EXPECT_TRUE(q.is_rational());
    EXPECT_TRUE(same(q.u_after(), eq.u_after));
    const up::Nurbs n = q.nurbs();
    const uniparam::Nurbs en = uniparam::moebius_nurbs(ec, eq, uniparam::digits_to_bits(o.digits) + 32);
    EXPECT_TRUE(n.exact());
    ASSERT_EQ(n.weights_exact().size(), en.weights_exact.size());
    for (std::size_t i = 0; i < en.weights_exact.size(); ++i) EXPECT_EQ(n.weights_exact()[i].str(), en.weights_exact[i].str());
    const auto f = q.formulas();
    const auto ef = uniparam::moebius_formulas(ec, eq, uniparam::Format::Text, o.digits);
    ASSERT_EQ(f.size(), ef.size());
    for (std::size_t i = 0; i < f.size(); ++i) {
      EXPECT_EQ(f[i].r, ef[i].r);
      EXPECT_EQ(f[i].interval, ef[i].s_interval);
      EXPECT_TRUE(f[i].exact);
    }
  }
}

TEST(Api, TargetBreakpointsAndLocateGiveTheEngineValues) {
  up::Options o;
  o.speed = up::SpeedKind::Parametric;
  const std::string text = "(t, t^3 - t/2)";
  const up::Curve c = up::Curve::parse(text, o);
  const uniparam::Curve ec = uniparam::Curve::parse(text);
  const uniparam::Options eo = engine(o);
  const uniparam::Speed sp(ec, uniparam::SpeedKind::Parametric);

  const up::Reparameterization c1 = up::moebius_target(c, up::Rational(99, 100), 64, o);
  const uniparam::MoebiusResult e1 =
      uniparam::reparam_c1(ec, uniparam::SpeedKind::Parametric, uniparam::Rational(99, 100), eo, 64);
  EXPECT_EQ(c1.method(), "C1 piecewise Moebius");
  EXPECT_EQ(c1.target_reached(), e1.target->reached);
  EXPECT_TRUE(same(c1.u_after(), e1.u_after));

  const up::Reparameterization cb = up::moebius_breakpoints(c, {up::Rational(0), up::Rational(1, 4), up::Rational(1)}, o);
  const uniparam::MoebiusResult eb = uniparam::moebius_c0(
      ec, uniparam::SpeedKind::Parametric,
      {uniparam::RealAlgebraic(uniparam::Rational(0)), uniparam::RealAlgebraic(uniparam::Rational(1, 4)),
       uniparam::RealAlgebraic(uniparam::Rational(1))},
      eo);
  EXPECT_TRUE(same(cb.u_after(), eb.u_after));
  EXPECT_EQ(cb.pieces(), 2u);

  const up::Located l = up::locate(c, up::Rational(1, 3), true, o);
  const uniparam::LocateResult el =
      uniparam::locate(ec, sp, uniparam::Rational(1, 3), uniparam::LocateTarget::Fraction, eo);
  EXPECT_TRUE(same(l.t, el.at.t));
  const auto xs = up::exact_samples(c, 5, o);
  const uniparam::ExactSamples ex = uniparam::exact_samples(ec, sp, 5, eo);
  ASSERT_EQ(xs.size(), 5u);
  for (std::size_t k = 0; k < xs.size(); ++k) EXPECT_TRUE(same(xs[k].t, ex.points[k].t));
  EXPECT_TRUE(xs.front().t.contains(up::Rational(0)) && xs.front().t.is_exact());
  EXPECT_TRUE(xs.back().t.contains(up::Rational(1)) && xs.back().t.is_exact());
}

TEST(Api, CompositeAndBezierGiveTheEngineValues) {
  up::Options o;
  o.speed = up::SpeedKind::Parametric;
  const std::string d = "M 0 0 Q 1 2 2 0 C 3 -1 4 1 5 0";
  const std::vector<up::Curve> paths = up::Curve::svg_path(d, o);
  ASSERT_EQ(paths.size(), 1u);
  const up::Curve& c = paths[0];
  EXPECT_EQ(c.segments(), 2u);
  EXPECT_FALSE(c.is_bezier());
  const uniparam::PathInput pin = uniparam::parse_svg_path(d)[0];
  std::vector<uniparam::Curve> segs;
  for (const auto& b : pin.segments) segs.push_back(b.to_curve());
  const uniparam::CompositeCurve cc(segs, pin.knots, pin.labels);
  const std::vector<uniparam::Speed> sp = cc.speeds(uniparam::SpeedKind::Parametric);
  const uniparam::Options eo = engine(o);

  const up::Uniformity u = up::uniformity(c, o);
  const uniparam::CompositeUniformity eu = uniparam::uniformity(cc, uniparam::SpeedKind::Parametric, eo);
  EXPECT_TRUE(same(u.mu, eu.mu));
  EXPECT_TRUE(same(u.u, eu.u));

  const up::Reparameterization r = up::moebius_pieces(c, 4, o);
  uniparam::CompositeMethod m;
  m.kind = uniparam::CompositeMethod::Kind::Pieces;
  m.pieces = 4;
  const uniparam::CompositeMap em = uniparam::composite_map(cc, sp, m, eo);
  EXPECT_EQ(r.pieces(), em.pieces());
  EXPECT_TRUE(same(r.u_after(), em.u_after()));
  uniparam::CompositeSampler es(cc, sp, em, eo.digits, eo.max_prec);
  EXPECT_TRUE(same(r.eval_r(up::Rational(2, 3)), es.at(uniparam::Rational(2, 3)).t));
  EXPECT_FALSE(r.nurbs().exact());
  EXPECT_TRUE(r.rational().nurbs().exact());

  const up::Curve bz = up::Curve::bezier("[[0,0],[0,1],[3,1]]", "", o);
  EXPECT_TRUE(bz.is_bezier());
  const up::Reparameterization br = up::bezier_bilinear(bz, o);
  const uniparam::BezierCurve eb = uniparam::BezierCurve::parse("[[0,0],[0,1],[3,1]]");
  const uniparam::BezierResult ebr = uniparam::bezier_optimal(eb, eo);
  EXPECT_EQ(br.method(), "Bezier bilinear");
  EXPECT_TRUE(same(br.u_after(), ebr.u_after));
  EXPECT_TRUE(same(br.u_before(), ebr.u_before));
  const up::Nurbs bn = br.nurbs();
  ASSERT_EQ(bn.weights_text().size(), ebr.weights_exact.size());
  for (std::size_t i = 0; i < ebr.weights_exact.size(); ++i) EXPECT_EQ(bn.weights_text()[i], ebr.weights_exact[i].str());
  // r(s) of the bilinear map (2.1) with the exact alpha: t = (1 - a) s / ((1 - a) s + a (1 - s)).
  const uniparam::Ball a = ebr.alpha_exact->to_ball(256);
  uniparam::Ball s(uniparam::Rational(1, 3), 256), one(1), t, den, x;
  arb_sub(x.get(), one.get(), a.get(), 256);      // 1 - a
  arb_mul(t.get(), x.get(), s.get(), 256);        // (1 - a) s
  arb_sub(den.get(), one.get(), s.get(), 256);    // 1 - s
  arb_mul(den.get(), den.get(), a.get(), 256);    // a (1 - s)
  arb_add(den.get(), den.get(), t.get(), 256);
  arb_div(t.get(), t.get(), den.get(), 256);
  const up::Ball rt = br.eval_r(up::Rational(1, 3));
  EXPECT_TRUE(rt.meets_digits(o.digits));
  const uniparam::Rational lo = uniparam::Rational::parse(rt.lower().str()), hi = uniparam::Rational::parse(rt.upper().str());
  EXPECT_TRUE(lo <= uniparam::mid_rational(t) + uniparam::rad_rational(t) && uniparam::mid_rational(t) - uniparam::rad_rational(t) <= hi);
}

}  // namespace

namespace {

template <class E, class F>
std::string message_of(F f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("WRONG TYPE: ") + e.what();
  }
  return "NO EXCEPTION";
}

bool has(const std::string& m, const std::string& part) { return m.find(part) != std::string::npos; }

TEST(Api, ErrorsHaveTheirTypesAndNameOptionsFields) {
  up::Options o;
  try {
    up::Curve::parse("(t, t^", o);
    ADD_FAILURE() << "no exception";
  } catch (const uniparam::ParseError& e) {
    EXPECT_EQ(e.column(), 7u);
  }
  EXPECT_TRUE(has(message_of<uniparam::DomainError>([&] { up::Curve::parse("(t, 1/(t - 1/2))", o); }), "pole"));
  EXPECT_TRUE(has(message_of<uniparam::DomainError>([&] { up::Curve::parse("(1, 2)", o); }), "constant"));

  up::Options bad = o;
  bad.digits = 0;
  EXPECT_EQ(message_of<uniparam::InvalidArgument>([&] { up::Curve::parse("(t, t^2)", bad); }),
            "Options::digits must be from 1 to 2000, got 0");
  bad = o;
  bad.time_limit = -1;
  EXPECT_TRUE(has(message_of<uniparam::InvalidArgument>([&] { up::Curve::parse("(t, t^2)", bad); }),
                  "Options::time_limit"));
  bad = o;
  bad.threads = 65;
  EXPECT_TRUE(has(message_of<uniparam::InvalidArgument>([&] { up::Curve::parse("(t, t^2)", bad); }),
                  "Options::threads"));

  up::Options small = o;
  small.max_degree = 5;
  const std::string deg = message_of<uniparam::BudgetExceeded>([&] { up::Curve::parse("(t, t^9)", small); });
  EXPECT_TRUE(has(deg, "Options::max_degree")) << deg;
  EXPECT_FALSE(has(deg, "--")) << deg;
  small = o;
  small.max_input_length = 5;
  EXPECT_TRUE(has(message_of<uniparam::BudgetExceeded>([&] { up::Curve::parse("(t, t^2)", small); }),
                  "Options::max_input_length"));

  up::Options prec = o;
  prec.digits = 60;
  prec.max_prec = 64;
  const up::Curve c = up::Curve::parse("(t, t^3)", o);
  const std::string pm = message_of<uniparam::BudgetExceeded>([&] { up::uniformity(c, prec); });
  EXPECT_TRUE(has(pm, "Options::max_prec")) << pm;
  EXPECT_FALSE(has(pm, "--max-prec")) << pm;

  EXPECT_TRUE(has(message_of<uniparam::InvalidArgument>([&] { up::bezier_bilinear(c, o); }), "Bezier"));
  up::Options po = o;
  po.speed = up::SpeedKind::Parametric;
  const up::Curve bz = up::Curve::bezier("[[0,0],[1,2],[2,0]]", "", po);
  EXPECT_TRUE(has(message_of<uniparam::InvalidArgument>([&] { up::bezier_bilinear(bz, o); }), "Options::speed"));
  const up::Reparameterization r = up::radical(c, o);
  EXPECT_TRUE(has(message_of<uniparam::InvalidArgument>([&] { r.nurbs(); }), "NURBS"));
  EXPECT_TRUE(has(message_of<uniparam::InvalidArgument>([&] { r.rational(); }), "rational"));
  EXPECT_TRUE(has(message_of<uniparam::InvalidArgument>([&] { r.eval_r(up::Rational(3, 2)); }), "[0, 1]"));
  EXPECT_TRUE(has(message_of<uniparam::InvalidArgument>([&] { r.samples(1); }), "K"));
  EXPECT_TRUE(has(message_of<uniparam::InvalidArgument>([&] { up::moebius_pieces(c, 0, o); }), "pieces"));
  EXPECT_TRUE(has(message_of<uniparam::InvalidArgument>([&] {
                    up::moebius_breakpoints(c, {up::Rational(0), up::Rational(1, 2)}, o);
                  }),
                  "breakpoints"));
  EXPECT_TRUE(has(message_of<uniparam::InvalidArgument>([&] { up::moebius_target(c, up::Rational(1), 64, o); }),
                  "target"));
  EXPECT_TRUE(has(message_of<uniparam::DomainError>([&] { up::locate(up::Curve::parse("(t, 2 t)", o), 1, true, o); }),
                  "zero"));
  EXPECT_TRUE(has(message_of<uniparam::InvalidArgument>([&] { up::Curve::svg_path("M 0 0 A 1 2 30 0 1 1 1", o); }),
                  "arc"));
  // An engine message naming a CLI option names the facade's instead.
  const std::string straight = message_of<uniparam::DomainError>(
      [&] { up::moebius(up::Curve::svg_path("M 0 0 Q 1 2 2 0 L 3 0", o).at(0), o); });
  EXPECT_TRUE(has(straight, "Options::speed = SpeedKind::Parametric")) << straight;
  EXPECT_FALSE(has(straight, "--")) << straight;
  EXPECT_TRUE(message_of<uniparam::ParseError>([&] { up::Rational::parse("1/x"); }).rfind("parse error", 0) == 0);
  EXPECT_TRUE(has(message_of<uniparam::DomainError>([&] { up::Rational(1, 0); }), "zero"));
}

TEST(Api, ResultsOwnTheirCurveAndOptions) {
  std::vector<up::Reparameterization> maps;
  up::Ball expected_t;
  {
    up::Options o;
    o.digits = 20;
    up::Curve c = up::Curve::parse("(t, t^3)", o);
    maps.push_back(up::radical(c, o));
    maps.push_back(up::moebius_target(c, up::Rational(9, 10), 64, o));
    std::vector<up::Curve> path = up::Curve::svg_path("M 0 0 Q 1 2 2 0 Q 3 -2 4 0", o);
    maps.push_back(up::moebius(path.at(0), o));
    expected_t = maps[0].eval_r(up::Rational(1, 2));
    o.digits = 3;  // changing the caller's Options changes nothing in the results
  }
  // Curve, Options and path are gone; every result still works on its own copies.
  EXPECT_EQ(maps[0].curve().str(), "(t, t^3)");
  EXPECT_EQ(maps[0].options().digits, 20);
  EXPECT_TRUE(same(maps[0].eval_r(up::Rational(1, 2)), expected_t));
  for (const auto& r : maps) {
    const auto smp = r.samples(5);
    ASSERT_EQ(smp.size(), 5u);
    EXPECT_TRUE(smp.front().t.contains(up::Rational(0)));
    EXPECT_TRUE(smp.back().t.contains(up::Rational(1)));
    for (const auto& p : smp) {
      EXPECT_TRUE(p.t.meets_digits(20));
      for (const auto& x : p.point) EXPECT_TRUE(x.meets_digits(20));
    }
    EXPECT_FALSE(r.formulas().empty());
  }
  EXPECT_EQ(maps[2].curve().segments(), 2u);
  EXPECT_TRUE(maps[1].rational().nurbs().exact());
  const up::Reparameterization copy = maps[1];
  maps.clear();
  EXPECT_FALSE(copy.nurbs().step("x.stp").empty());
}

TEST(Api, ThreadsOptionGivesTheSameBalls) {
  const std::string text = "(t^5 - 2 t^3 + t, 3 t^4 - t^2 + 2 t)";
  up::Options one, two;
  one.threads = 1;
  two.threads = 2;
  const up::Curve c = up::Curve::parse(text, one);
  const std::uint64_t before = uniparam::parallel_dispatches();
  const up::Uniformity u1 = up::uniformity(c, one);
  const up::Reparameterization r1 = up::moebius_pieces(c, 4, one);
  const up::Reparameterization::Sample s1 = r1.at(up::Rational(1, 3));
  // One thread: no pool thread is ever woken.
  EXPECT_EQ(uniparam::parallel_dispatches(), before);
  const up::Uniformity u2 = up::uniformity(c, two);
  const up::Reparameterization r2 = up::moebius_pieces(c, 4, two);
  EXPECT_TRUE(same(u1.mu, u2.mu));
  EXPECT_TRUE(same(u1.u, u2.u));
  EXPECT_TRUE(same(r1.u_after(), r2.u_after()));
  const up::Reparameterization::Sample s2 = r2.at(up::Rational(1, 3));
  EXPECT_TRUE(same(s1.t, s2.t));
  EXPECT_TRUE(same(s1.speed, s2.speed));
  // The option holds for the call only: nothing is left in force after it.
  EXPECT_EQ(uniparam::worker_count(), [] {
    const uniparam::ScopedWorkerCount none(0);
    return uniparam::worker_count();
  }());
}

TEST(Api, TimeLimitThatExpiresGivesTheBudgetError) {
  up::Options o;
  o.digits = 200;
  o.time_limit = 1e-9;  // expired at the first check
  up::Options parse_opt;
  const up::Curve c = up::Curve::parse("(t, t^3 - t/3)", parse_opt);
  const std::string m = message_of<uniparam::TimeLimitExceeded>([&] { up::uniformity(c, o); });
  EXPECT_TRUE(has(m, "time limit exceeded")) << m;
  EXPECT_TRUE(has(m, "Options::time_limit")) << m;
  EXPECT_FALSE(has(m, "--timeout")) << m;
  // A result computed without a limit keeps its own options: its later
  // calls are not limited by another Options' time limit.
  const up::Reparameterization r = up::moebius(c, parse_opt);
  EXPECT_TRUE(r.eval_r(up::Rational(1, 2)).meets_digits(15));
  // Nothing is left in force after the failed call.
  EXPECT_FALSE(uniparam::has_time_budget());
}

}  // namespace
