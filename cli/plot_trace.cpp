// What `uniparam plot` draws, computed: the trace of the curve (sampled
// adaptively in its own geometry), the dense speed samples and the
// breakpoints, all projected to the plane.
#include <algorithm>
#include <cmath>
#include <vector>

#include "output.hpp"
#include "plot_view.hpp"

namespace uniparam::cli::plot {

namespace {

std::vector<double> mids(const std::vector<Ball>& v) {
  std::vector<double> o;
  for (const auto& b : v) o.push_back(mid_double(b));
  return o;
}

// ---- The trace: the curve itself, sampled in its own geometry ----------
//
// Equal steps of t can miss most of a curve (a circle with weights [1, 8e40,
// 1e82] runs its whole arc for t below 1e-39). The trace starts from seeds
// spread in t and in the curve's geometry (t_j = j/64 and r(j/64), r the
// uniformizing map), then bisects each piece [a, b] in t until the chord
// p(a)p(b) is at most kChordPx pixels long and p at a quarter, half and three
// quarters of the piece lies within kFlatPx pixels of it. Parameters are exact
// dyadic numbers (so pieces near t = 1 stay resolved), and each point is
// evaluated with the precision raised until its ball is below kEvalPx pixels.

constexpr double kPanelPx = 330;   // the curve panels' size
constexpr double kChordPx = 8;     // longest segment of the trace
constexpr double kFlatPx = 0.2;    // largest distance of a tested point from its segment
constexpr double kEvalPx = 0.02;   // accuracy of a trace point
constexpr int kMaxBisections = 1100;
constexpr long kMaxTraceEvaluations = 200000;

// The midpoint of an exact ball, as an exact ball clamped to [0, 1].
Ball exact_unit(const Ball& b) {
  Ball t;
  arf_set(arb_midref(t.get()), arb_midref(b.get()));
  if (arf_sgn(arb_midref(t.get())) < 0) arf_zero(arb_midref(t.get()));
  if (arf_cmp_si(arb_midref(t.get()), 1) > 0) arf_one(arb_midref(t.get()));
  return t;
}

Ball exact_middle(const Ball& a, const Ball& b) {
  Ball m;
  arb_add(m.get(), a.get(), b.get(), ARF_PREC_EXACT);
  arb_mul_2exp_si(m.get(), m.get(), -1);
  return m;
}

// p(t) projected, for an exact t, with balls below `tol` (data units; for
// tol <= 0 below 2^-40 of the point's size). False when no finite point
// came out within max_prec.
bool trace_point(const PlotView& pv, const Projection& proj, const Ball& t, double tol, long max_prec, Point& out) {
  const long bits = static_cast<long>(arf_bits(arb_midref(t.get())));
  for (long prec = bits + 64;; prec *= 2) {
    const std::vector<Ball> v = pv.point(t, prec);
    std::vector<double> m;
    double rad = 0, size = 0;
    bool finite = true;
    for (const auto& b : v) {
      finite = finite && b.is_finite();
      m.push_back(mid_double(b));
      rad = std::max(rad, mag_get_d(arb_radref(b.get())));
      size = std::max(size, std::fabs(m.back()));
    }
    out = proj(m);
    // a projection adds at most 1.7 x the largest radius (isometric Y)
    const bool good = finite && std::isfinite(out.first) && std::isfinite(out.second) &&
                      1.7 * rad <= (tol > 0 ? tol : std::ldexp(size, -40));
    if (good) return true;
    if (prec >= std::max(max_prec, bits + 64)) return finite && std::isfinite(out.first) && std::isfinite(out.second);
  }
}

double segment_distance(Point p, Point a, Point b) {
  const double dx = b.first - a.first, dy = b.second - a.second;
  const double l2 = dx * dx + dy * dy;
  double u = l2 > 0 ? ((p.first - a.first) * dx + (p.second - a.second) * dy) / l2 : 0;
  u = std::min(1.0, std::max(0.0, u));
  return std::hypot(p.first - a.first - u * dx, p.second - a.second - u * dy);
}

/// The trace of c (projected) for the curve panels: a polyline from p(0) to
/// p(1) whose segments are at most kChordPx pixels long and within about
/// kFlatPx pixels of the curve at the scale of the panels (see above).
/// \pre r was computed for c. Checks the time budget (BudgetExceeded).
std::vector<Point> trace_curve(const PlotView& c, const Projection& proj, long max_prec) {
  // Seeds: equal steps of t and of s (through r), sorted, without repeats.
  std::vector<Ball> seeds;
  const int n = 64;
  for (int j = 0; j <= n; ++j) seeds.push_back(Ball(Rational(j, n), 64));  // dyadic: exact
  for (int j = 1; j < n; ++j) {
    check_time_budget();
    try {
      const Ball t = c.r(Ball(Rational(j, n), 128), 128);
      if (arf_is_finite(arb_midref(t.get()))) seeds.push_back(exact_unit(t));
    } catch (const BudgetExceeded&) {
      throw;
    } catch (const Error&) {
      // a seed is only a starting point: the equal steps of t remain
    }
  }
  std::sort(seeds.begin(), seeds.end(),
            [](const Ball& a, const Ball& b) { return arf_cmp(arb_midref(a.get()), arb_midref(b.get())) < 0; });
  seeds.erase(std::unique(seeds.begin(), seeds.end(),
                          [](const Ball& a, const Ball& b) { return arf_equal(arb_midref(a.get()), arb_midref(b.get())); }),
              seeds.end());
  std::vector<Ball> ts;
  std::vector<Point> ps;
  Range xr, yr;
  for (const auto& t : seeds) {
    Point p;
    if (!trace_point(c, proj, t, 0, max_prec, p)) continue;
    ts.push_back(t);
    ps.push_back(p);
    xr.add(p.first);
    yr.add(p.second);
  }
  if (ps.size() < 2) return ps;
  double extent = std::max(xr.hi - xr.lo, yr.hi - yr.lo);
  if (!(extent > 0)) extent = std::max({1.0, std::fabs(xr.lo), std::fabs(yr.lo)});
  const double px = extent * 1.12 / kPanelPx;  // data per pixel (the panels pad by 6% a side)
  const double chord = kChordPx * px, flat = kFlatPx * px, tol = kEvalPx * px;

  struct Piece {
    Ball ta, tb;
    Point pa, pb;
    int depth = 0;
    bool has_mid = false;
    Ball tm;
    Point pm;
  };
  std::vector<Point> out = {ps.front()};
  long evaluations = 0;
  std::vector<Piece> stack;
  for (std::size_t i = ps.size() - 1; i > 0; --i) stack.push_back({ts[i - 1], ts[i], ps[i - 1], ps[i], 0, false, {}, {}});
  while (!stack.empty()) {
    Piece q = std::move(stack.back());
    stack.pop_back();
    check_time_budget();
    if (q.depth >= kMaxBisections || evaluations >= kMaxTraceEvaluations) {
      out.push_back(q.pb);
      continue;
    }
    if (!q.has_mid) {
      q.tm = exact_middle(q.ta, q.tb);
      ++evaluations;
      if (!trace_point(c, proj, q.tm, tol, max_prec, q.pm)) { out.push_back(q.pb); continue; }
    }
    const Ball t1 = exact_middle(q.ta, q.tm), t3 = exact_middle(q.tm, q.tb);
    Point p1, p3;
    evaluations += 2;
    if (!trace_point(c, proj, t1, tol, max_prec, p1) || !trace_point(c, proj, t3, tol, max_prec, p3)) {
      out.push_back(q.pb);
      continue;
    }
    const bool done = std::hypot(q.pb.first - q.pa.first, q.pb.second - q.pa.second) <= chord &&
                      segment_distance(p1, q.pa, q.pb) <= flat && segment_distance(q.pm, q.pa, q.pb) <= flat &&
                      segment_distance(p3, q.pa, q.pb) <= flat;
    if (done) {
      out.push_back(q.pb);
      continue;
    }
    stack.push_back({q.tm, q.tb, q.pm, q.pb, q.depth + 1, true, t3, p3});
    stack.push_back({q.ta, q.tm, q.pa, q.pm, q.depth + 1, true, t1, p1});
  }
  return out;
}

}  // namespace

PlotData collect(const PlotView& v, const Projection& proj, long max_prec) {
  const long prec = 64;
  PlotData d;
  d.trace = trace_curve(v, proj, max_prec);
  const int dense = 800;
  for (int j = 0; j <= dense; ++j) {
    const Ball t(Rational(j, dense), prec);
    d.speed_before.push_back({static_cast<double>(j) / dense, mid_double(v.speed_before(t, prec))});
  }
  for (const auto& p : v.samples.before) d.before.push_back(proj(mids(p.point)));
  for (const auto& p : v.samples.after) d.after.push_back(proj(mids(p.point)));
  const std::size_t N = v.joints.size() - 1;
  for (std::size_t i = 1; i < N; ++i) {
    const Ball& t = v.joints[i].second;
    d.breakpoints.push_back(proj(mids(v.point(t, prec))));
    d.breakpoint_speeds.push_back({mid_double(t), mid_double(v.speed_before(t, prec))});
    d.joints_s.push_back(mid_double(v.joints[i].first));
  }
  // p o r's speed piece by piece, so that jumps at C0 joints show; interior
  // piece ends are moved inside by 1e-9 of the piece so that only one piece
  // is evaluated there.
  const int per_piece = std::max(24, 800 / static_cast<int>(N));
  for (std::size_t i = 0; i < N; ++i) {
    const double a = mid_double(v.joints[i].first), b = mid_double(v.joints[i + 1].first);
    const double ia = i == 0 ? 0 : 1e-9 * (b - a), ib = i + 1 == N ? 0 : 1e-9 * (b - a);
    std::vector<Point> piece;
    for (int j = 0; j <= per_piece; ++j) {
      double s = a + ia + (b - ib - a - ia) * j / per_piece;
      s = std::min(1.0, std::max(0.0, s));
      Ball sb;
      arb_set_d(sb.get(), s);  // s is the exact double; only a drawing position
      piece.push_back({s, mid_double(v.speed_after(sb, prec))});
    }
    d.speed_after.push_back(std::move(piece));
  }
  return d;
}

}  // namespace uniparam::cli::plot
