// Tests of the SVG path reader (reparam/path.hpp): every command letter,
// absolute and relative spellings of random paths giving identical segments,
// implicit repetitions, the S/T reflection rules, the number grammar, Z and
// subpaths, zero-length segments, and arcs checked in exact arithmetic
// against ellipses built independently (every evaluated point on the
// ellipse, exact end points, sweep and large-arc flags from the side of the
// chord), plus every error kind.
#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "support/bezier_point.hpp"
#include "support/errors.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/reparam/path.hpp"

namespace uniparam {
namespace {

using Points = std::vector<std::vector<Rational>>;

Rational R(long a, long b = 1) { return Rational(a, b); }

using test_support::bezier_point;

// Segments as comparable text (points and weights).
std::string text_of(const std::vector<PathInput>& paths) {
  std::string s;
  for (const auto& p : paths) {
    s += "{";
    for (const auto& b : p.segments) {
      s += b.str();
      if (b.is_rational())
        for (const auto& w : b.weights()) s += " " + w.str();
      s += "; ";
    }
    s += "}";
  }
  return s;
}


TEST(SvgPath, EveryCommandLetter) {
  const auto paths = parse_svg_path(
      "M 0 0 L 10 0 H 20 V 10 C 20 20 30 20 30 10 S 40 0 40 10 Q 50 20 60 10 T 80 10 "
      "A 5 5 0 0 1 88 10 Z");
  ASSERT_EQ(paths.size(), 1u);
  const auto& p = paths[0];
  // L, H, V, C, S, Q, T, two arc pieces (a sweep above 90 degrees), Z.
  ASSERT_EQ(p.segments.size(), 10u);
  const long degrees[] = {1, 1, 1, 3, 3, 2, 2, 2, 2, 1};
  for (std::size_t k = 0; k < 10; ++k) EXPECT_EQ(p.segments[k].degree(), degrees[k]) << p.labels[k];
  EXPECT_EQ(p.segments[1].points()[1], (std::vector<Rational>{R(20), R(0)}));  // H keeps y
  EXPECT_EQ(p.segments[2].points()[1], (std::vector<Rational>{R(20), R(10)}));  // V keeps x
  EXPECT_EQ(p.segments[9].points()[1], (std::vector<Rational>{R(0), R(0)}));   // Z back to the start
  ASSERT_EQ(p.knots.size(), 11u);
  for (long j = 0; j <= 10; ++j) EXPECT_EQ(p.knots[static_cast<std::size_t>(j)], R(j, 10));
  EXPECT_EQ(p.labels[3], "segment 4: C at column 24");
  EXPECT_NE(p.labels[7].find("A at column 79 (arc 1, piece 1 of 2)"), std::string::npos) << p.labels[7];
  EXPECT_EQ(p.labels[9], "segment 10: Z at column 97");
  // Continuity.
  for (std::size_t k = 0; k + 1 < p.segments.size(); ++k)
    EXPECT_EQ(p.segments[k].points().back(), p.segments[k + 1].points().front()) << k;
}

// Random paths written twice, with absolute and with relative commands
// (coordinates as integers or decimals with one fractional digit), and with
// and without implicit repetitions: the segments are identical.
TEST(SvgPath, RelativeAndAbsoluteSpellingsAgree) {
  std::mt19937_64 rng(3636);
  auto coord = [&] { return R(static_cast<long>(rng() % 401) - 200, 10); };
  auto dec = [](const Rational& q) {  // q has denominator 1, 2, 5 or 10: one fractional digit
    const Rational t = q * R(10);
    std::string s = t.num().str();
    const bool neg = s[0] == '-';
    if (neg) s = s.substr(1);
    while (s.size() < 2) s = "0" + s;
    return (neg ? "-" : "") + s.substr(0, s.size() - 1) + "." + s.substr(s.size() - 1);
  };
  // Chords (multiplied by 1/10 below) of arcs with a rational center for
  // radii (5, 5) and (10, 5): half chords with a Pythagorean complement.
  struct ArcShape { long rx, ry, rot, dx, dy; };
  const ArcShape arcs[] = {{5, 5, 0, 8, 0}, {5, 5, 0, 0, 6}, {5, 5, 0, 6, 8}, {5, 5, 90, -8, 0}, {10, 5, 0, 16, 0},
                           {10, 5, 90, 0, 16}, {10, 5, 180, -16, 0}, {10, 5, -90, 0, -16}, {1, 1, 0, 30, 40}};
  int compared = 0;
  for (int it = 0; it < 60; ++it) {
    std::string abs = "M", rel = "m";
    Rational cx = coord(), cy = coord(), sx = cx, sy = cy;
    abs += " " + dec(cx) + " " + dec(cy);
    rel += " " + dec(cx) + " " + dec(cy);
    char prev = 'M';
    for (int k = 0; k < 12; ++k) {
      const int c = static_cast<int>(rng() % 10);
      const char letters[] = "LHVCSQTAZM";
      char L = letters[c];
      if ((L == 'M' || L == 'Z') && (prev == 'M' || prev == 'Z')) L = 'L';  // keep subpaths nonempty
      const bool repeat = L == prev && L != 'Z' && L != 'M' && (rng() & 1);
      std::string a = repeat ? "" : std::string(" ") + L, r = repeat ? "" : std::string(" ") + char(L - 'A' + 'a');
      if (repeat) { a += ","; r += " "; }
      auto pt = [&](const Rational& x, const Rational& y) {
        a += " " + dec(x) + " " + dec(y);
        r += " " + dec(x - cx) + "," + dec(y - cy);
      };
      if (L == 'L' || L == 'T') {
        const Rational x = coord(), y = coord();
        pt(x, y);
        cx = x; cy = y;
      } else if (L == 'M') {
        const Rational x = coord(), y = coord();
        pt(x, y);
        cx = sx = x; cy = sy = y;
      } else if (L == 'H') {
        const Rational x = coord();
        a += " " + dec(x);
        r += " " + dec(x - cx);
        cx = x;
      } else if (L == 'V') {
        const Rational y = coord();
        a += " " + dec(y);
        r += " " + dec(y - cy);
        cy = y;
      } else if (L == 'C' || L == 'S' || L == 'Q') {
        const int n = L == 'C' ? 3 : 2;
        Rational x, y;
        for (int q = 0; q < n; ++q) { x = coord(); y = coord(); pt(x, y); }
        cx = x; cy = y;
      } else if (L == 'A') {
        const ArcShape& s = arcs[rng() % (sizeof arcs / sizeof arcs[0])];
        const bool large = rng() & 1, sweep = rng() & 1;
        const std::string head = " " + std::to_string(s.rx) + " " + std::to_string(s.ry) + " " +
                                 std::to_string(s.rot) + " " + (large ? "1" : "0") + (sweep ? " 1" : " 0");
        a += head;
        r += head;
        pt(cx + R(s.dx), cy + R(s.dy));
        cx = cx + R(s.dx);
        cy = cy + R(s.dy);
      } else {  // Z
        cx = sx; cy = sy;
      }
      abs += a;
      rel += r;
      prev = L;
    }
    SCOPED_TRACE(abs + "\n" + rel);
    std::vector<PathInput> pa, pr;
    try {
      pa = parse_svg_path(abs);
    } catch (const InvalidArgument& e) {
      // a subpath of zero-length segments only (M then Z, say): both spellings must fail alike
      const std::regex column("column [0-9]+");
      EXPECT_EQ(std::regex_replace(test_support::message_of([&] { parse_svg_path(rel); }), column, ""),
                std::regex_replace(std::string(e.what()), column, ""));
      continue;
    }
    pr = parse_svg_path(rel);
    EXPECT_EQ(text_of(pa), text_of(pr));
    ++compared;
  }
  EXPECT_GE(compared, 50);
}

TEST(SvgPath, ImplicitRepetitions) {
  EXPECT_EQ(text_of(parse_svg_path("M 0 0 1 1 2 0")), text_of(parse_svg_path("M 0 0 L 1 1 L 2 0")));
  EXPECT_EQ(text_of(parse_svg_path("m 1 1 2 2 3 3")), text_of(parse_svg_path("M 1 1 l 2 2 l 3 3")));
  EXPECT_EQ(text_of(parse_svg_path("M0 0C1 1 2 2 3 0 4 1 5 1 6 0")),
            text_of(parse_svg_path("M0 0C1 1 2 2 3 0C4 1 5 1 6 0")));
  EXPECT_EQ(text_of(parse_svg_path("M0 0h1 2 3v4 5")), text_of(parse_svg_path("M0 0H1H3H6V4V9")));
  const auto p = parse_svg_path("M 0 0 1 1");
  EXPECT_NE(p[0].labels[0].find("implicit lineto"), std::string::npos) << p[0].labels[0];
}

TEST(SvgPath, ReflectionRules) {
  // S reflects the previous cubic's second control point about the current point.
  auto p = parse_svg_path("M0 0 C 1 2 3 4 5 5 S 9 9 10 10")[0];
  EXPECT_EQ(p.segments[1].points()[1], (std::vector<Rational>{R(7), R(6)}));
  p = parse_svg_path("M0 0 c 1 2 3 4 5 5 s 4 4 5 5")[0];
  EXPECT_EQ(p.segments[1].points()[1], (std::vector<Rational>{R(7), R(6)}));
  // ... and after S as well; after any other command it is the current point.
  p = parse_svg_path("M0 0 S 3 4 5 5 S 9 9 10 10")[0];
  EXPECT_EQ(p.segments[0].points()[1], (std::vector<Rational>{R(0), R(0)}));
  EXPECT_EQ(p.segments[1].points()[1], (std::vector<Rational>{R(7), R(6)}));
  p = parse_svg_path("M0 0 Q 1 2 3 3 S 9 9 10 10")[0];
  EXPECT_EQ(p.segments[1].points()[1], (std::vector<Rational>{R(3), R(3)}));
  // T reflects the previous quadratic's control point; chains of T too.
  p = parse_svg_path("M0 0 Q 1 2 3 3 T 6 6 T 9 5")[0];
  EXPECT_EQ(p.segments[1].points()[1], (std::vector<Rational>{R(5), R(4)}));
  EXPECT_EQ(p.segments[2].points()[1], (std::vector<Rational>{R(7), R(8)}));
  p = parse_svg_path("M0 0 C 1 2 3 4 5 5 T 9 9")[0];
  EXPECT_EQ(p.segments[1].points()[1], (std::vector<Rational>{R(5), R(5)}));
  p = parse_svg_path("M0 0 L 5 5 T 9 9")[0];  // T after L: control = current point
  EXPECT_EQ(p.segments[1].points()[1], (std::vector<Rational>{R(5), R(5)}));
}

TEST(SvgPath, NumberGrammarIsExact) {
  auto p = parse_svg_path("M10-5L.5.5")[0];
  EXPECT_EQ(p.segments[0].points()[0], (std::vector<Rational>{R(10), R(-5)}));
  EXPECT_EQ(p.segments[0].points()[1], (std::vector<Rational>{R(1, 2), R(1, 2)}));
  p = parse_svg_path("M1e1 2E-1L+3.,-0.1e+2")[0];
  EXPECT_EQ(p.segments[0].points()[0], (std::vector<Rational>{R(10), R(1, 5)}));
  EXPECT_EQ(p.segments[0].points()[1], (std::vector<Rational>{R(3), R(-10)}));
  p = parse_svg_path("M1e-0000000001 0e0L2E+000 0")[0];  // leading zeros of exponents
  EXPECT_EQ(p.segments[0].points()[0], (std::vector<Rational>{R(1, 10), R(0)}));
  p = parse_svg_path("M 0.1 0.2 L 0.3 0.7")[0];
  EXPECT_EQ(p.segments[0].points()[1], (std::vector<Rational>{R(3, 10), R(7, 10)}));
  p = parse_svg_path("M\t0\n0\r\fL 1 , 1")[0];
  EXPECT_EQ(p.segments[0].points()[1], (std::vector<Rational>{R(1), R(1)}));
  // Arc flags without separators.
  const auto a = parse_svg_path("M0 0a1 1 0 00 1 1")[0];
  EXPECT_EQ(a.segments.back().points().back(), (std::vector<Rational>{R(1), R(1)}));
  EXPECT_EQ(text_of({a}), text_of(parse_svg_path("M0 0a1,1,0,0,0,1,1")));
}

TEST(SvgPath, ClosepathAndSubpaths) {
  // Z adds the closing line only when needed.
  EXPECT_EQ(parse_svg_path("M0 0 L1 0 L1 1 Z")[0].segments.size(), 3u);
  EXPECT_EQ(parse_svg_path("M0 0 L1 0 L1 1 L0 0 Z")[0].segments.size(), 3u);
  // A command after Z starts a new subpath at the same start; m after z is relative to it.
  auto ps = parse_svg_path("M1 1 L2 1 L2 2 z L 5 5 z m 1 1 l 1 0");
  ASSERT_EQ(ps.size(), 3u);
  EXPECT_EQ(ps[1].segments[0].points()[0], (std::vector<Rational>{R(1), R(1)}));
  EXPECT_EQ(ps[1].segments.size(), 2u);  // L and the closing line
  EXPECT_EQ(ps[2].segments[0].points()[0], (std::vector<Rational>{R(2), R(2)}));
  // The first moveto is absolute even written 'm'; later ones are relative.
  ps = parse_svg_path("m 1 1 l 1 0 m 1 1 l 1 0");
  EXPECT_EQ(ps[1].segments[0].points()[0], (std::vector<Rational>{R(3), R(2)}));
  // "zz": the second closepath adds nothing.
  EXPECT_EQ(parse_svg_path("M0 0 L1 0 L1 1 ZZ").size(), 1u);
}

TEST(SvgPath, ZeroLengthSegmentsDropped) {
  auto p = parse_svg_path("M0 0 L0 0 L1 1 l0 0 h0 v0 C 1 1 1 1 1 1 Q 1 1 1 1 A 2 2 0 0 1 1 1 L 2 2")[0];
  ASSERT_EQ(p.segments.size(), 2u);
  EXPECT_EQ(p.knots, (std::vector<Rational>{R(0), R(1, 2), R(1)}));
  EXPECT_EQ(p.labels[1].substr(0, 10), "segment 2:");
  const std::string m = test_support::message_of([] { parse_svg_path("M0 0 L1 1 M 5 5 L 5 5"); });
  EXPECT_NE(m.find("subpath 2 at column 11 has no segment"), std::string::npos) << m;
  EXPECT_NE(test_support::message_of([] { parse_svg_path("M 1 1"); }).find("subpath 1 at column 1 has no segment"),
            std::string::npos);
}

// --- arcs -------------------------------------------------------------------

struct Ellipse {
  Rational cx, cy, rx, ry;
  int quarter_turns;  // rotation by 90 * quarter_turns degrees
  // cos, sin of the rotation
  Rational cs() const { int k = ((quarter_turns % 4) + 4) % 4; return k == 0 ? R(1) : k == 2 ? R(-1) : R(0); }
  Rational sn() const { int k = ((quarter_turns % 4) + 4) % 4; return k == 1 ? R(1) : k == 3 ? R(-1) : R(0); }
  // The point of the unit circle (c, s) mapped onto the ellipse.
  std::vector<Rational> at(const Rational& c, const Rational& s) const {
    const Rational X = rx * c, Y = ry * s;
    return {cx + cs() * X - sn() * Y, cy + sn() * X + cs() * Y};
  }
  // The implicit equation's value: 1 exactly on the ellipse.
  Rational level(const std::vector<Rational>& p) const {
    const Rational dx = p[0] - cx, dy = p[1] - cy;
    const Rational X = cs() * dx + sn() * dy, Y = -sn() * dx + cs() * dy;
    return X * X / (rx * rx) + Y * Y / (ry * ry);
  }
};

std::string dec_of(const Rational& q) {  // exact decimal text of a rational with denominator 2^a 5^b
  Rational t = q;
  int digits = 0;
  while (!t.is_integer()) { t = t * R(10); ++digits; }
  std::string s = t.num().str();
  const bool neg = s[0] == '-';
  if (neg) s = s.substr(1);
  while (static_cast<int>(s.size()) <= digits) s = "0" + s;
  if (digits) s = s.substr(0, s.size() - digits) + "." + s.substr(s.size() - digits);
  return (neg ? "-" : "") + s;
}

Rational cross(const std::vector<Rational>& o, const std::vector<Rational>& a, const std::vector<Rational>& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

// Arcs between rational points of ellipses with known rational centers: the
// reader must find that ellipse (every evaluated point on it), start and end
// exactly, and go the way the flags say (interior points on the side of the
// chord given by the sweep flag; the large-arc flag picks the center).
TEST(SvgPath, ArcsAreExactConicArcs) {
  std::mt19937_64 rng(90);
  // Rational points of the unit circle ((1 - m^2), 2m) / (1 + m^2), m = a/b,
  // with 1 + m^2 a power of 2 times a power of 5 so that the coordinates are finite decimals.
  std::vector<std::pair<Rational, Rational>> circle = {{R(1), R(0)}, {R(0), R(1)}, {R(-1), R(0)}, {R(0), R(-1)}};
  for (const auto& [a, b] : std::vector<std::pair<long, long>>{{1, 2}, {1, 3}, {1, 7}, {2, 11}, {1, 1}}) {
    const Rational m = R(a, b), d = R(1) + m * m;
    const Rational c = (R(1) - m * m) / d, s = R(2) * m / d;
    for (int sx : {1, -1})
      for (int sy : {1, -1}) circle.push_back({c * R(sx), s * R(sy)});
  }
  int checked = 0;
  for (int it = 0; it < 200; ++it) {
    Ellipse e{R(static_cast<long>(rng() % 41) - 20, 2), R(static_cast<long>(rng() % 41) - 20, 4),
              R(static_cast<long>(rng() % 8) + 1, 2), R(static_cast<long>(rng() % 8) + 1, 5),
              static_cast<int>(rng() % 6) - 2};
    const auto& q1 = circle[rng() % circle.size()];
    const auto& q2 = circle[rng() % circle.size()];
    if (q1 == q2) continue;
    const bool sweep = rng() & 1;
    // unit-circle cross product: > 0 when the positive sweep from q1 to q2 is below 180 degrees
    const Rational cr = q1.first * q2.second - q1.second * q2.first;
    const bool half = cr.is_zero();
    const bool large = half ? bool(rng() & 1) : (sweep ? cr.sign() < 0 : cr.sign() > 0);
    const auto p1 = e.at(q1.first, q1.second), p2 = e.at(q2.first, q2.second);
    const std::string d = "M " + dec_of(p1[0]) + " " + dec_of(p1[1]) + " A " + dec_of(e.rx) + " " + dec_of(e.ry) +
                          " " + std::to_string(90 * e.quarter_turns) + " " + (large ? "1 " : "0 ") +
                          (sweep ? "1 " : "0 ") + dec_of(p2[0]) + " " + dec_of(p2[1]);
    SCOPED_TRACE(d);
    const auto paths = parse_svg_path(d);
    ASSERT_EQ(paths.size(), 1u);
    const auto& segs = paths[0].segments;
    ASSERT_GE(segs.size(), 1u);
    ASSERT_LE(segs.size(), 4u);
    EXPECT_EQ(segs.front().points().front(), p1);
    EXPECT_EQ(segs.back().points().back(), p2);
    // A positive sweep runs to the right of the chord p1 -> p2 (the ellipse
    // is convex and the map to the unit circle keeps orientation); the
    // large arc is the one on the center's side (which center was taken is
    // checked by every point lying on this ellipse).
    const int side = sweep ? -1 : 1;
    if (!half) EXPECT_EQ(cross(p1, p2, {e.cx, e.cy}).sign(), large ? side : -side);
    for (const auto& b : segs) {
      ASSERT_EQ(b.degree(), 2);
      ASSERT_TRUE(b.is_rational());
      for (const Rational& t : {R(0), R(1, 7), R(1, 3), R(1, 2), R(5, 6), R(1)}) {
        const auto x = bezier_point(b, t);
        EXPECT_EQ(e.level(x), R(1)) << t.str();
        if (t == R(1, 2)) EXPECT_EQ(cross(p1, p2, x).sign(), side);
      }
    }
    ++checked;
  }
  EXPECT_GT(checked, 150);
}

TEST(SvgPath, ArcRadiiScaledUpAndDegenerate) {
  // Radii too small: scaled up (F.6.6), the center is the chord's midpoint.
  auto p = parse_svg_path("M 0 0 A 1 2 0 0 1 10 0")[0];
  // lambda = 25/1: rx = 5, ry = 10 about (5, 0)
  Ellipse e{R(5), R(0), R(5), R(10), 0};
  for (const auto& b : p.segments)
    for (const Rational& t : {R(1, 3), R(1, 2), R(3, 4)}) EXPECT_EQ(e.level(bezier_point(b, t)), R(1));
  EXPECT_EQ(p.segments.size(), 2u);
  // Zero radius: the chord.
  p = parse_svg_path("M 0 0 A 0 2 0 0 1 10 5")[0];
  ASSERT_EQ(p.segments.size(), 1u);
  EXPECT_EQ(p.segments[0].degree(), 1);
  // Equal end points: omitted.
  p = parse_svg_path("M 0 0 L 1 0 A 2 2 0 1 1 1 0 L 2 0")[0];
  EXPECT_EQ(p.segments.size(), 2u);
  // Negative radii are taken in absolute value; rotation 450 = 90.
  EXPECT_EQ(text_of(parse_svg_path("M 0 0 A -5 -5 0 0 1 8 0")), text_of(parse_svg_path("M 0 0 A 5 5 0 0 1 8 0")));
  EXPECT_EQ(text_of(parse_svg_path("M 0 0 A 10 5 450 0 1 0 16")), text_of(parse_svg_path("M 0 0 A 10 5 90 0 1 0 16")));
}

TEST(SvgPath, ArcsThatWouldNeedApproximationAreRefused) {
  std::string m = test_support::message_of([] { parse_svg_path("M 0 0 L 1 0 A 5 5 45 0 1 9 0"); });
  EXPECT_NE(m.find("arc 1 at column 13"), std::string::npos) << m;
  EXPECT_NE(m.find("45 degrees is not a multiple of 90"), std::string::npos) << m;
  EXPECT_NE(m.find("does not approximate"), std::string::npos) << m;
  m = test_support::message_of([] { parse_svg_path("M 0 0 A 5 5 0 0 1 8 0 a 5 5 0 0 1 1 0"); });
  EXPECT_NE(m.find("arc 2 at column 23: its center is irrational (the radicand 99 of"), std::string::npos) << m;
  EXPECT_NE(m.find("does not approximate"), std::string::npos) << m;
}

TEST(SvgPath, ParseErrorsWithColumns) {
  struct Case { const char* d; std::size_t column; const char* words; };
  const Case cases[] = {
      {"L 1 1", 1, "must start with a moveto"},
      {"M 1", 4, "ends where a number"},
      {"M 1 2 X 3", 7, "unexpected 'X'"},
      {"M 1 2 L 3 4 Z 3", 15, "takes no parameters"},
      {"M 1,,2", 5, "where a number"},
      {"M 1 2,", 7, "must be followed by a number"},
      {"M,1 2", 2, "where a number"},
      {"M 0 0 A 1 1 0 2 0 3 3", 15, "arc flag"},
      {"M 0 0 A 1 1 0 1", 16, "ends where an arc flag"},
      {"M 1e 2", 5, "malformed exponent"},
      {"M 1e1000 0", 3, "exponent of 1000 or more"},
      {"M 1 2 L . 3", 9, "where a number"},
      {"M 1 2 L 3 4 -", 13, "unexpected '-'"},
  };
  for (const auto& c : cases) {
    try {
      parse_svg_path(c.d);
      ADD_FAILURE() << "no ParseError for " << c.d;
    } catch (const ParseError& e) {
      EXPECT_EQ(e.column(), c.column) << c.d << " -> " << e.what();
      EXPECT_NE(std::string(e.what()).find(c.words), std::string::npos) << c.d << " -> " << e.what();
    }
  }
  EXPECT_THROW(parse_svg_path(""), InvalidArgument);
  EXPECT_THROW(parse_svg_path(" \n "), InvalidArgument);
  SvgLimits lim;
  lim.max_length = 10;
  EXPECT_NE(test_support::message_of([&] { parse_svg_path("M 0 0 L 1 1", lim); }).find("more than the limit of 10"),
            std::string::npos);
  lim = SvgLimits{};
  lim.max_segments = 3;
  EXPECT_NO_THROW(parse_svg_path("M 0 0 1 1 2 2 3 3", lim));
  EXPECT_NE(test_support::message_of([&] { parse_svg_path("M 0 0 1 1 2 2 3 3 4 4", lim); }).find("more than 3 segments"),
            std::string::npos);
}

// Random edits of valid paths: every outcome is a result or a uniparam::Error
// (no crash, no other exception); a result keeps the PathInput invariants.
TEST(SvgPath, MutatedPathsGiveResultsOrErrors) {
  const std::vector<std::string> seeds = {
      "M 0 0 L 10 0 H 20 V 10 C 20 20 30 20 30 10 S 40 0 40 10 Q 50 20 60 10 T 80 10 A 5 5 0 0 1 88 10 Z",
      "m1.5.5l-2-3.25e1zm4 4a10 5 90 1 0 0 16c1,2,3,4,5,6s1 1 2 2q3 3 4 4t5 5h1v1z",
      "M10-5L.5.5A3 4 180 10 2 2"};
  const std::string alphabet = "MmLlHhVvCcSsQqTtZzAa0123456789.-+eE, \t";
  std::mt19937_64 rng(404);
  const int results = test_support::mutated_results(seeds, alphabet, 4, rng, 3000, [](const std::string& d) {
    for (const auto& p : parse_svg_path(d)) {
      ASSERT_FALSE(p.segments.empty()) << d;
      ASSERT_EQ(p.knots.size(), p.segments.size() + 1) << d;
      ASSERT_EQ(p.labels.size(), p.segments.size()) << d;
      for (std::size_t k = 0; k + 1 < p.segments.size(); ++k)
        ASSERT_EQ(p.segments[k].points().back(), p.segments[k + 1].points().front()) << d;
    }
  });
  EXPECT_GT(results, 100);
}

}  // namespace
}  // namespace uniparam
