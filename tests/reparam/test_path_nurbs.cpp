// Tests of the NURBS / B-spline reader (reparam/path.hpp): NURBS circles
// with exact rational weights whose segments lie exactly on the circle,
// random (rational) B-splines with interior and repeated knots, clamped and
// unclamped, whose Bezier segments agree exactly with an independent
// evaluation by the Cox-de Boor basis functions, and every validation error.
#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <string>
#include <vector>

#include "support/bezier_point.hpp"
#include "support/errors.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/reparam/path.hpp"

namespace uniparam {
namespace {

Rational R(long a, long b = 1) { return Rational(a, b); }

using test_support::bezier_point;

// Cox-de Boor: N_{i,p}(x) for the knot vector u, with the half-open
// convention on [u_i, u_{i+1}) except that x = `right` (the domain's end)
// belongs to the last nonempty span before it.
Rational basis(const std::vector<Rational>& u, std::size_t i, long p, const Rational& x, const Rational& right) {
  if (p == 0) {
    if (u[i] <= x && x < u[i + 1]) return R(1);
    if (x == right && u[i] < u[i + 1] && u[i + 1] == right) return R(1);
    return R(0);
  }
  Rational r(0);
  if (u[i + static_cast<std::size_t>(p)] != u[i])
    r = r + (x - u[i]) / (u[i + static_cast<std::size_t>(p)] - u[i]) * basis(u, i, p - 1, x, right);
  if (u[i + static_cast<std::size_t>(p) + 1] != u[i + 1])
    r = r + (u[i + static_cast<std::size_t>(p) + 1] - x) / (u[i + static_cast<std::size_t>(p) + 1] - u[i + 1]) *
                basis(u, i + 1, p - 1, x, right);
  return r;
}

std::vector<Rational> nurbs_point(const std::vector<std::vector<Rational>>& P, const std::vector<Rational>& w,
                                  const std::vector<Rational>& u, long p, const Rational& x) {
  const Rational right = u[P.size()];
  std::vector<Rational> num(P[0].size(), R(0));
  Rational den(0);
  for (std::size_t i = 0; i < P.size(); ++i) {
    const Rational b = basis(u, i, p, x, right) * w[i];
    den = den + b;
    for (std::size_t c = 0; c < num.size(); ++c) num[c] = num[c] + b * P[i][c];
  }
  for (auto& v : num) v = v / den;
  return num;
}

std::string json_list(const std::vector<Rational>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", \"" : "\"") + v[i].str() + "\"";
  return s + "]";
}

std::string nurbs_json(long p, const std::vector<Rational>& u, const std::vector<std::vector<Rational>>& P,
                       const std::vector<Rational>& w) {
  std::string s = "{\"degree\": " + std::to_string(p) + ", \"knots\": " + json_list(u) + ", \"control\": [";
  for (std::size_t i = 0; i < P.size(); ++i) s += (i ? ", " : "") + json_list(P[i]);
  s += "]";
  if (!w.empty()) s += ", \"weights\": " + json_list(w);
  return s + "}";
}


TEST(NurbsInput, FullCircleWithRationalWeights) {
  // Four quarter circles, each with w1^2 / (w0 w2) = 1/2: weights 1, 1, 2, 2, 4, 4, 8, 8, 16.
  const auto path = parse_nurbs(R"({"degree": 2, "knots": [0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4],
    "control": [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1], [0, -1], [1, -1], [1, 0]],
    "weights": [1, 1, 2, 2, 4, 4, 8, 8, 16]})");
  ASSERT_EQ(path.segments.size(), 4u);
  EXPECT_EQ(path.knots, (std::vector<Rational>{R(0), R(1, 4), R(1, 2), R(3, 4), R(1)}));
  for (const auto& b : path.segments) {
    ASSERT_TRUE(b.is_rational());
    for (const Rational& t : {R(0), R(1, 5), R(1, 3), R(1, 2), R(7, 9), R(1)}) {
      const auto x = bezier_point(b, t);
      EXPECT_EQ(x[0] * x[0] + x[1] * x[1], R(1)) << t.str();
    }
  }
}

TEST(NurbsInput, PythagoreanArcs) {
  // Arcs of the unit circle from (1, 0) to (3/5, 4/5) to (-7/25, 24/25)
  // (turns by the angle with cosine 3/5): the tangents meet at (1, 1/2) and
  // (1/5, 11/10); each arc has w1^2 / (w0 w2) = 4/5, the squared cosine of
  // its half angle; all data written as decimals.
  const auto path = parse_nurbs(R"({"degree": 2, "knots": [0, 0, 0, 0.5, 0.5, 1, 1, 1],
    "control": [[1, 0], [1, 0.5], [0.6, 0.8], [0.2, 1.1], [-0.28, 0.96]],
    "weights": [1, 0.8, 0.8, 0.64, 0.64]})");
  ASSERT_EQ(path.segments.size(), 2u);
  for (const auto& b : path.segments)
    for (const Rational& t : {R(1, 4), R(1, 2), R(2, 3)}) {
      const auto x = bezier_point(b, t);
      EXPECT_EQ(x[0] * x[0] + x[1] * x[1], R(1)) << t.str();
    }
  EXPECT_EQ(path.segments[1].points().back(), (std::vector<Rational>{R(-7, 25), R(24, 25)}));
}

// Random B-splines and NURBS of degree 1-4 in 2 or 3 dimensions with random
// (repeated) knots, clamped or not: every segment equals the spline on its span.
TEST(NurbsInput, SegmentsAgreeWithCoxDeBoor) {
  std::mt19937_64 rng(1972);
  int checked = 0;
  for (int it = 0; it < 60; ++it) {
    const long p = 1 + static_cast<long>(rng() % 4);
    const std::size_t np = static_cast<std::size_t>(p) + 1 + rng() % 5, dim = 2 + rng() % 2;
    const bool clamped = rng() & 1, weighted = rng() & 1;
    std::vector<std::vector<Rational>> P(np);
    for (auto& q : P)
      for (std::size_t c = 0; c < dim; ++c) q.push_back(R(static_cast<long>(rng() % 41) - 20, 1 + rng() % 3));
    std::vector<Rational> w;
    if (weighted)
      for (std::size_t i = 0; i < np; ++i) w.push_back(R(1 + static_cast<long>(rng() % 9), 1 + rng() % 4));
    // knots: nondecreasing, interior multiplicity <= p
    const std::size_t nk = np + static_cast<std::size_t>(p) + 1;
    std::vector<Rational> u;
    Rational x(static_cast<long>(rng() % 5) - 2);
    while (u.size() < nk) {
      std::size_t mult = 1 + rng() % static_cast<std::size_t>(p);
      if (clamped && (u.empty() || u.size() + static_cast<std::size_t>(p) + 1 == nk)) mult = static_cast<std::size_t>(p) + 1;
      for (std::size_t k = 0; k < mult && u.size() < nk; ++k) u.push_back(x);
      x = x + R(1 + static_cast<long>(rng() % 3), 1 + rng() % 2);
    }
    const std::string text = nurbs_json(p, u, P, w);
    SCOPED_TRACE(text);
    PathInput path;
    try {
      path = parse_nurbs(text);
    } catch (const InvalidArgument& e) {
      // a random spline may have an empty domain or a span that is a single
      // point; nothing else may fail
      const std::string m = e.what();
      EXPECT_TRUE(m.find("single point") != std::string::npos || m.find("empty domain") != std::string::npos) << m;
      continue;
    }
    const std::vector<Rational> ww = weighted ? w : std::vector<Rational>(np, R(1));
    const Rational lo = u[static_cast<std::size_t>(p)], hi = u[np], width = hi - lo;
    ASSERT_EQ(path.knots.front(), R(0));
    ASSERT_EQ(path.knots.back(), R(1));
    for (std::size_t j = 0; j < path.segments.size(); ++j) {
      const Rational a = lo + path.knots[j] * width, b = lo + path.knots[j + 1] * width;
      ASSERT_LT(a, b);
      EXPECT_EQ(path.segments[j].degree(), p);
      for (const Rational& s : {R(0), R(1, 3), R(1, 2), R(4, 5), R(1)}) {
        // s = 1 is the span's right end: evaluated from the right span by
        // Cox-de Boor, equal by continuity (interior multiplicity <= p).
        EXPECT_EQ(bezier_point(path.segments[j], s), nurbs_point(P, ww, u, p, a + s * (b - a)))
            << "segment " << j << " s = " << s.str();
      }
    }
    // every distinct knot of the domain is a joint
    std::size_t distinct = 0;
    for (std::size_t i = static_cast<std::size_t>(p); i < np; ++i) distinct += u[i] < u[i + 1];
    EXPECT_EQ(path.segments.size(), distinct);
    ++checked;
  }
  EXPECT_GE(checked, 40);
}

TEST(NurbsInput, EqualWeightsGiveIntegralSegments) {
  const auto a = parse_nurbs(R"({"degree": 1, "knots": [0, 0, 1, 1], "control": [[0, 0], [1, 2]], "weights": [3, 3]})");
  EXPECT_FALSE(a.segments[0].is_rational());
  const auto b = parse_nurbs(R"({"degree": 1, "knots": [0, 0, 1, 1], "control": [[0, 0], [1, 2]], "weights": [3, 2]})");
  EXPECT_TRUE(b.segments[0].is_rational());
  EXPECT_EQ(a.labels[0], "span [0, 1] (knots 1 and 2)");
}

TEST(NurbsInput, ValidationErrors) {
  struct Case { const char* json; const char* words; };
  const Case cases[] = {
      {R"([1])", "a NURBS description must be an object, got an array"},
      {R"({"knots": [0, 0, 1, 1], "control": [[0, 0], [1, 1]]})", "missing key \"degree\""},
      {R"({"degree": 1, "control": [[0, 0], [1, 1]]})", "missing key \"knots\""},
      {R"({"degree": 1, "knots": [0, 0, 1, 1]})", "missing key \"control\""},
      {R"({"degree": 1, "knots": [0, 0, 1, 1], "control": [[0, 0], [1, 1]], "weight": [1, 1]})", "unknown key \"weight\""},
      {R"({"degree": 0, "knots": [0, 1], "control": [[0, 0]]})", "\"degree\" must be an integer from 1 to 1000"},
      {R"({"degree": 1.5, "knots": [0, 0, 1, 1], "control": [[0, 0], [1, 1]]})", "must be an integer"},
      {R"({"degree": "1", "knots": [0, 0, 1, 1], "control": [[0, 0], [1, 1]]})", "must be an integer, got a string"},
      {R"({"degree": 2, "knots": [0, 0, 1, 1], "control": [[0, 0], [1, 1]]})", "degree 2 needs at least 3 control points"},
      {R"({"degree": 1, "knots": [0, 0, 1], "control": [[0, 0], [1, 1]]})", "need 4 knots (control points + degree + 1), got 3"},
      {R"({"degree": 1, "knots": [0, 1, 0, 1], "control": [[0, 0], [1, 1]]})", "non-decreasing, but knot 2 = 0 is below knot 1 = 1"},
      {R"({"degree": 1, "knots": [0, 1, 1, 2], "control": [[0, 0], [1, 1]]})", "empty domain"},
      {R"({"degree": 2, "knots": [0, 0, 0, 1, 1, 1, 2, 2, 2], "control": [[0, 0], [1, 1], [2, 0], [3, 1], [4, 0], [5, 5]]})",
       "knot 1 (knots 3 to 5) has multiplicity 3, above 2 (the degree) inside the domain"},
      {R"({"degree": 1, "knots": [0, 0, 0, 1, 1], "control": [[0, 0], [1, 1], [2, 2]]})", "has multiplicity 3, above 2 (degree + 1)"},
      {R"({"degree": 1, "knots": [0, 0, 1, 1], "control": [[0, 0], [1, 1]], "weights": [1]})", "need 2 weights, got 1"},
      {R"({"degree": 1, "knots": [0, 0, 1, 1], "control": [[0, 0], [1, 1]], "weights": [1, 0]})", "weight 1 = 0 is not positive"},
      {R"({"degree": 1, "knots": [0, 0, 1, 1], "control": [[0, 0], [1, 1]], "weights": [-1, 1]})", "weight 0 = -1 is not positive"},
      {R"({"degree": 1, "knots": [0, 0, 1, 1], "control": [[0], [1]]})", "at least 2 coordinates"},
      {R"({"degree": 1, "knots": [0, 0, 1, 1], "control": [[0, 0], [1, 1, 1]]})", "control point 1 has 3 coordinates, control point 0 has 2"},
      {R"({"degree": 1, "knots": [0, 0, 1, 1], "control": [[0, 0], [1, "x"]]})", "control point 1 coordinate 1"},
      {R"({"degree": 1, "knots": [0, 0, "1/0", 1], "control": [[0, 0], [1, 1]]})", "knot 2"},
      {R"({"degree": 1, "knots": [0, 0, 1, 1], "control": [[0, 0], 5]})", "control point 1 must be an array"},
      {R"({"degree": 1, "knots": {}, "control": [[0, 0], [1, 1]]})", "\"knots\" must be an array, got an object"},
      {R"({"degree": 1, "knots": [0, 0, 1, 2, 2], "control": [[0, 0], [1, 1], [1, 1]]})",
       "span [1, 2] (knots 2 and 3) is a single point"},
  };
  for (const auto& c : cases) {
    const std::string m = test_support::message_of([&] { parse_nurbs(c.json); });
    EXPECT_NE(m.find(c.words), std::string::npos) << c.json << "\n -> " << m;
  }
  EXPECT_THROW(parse_nurbs("{\"degree\": 1,"), ParseError);
  NurbsLimits lim;
  lim.max_points = 2;
  EXPECT_NE(test_support::message_of([&] {
              parse_nurbs(R"({"degree": 1, "knots": [0, 0, 1, 2, 2], "control": [[0, 0], [1, 1], [2, 0]]})", lim);
            }).find("more than 2 control points"),
            std::string::npos);
}

TEST(NurbsInput, UnclampedUniformCubic) {
  // A uniform cubic B-spline on knots 0..9 with 6 control points: domain [3, 6], three segments.
  const auto path = parse_nurbs(R"({"degree": 3, "knots": [0, 1, 2, 3, 4, 5, 6, 7, 8, 9],
    "control": [[0, 0], [1, 3], [3, 4], [5, 1], [7, 2], [9, 0]]})");
  ASSERT_EQ(path.segments.size(), 3u);
  EXPECT_EQ(path.knots, (std::vector<Rational>{R(0), R(1, 3), R(2, 3), R(1)}));
  // The uniform cubic's segment starts at (P0 + 4 P1 + P2) / 6.
  EXPECT_EQ(path.segments[0].points()[0], (std::vector<Rational>{R(7, 6), R(16, 6)}));
  for (std::size_t j = 0; j + 1 < path.segments.size(); ++j)
    EXPECT_EQ(path.segments[j].points().back(), path.segments[j + 1].points().front());
}

// Random edits of a valid description: a result or a uniparam::Error, never
// a crash or another exception.
TEST(NurbsInput, MutatedDescriptionsGiveResultsOrErrors) {
  const std::string seed =
      R"({"degree": 2, "knots": [0, 0, 0, 0.5, 0.5, 1, 1, 1], "control": [[1, 0], [1, 0.5], [0.6, 0.8], )"
      R"([0.2, 1.1], [-0.28, 0.96]], "weights": [1, 0.8, 0.8, 0.64, 0.64]})";
  const std::string alphabet = "0123456789.-e,[]{}\": /";
  std::mt19937_64 rng(2023);
  const int results = test_support::mutated_results({seed}, alphabet, 3, rng, 3000, [](const std::string& t) {
    const PathInput p = parse_nurbs(t);
    EXPECT_EQ(p.knots.size(), p.segments.size() + 1) << t;
  });
  EXPECT_GT(results, 100);
}

}  // namespace
}  // namespace uniparam
