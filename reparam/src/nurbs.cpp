#include "uniparam/reparam/nurbs.hpp"

#include <algorithm>
#include <tuple>
#include <type_traits>
#include <stdexcept>
#include <string>

#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/poly.hpp"
#include "uniparam/core/ratfunc.hpp"
#include "moebius_map.hpp"

namespace uniparam {

namespace {

// The two number types the construction runs in: exact rationals and balls.
struct QField {
  using T = Rational;
  T q(const Rational& x) const { return x; }
  T add(const T& a, const T& b) const { return a + b; }
  T sub(const T& a, const T& b) const { return a - b; }
  T mul(const T& a, const T& b) const { return a * b; }
  T div(const T& a, const T& b) const { return a / b; }
  bool positive(const T& a) const { return a.sign() > 0; }
  bool negative(const T& a) const { return a.sign() < 0; }
  bool same(const T& a, const T& b) const { return a == b; }
};

struct BField {
  using T = Ball;
  long prec;
  T q(const Rational& x) const { return Ball(x, prec); }
  T add(const T& a, const T& b) const { Ball r; arb_add(r.get(), a.get(), b.get(), prec); return r; }
  T sub(const T& a, const T& b) const { Ball r; arb_sub(r.get(), a.get(), b.get(), prec); return r; }
  T mul(const T& a, const T& b) const { Ball r; arb_mul(r.get(), a.get(), b.get(), prec); return r; }
  T div(const T& a, const T& b) const { Ball r; arb_div(r.get(), a.get(), b.get(), prec); return r; }
  bool positive(const T& a) const { return a.certainly_positive(); }
  bool negative(const T& a) const { return a.certainly_negative(); }
  bool same(const T& a, const T& b) const { return arb_overlaps(a.get(), b.get()); }
};

// A rational Bezier segment over [sa, sb] in homogeneous form: h[j] is
// (w_j x_j1, ..., w_j x_jn, w_j), j = 0..d. `piece` is the Moebius piece.
template <class T>
struct Segment {
  T sa, sb;
  std::vector<std::vector<T>> h;
  std::size_t piece;
};

// The homogeneous numerators (X_1, ..., X_n, W) of c's components over their
// least common denominator W (so p = X / W, W with no zero in [0, 1]).
std::vector<Poly> homogeneous(const Curve& c) {
  Poly W(1);
  for (const auto& f : c.components()) {
    const Poly d = f.den();
    W = W * divexact(d, gcd(W, d));
  }
  std::vector<Poly> H;
  for (const auto& f : c.components()) H.push_back(f.num() * divexact(W, f.den()));
  H.push_back(W);
  return H;
}

long homogeneous_degree(const std::vector<Poly>& H) {
  long d = 0;
  for (const auto& p : H) d = std::max(d, p.degree());
  return d;
}

Rational binom(long n, long k) {
  Integer r;
  fmpz_bin_uiui(r.get(), static_cast<unsigned long>(n), static_cast<unsigned long>(k));
  return Rational(r);
}

// The Bernstein coefficients (degree d) of every H_k on [ta, tb], each
// multiplied by (1 - a)^j a^(d - j): the homogeneous control points of
// (X, W) o r on its piece in the local parameter u.
template <class F>
std::vector<std::vector<typename F::T>> piece_control(const F& f, const std::vector<Poly>& H, long d,
                                                      const typename F::T& ta, const typename F::T& tb,
                                                      const typename F::T& a) {
  using T = typename F::T;
  const T h = f.sub(tb, ta);
  const std::size_t m = H.size();
  std::vector<std::vector<T>> out(static_cast<std::size_t>(d + 1), std::vector<T>(m, f.q(Rational(0))));
  for (std::size_t k = 0; k < m; ++k) {
    // q(tau) = H_k(ta + h tau) by Horner on the coefficient vector
    std::vector<T> q(static_cast<std::size_t>(d + 1), f.q(Rational(0)));
    for (long i = d; i >= 0; --i) {
      // q <- q * (ta + h tau) + c_i
      std::vector<T> next(static_cast<std::size_t>(d + 1), f.q(Rational(0)));
      for (long e = 0; e <= d; ++e) {
        next[e] = f.add(next[e], f.mul(q[e], ta));
        if (e + 1 <= d) next[e + 1] = f.add(next[e + 1], f.mul(q[e], h));
      }
      next[0] = f.add(next[0], f.q(Rational(H[k].coeff(i))));
      q = std::move(next);
    }
    for (long j = 0; j <= d; ++j) {
      T b = f.q(Rational(0));
      for (long i = 0; i <= j; ++i) b = f.add(b, f.mul(f.q(binom(j, i) / binom(d, i)), q[i]));
      out[j][k] = b;
    }
  }
  const T one = f.q(Rational(1));
  const T oma = f.sub(one, a);
  for (long j = 0; j <= d; ++j) {
    T s = one;
    for (long e = 0; e < j; ++e) s = f.mul(s, oma);
    for (long e = 0; e < d - j; ++e) s = f.mul(s, a);
    for (auto& x : out[j]) x = f.mul(x, s);
  }
  return out;
}

// Splits a segment at u = 1/2 (de Casteljau on the homogeneous points).
template <class F>
std::pair<Segment<typename F::T>, Segment<typename F::T>> halve(const F& f, const Segment<typename F::T>& s) {
  using T = typename F::T;
  const T half = f.q(Rational(1, 2));
  const std::size_t d = s.h.size() - 1;
  Segment<T> L{s.sa, f.mul(f.add(s.sa, s.sb), half), {}, s.piece};
  Segment<T> R{L.sb, s.sb, {}, s.piece};
  std::vector<std::vector<T>> cur = s.h;
  L.h.push_back(cur.front());
  R.h.push_back(cur.back());
  for (std::size_t level = 1; level <= d; ++level) {
    std::vector<std::vector<T>> nxt;
    for (std::size_t j = 0; j + 1 < cur.size(); ++j) {
      std::vector<T> v;
      for (std::size_t k = 0; k < cur[j].size(); ++k) v.push_back(f.mul(f.add(cur[j][k], cur[j + 1][k]), half));
      nxt.push_back(v);
    }
    cur = std::move(nxt);
    L.h.push_back(cur.front());
    R.h.push_back(cur.back());
  }
  std::reverse(R.h.begin(), R.h.end());
  return {L, R};
}

// The same segment with its degree raised by one (homogeneous points:
// h'_i = i/(d+1) h_{i-1} + (1 - i/(d+1)) h_i).
template <class F>
void elevate(const F& f, Segment<typename F::T>& s) {
  using T = typename F::T;
  const long d = static_cast<long>(s.h.size()) - 1;
  std::vector<std::vector<T>> h;
  h.push_back(s.h.front());
  for (long i = 1; i <= d; ++i) {
    const T a = f.q(Rational(i, d + 1)), b = f.q(Rational(d + 1 - i, d + 1));
    std::vector<T> v;
    for (std::size_t k = 0; k < s.h[i].size(); ++k) v.push_back(f.add(f.mul(a, s.h[i - 1][k]), f.mul(b, s.h[i][k])));
    h.push_back(std::move(v));
  }
  h.push_back(s.h.back());
  s.h = std::move(h);
}

template <class F>
bool weights_positive(const F& f, const Segment<typename F::T>& s) {
  for (const auto& v : s.h)
    if (!f.positive(v.back())) return false;
  return true;
}

// Subdivides `s` until every weight is positive (after fixing the sign of the
// homogeneous form by its first weight), appending the pieces to `out`.
template <class F>
void positive_segments(const F& f, Segment<typename F::T> s, std::vector<Segment<typename F::T>>& out,
                       std::size_t& subdivided) {
  using T = typename F::T;
  if (f.negative(s.h.front().back()))
    for (auto& v : s.h)
      for (auto& x : v) x = f.sub(f.q(Rational(0)), x);
  else if (!f.positive(s.h.front().back()))
    throw BudgetExceeded("the signs of the NURBS weights could not be certified at the working precision: raise --digits");
  std::vector<Segment<T>> todo{s};
  std::vector<Segment<T>> done;
  const std::size_t limit = 4096;
  bool split = false;
  while (!todo.empty()) {
    check_time_budget();
    Segment<T> cur = todo.back();
    todo.pop_back();
    if (weights_positive(f, cur)) { done.push_back(cur); continue; }
    if (done.size() + todo.size() + 2 > limit)
      throw BudgetExceeded("a NURBS piece needs more than 4096 segments for positive weights");
    auto [L, R] = halve(f, cur);
    split = true;
    todo.push_back(R);
    todo.push_back(L);
  }
  if (split) subdivided += done.size();
  for (auto& d : done) out.push_back(std::move(d));
}

// Joins the segments into one NURBS: weights of segment 0 scaled to w_0 = 1,
// of each next segment to agree with the previous segment's last weight.
template <class F>
void assemble(const F& f, std::vector<Segment<typename F::T>>& segs, long d, std::vector<typename F::T>& knots,
              std::vector<std::vector<typename F::T>>& points, std::vector<typename F::T>& weights) {
  using T = typename F::T;
  T prev_w = f.q(Rational(1));
  for (std::size_t i = 0; i < segs.size(); ++i) {
    auto& s = segs[i];
    const T lambda = f.div(prev_w, s.h.front().back());
    for (auto& v : s.h)
      for (auto& x : v) x = f.mul(x, lambda);
    for (std::size_t j = 0; j < s.h.size(); ++j) {
      const T w = s.h[j].back();
      std::vector<T> p;
      for (std::size_t k = 0; k + 1 < s.h[j].size(); ++k) p.push_back(f.div(s.h[j][k], w));
      if (i > 0 && j == 0) {
        // the joint: the same point as the previous segment's last one
        for (std::size_t k = 0; k < p.size(); ++k)
          if (!f.same(p[k], points.back()[k]))
            throw std::logic_error("the NURBS segments of p o r do not meet at a joint");
        continue;
      }
      points.push_back(p);
      weights.push_back(w);
    }
    prev_w = s.h.back().back();
  }
  for (long e = 0; e <= d; ++e) knots.push_back(segs.front().sa);
  for (std::size_t i = 1; i < segs.size(); ++i)
    for (long e = 0; e < d; ++e) knots.push_back(segs[i].sa);
  for (long e = 0; e <= d; ++e) knots.push_back(segs.back().sb);
}

// Bernstein evaluation of one segment (points P, weights w) at local u.
template <class F>
std::vector<typename F::T> eval_segment(const F& f, const std::vector<std::vector<typename F::T>>& P,
                                        const std::vector<typename F::T>& w, std::size_t first, long d,
                                        const typename F::T& u) {
  using T = typename F::T;
  const T one = f.q(Rational(1));
  const T omu = f.sub(one, u);
  const std::size_t n = P[first].size();
  std::vector<T> num(n, f.q(Rational(0)));
  T den = f.q(Rational(0));
  for (long j = 0; j <= d; ++j) {
    T b = f.q(binom(d, j));
    for (long e = 0; e < j; ++e) b = f.mul(b, u);
    for (long e = 0; e < d - j; ++e) b = f.mul(b, omu);
    const T bw = f.mul(b, w[first + j]);
    den = f.add(den, bw);
    for (std::size_t k = 0; k < n; ++k) num[k] = f.add(num[k], f.mul(bw, P[first + j][k]));
  }
  for (auto& x : num) x = f.div(x, den);
  return num;
}

// t = r(s) on Moebius piece i, exactly.
Rational moebius_exact(const MoebiusResult& r, std::size_t i, const Rational& s) {
  const Rational& ta = r.exact->T[i];
  const Rational& tb = r.exact->T[i + 1];
  const Rational& a = r.exact->alpha[i];
  const Rational u = (s - r.exact->S[i]) / (r.exact->S[i + 1] - r.exact->S[i]);
  Rational x;
  detail::moebius_alpha_map(detail::RationalMapArith{}, &x, nullptr, &u, &a);
  return ta + (tb - ta) * x;
}

void fill_balls_from_exact(Nurbs& n, long prec) {
  for (const auto& k : n.knots_exact) n.knots.emplace_back(k, prec);
  for (const auto& p : n.points_exact) {
    std::vector<Ball> v;
    for (const auto& x : p) v.emplace_back(x, prec);
    n.points.push_back(v);
  }
  for (const auto& w : n.weights_exact) n.weights.emplace_back(w, prec);
}

bool overlaps(const std::vector<Ball>& a, const std::vector<Ball>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (!arb_overlaps(a[k].get(), b[k].get())) return false;
  return true;
}

[[noreturn]] void internal(const std::string& what) {
  throw std::logic_error("the NURBS of p o r differs from p(r(s)) " + what);
}

// p(t), exactly.
std::vector<Rational> exact_point(const Curve& c, const Rational& t) {
  std::vector<Rational> v;
  for (const auto& x : c.components()) v.push_back(x(t));
  return v;
}

// The self-check of an exact NURBS: n(s) equals expected(segment, s) =
// p(r(s)) exactly at s = sa + (sb - sa) q / 4, q = 0..4, of every segment.
template <class Expected>
void check_exact_nurbs(const Nurbs& n, const std::vector<Segment<Rational>>& segs, Expected expected) {
  for (const auto& s : segs) {
    check_time_budget();
    for (long q = 0; q <= 4; ++q) {
      const Rational sv = s.sa + (s.sb - s.sa) * Rational(q, 4);
      if (nurbs_eval(n, sv) != expected(s, sv)) internal("at s = " + sv.str());
    }
  }
}

// The self-check of a ball NURBS: n(s) overlaps expected(s), an enclosure of
// p(r(s)), at the same five points of every segment (the ends taken as they
// are, every point clamped to [0, 1]).
template <class Expected>
void check_ball_nurbs(const BField& f, const Nurbs& n, const std::vector<Segment<Ball>>& segs, long prec,
                      Expected expected) {
  for (const auto& s : segs) {
    check_time_budget();
    for (long q = 0; q <= 4; ++q) {
      Ball sv = f.add(s.sa, f.mul(f.sub(s.sb, s.sa), f.q(Rational(q, 4))));
      if (q == 0) sv = s.sa;
      if (q == 4) sv = s.sb;
      clamp_unit(sv.get(), prec);
      if (!overlaps(nurbs_eval(n, sv, prec), expected(sv))) internal("at s = " + sv.str(10));
    }
  }
}

}  // namespace

// Index in the knot vector of the start of segment i (i = 0..segments; the
// end of the last segment for i = segments).
static std::size_t break_index(const Nurbs& n, std::size_t i) { return i == 0 ? 0 : static_cast<std::size_t>(n.degree) * i + 1; }

std::vector<Ball> Nurbs::breaks() const {
  std::vector<Ball> b;
  for (std::size_t i = 0; i <= segments; ++i) b.push_back(knots[break_index(*this, i)]);
  return b;
}

Nurbs moebius_nurbs(const Curve& c, const MoebiusResult& r, long prec) {
  // A balanced map r = m o r_q (MoebiusResult::balanced): p o r is q o r_q
  // exactly, and q's pieces are free of m's extreme parameters.
  if (r.balanced) return moebius_nurbs(r.balanced->curve->q, *r.balanced->on, prec);
  const std::vector<Poly> H = homogeneous(c);
  const long d = homogeneous_degree(H);
  Nurbs n;
  n.degree = d;
  n.dimension = c.dimension();
  const std::size_t N = r.pieces();
  if (r.exact.has_value()) {
    const QField f;
    std::vector<Segment<Rational>> segs;
    for (std::size_t i = 0; i < N; ++i) {
      check_time_budget();
      Segment<Rational> s{r.exact->S[i], r.exact->S[i + 1],
                          piece_control(f, H, d, r.exact->T[i], r.exact->T[i + 1], r.exact->alpha[i]), i};
      positive_segments(f, s, segs, n.subdivided);
    }
    assemble(f, segs, d, n.knots_exact, n.points_exact, n.weights_exact);
    n.kind = Nurbs::Kind::Exact;
    n.segments = segs.size();
    fill_balls_from_exact(n, prec);
    check_exact_nurbs(n, segs, [&](const Segment<Rational>& seg, const Rational& sv) {
      return exact_point(c, moebius_exact(r, seg.piece, sv));
    });
    return n;
  }
  const BField f{prec};
  std::vector<Segment<Ball>> segs;
  for (std::size_t i = 0; i < N; ++i) {
    check_time_budget();
    Segment<Ball> s{r.S[i], r.S[i + 1],
                    piece_control(f, H, d, r.T[i].t.to_ball(prec), r.T[i + 1].t.to_ball(prec), r.alpha[i]), i};
    positive_segments(f, s, segs, n.subdivided);
  }
  assemble(f, segs, d, n.knots, n.points, n.weights);
  n.kind = Nurbs::Kind::Balls;
  n.segments = segs.size();
  check_ball_nurbs(f, n, segs, prec, [&](const Ball& sv) { return eval_point(c, r, sv, prec); });
  return n;
}

Nurbs composite_nurbs(const CompositeCurve& c, const CompositeMap& m, long prec) {
  const std::size_t M = c.size();
  std::vector<const MoebiusResult*> parts;
  std::vector<const Curve*> curves;  // a balanced part's q o r_q is p o r (moebius_nurbs)
  std::vector<std::vector<Poly>> H;
  long D = 1;
  bool exact = true;
  for (std::size_t j = 0; j < M; ++j) {
    const MoebiusResult* r = m.parts()[j].moebius_result();
    if (!r)
      throw InvalidArgument(c.label(j) + ": its map is not a Moebius map, so p o r is not a NURBS curve there");
    parts.push_back(r->balanced ? r->balanced->on.get() : r);
    curves.push_back(r->balanced ? &r->balanced->curve->q : &c.segment(j));
    exact = exact && r->exact.has_value();
    H.push_back(homogeneous(*curves.back()));
    D = std::max(D, homogeneous_degree(H.back()));
  }
  for (const Joint& jt : joints(c, 64))
    if (!jt.continuous)
      throw InvalidArgument("the curve jumps at joint " + std::to_string(jt.index) +
                            " (the segments do not meet): one NURBS curve cannot carry a jump");
  Nurbs n;
  n.degree = D;
  n.dimension = c.dimension();
  // Which (segment, piece) each NURBS segment comes from.
  std::vector<std::pair<std::size_t, std::size_t>> origin;
  auto build = [&](const auto& f, auto& segs, auto global_s, auto piece_data) {
    for (std::size_t j = 0; j < M; ++j) {
      const long d = homogeneous_degree(H[j]);
      for (std::size_t i = 0; i < parts[j]->pieces(); ++i) {
        check_time_budget();
        auto [ta, tb, a] = piece_data(*parts[j], i);
        typename std::decay_t<decltype(segs)>::value_type s{global_s(j, i), global_s(j, i + 1),
                                                            piece_control(f, H[j], d, ta, tb, a), origin.size()};
        origin.emplace_back(j, i);
        for (long e = d; e < D; ++e) elevate(f, s);
        positive_segments(f, s, segs, n.subdivided);
      }
    }
  };
  const BField bf{prec};
  if (exact) {
    const QField f;
    std::vector<Segment<Rational>> segs;
    build(f, segs,
          [&](std::size_t j, std::size_t i) {
            return m.S()[j] + (m.S()[j + 1] - m.S()[j]) * parts[j]->exact->S[i];
          },
          [](const MoebiusResult& r, std::size_t i) {
            return std::make_tuple(r.exact->T[i], r.exact->T[i + 1], r.exact->alpha[i]);
          });
    assemble(f, segs, D, n.knots_exact, n.points_exact, n.weights_exact);
    n.kind = Nurbs::Kind::Exact;
    n.segments = segs.size();
    fill_balls_from_exact(n, prec);
    check_exact_nurbs(n, segs, [&](const Segment<Rational>& seg, const Rational& sv) {
      const auto [j, i] = origin[seg.piece];
      return exact_point(*curves[j], moebius_exact(*parts[j], i, (sv - m.S()[j]) / (m.S()[j + 1] - m.S()[j])));
    });
    return n;
  }
  std::vector<Segment<Ball>> segs;
  build(bf, segs,
        [&](std::size_t j, std::size_t i) {
          const Ball& loc = parts[j]->S[i];
          return bf.add(bf.q(m.S()[j]), bf.mul(bf.q(m.S()[j + 1] - m.S()[j]), loc));
        },
        [&](const MoebiusResult& r, std::size_t i) {
          return std::make_tuple(r.T[i].t.to_ball(prec), r.T[i + 1].t.to_ball(prec), r.alpha[i]);
        });
  // The ends exactly 0 and 1.
  segs.front().sa = Ball(0);
  segs.back().sb = Ball(1);
  assemble(bf, segs, D, n.knots, n.points, n.weights);
  n.kind = Nurbs::Kind::Balls;
  n.segments = segs.size();
  check_ball_nurbs(bf, n, segs, prec, [&](const Ball& sv) { return c.eval(m.eval_r(c, sv, prec), prec); });
  return n;
}

Nurbs bezier_nurbs(const BezierCurve& b, const BezierResult& r, long prec) {
  Nurbs n;
  n.degree = b.degree();
  n.dimension = b.dimension();
  n.segments = 1;
  for (long e = 0; e <= n.degree; ++e) n.knots_exact.push_back(Rational(0));
  for (long e = 0; e <= n.degree; ++e) n.knots_exact.push_back(Rational(1));
  n.points_exact = b.points();
  for (const auto& k : n.knots_exact) n.knots.emplace_back(k, prec);
  for (const auto& p : n.points_exact) {
    std::vector<Ball> v;
    for (const auto& x : p) v.emplace_back(x, prec);
    n.points.push_back(v);
  }
  if (r.exact) {
    n.kind = Nurbs::Kind::Surd;
    n.weights_surd = r.weights_exact;
    for (const auto& w : r.weights_exact) n.weights.push_back(w.to_ball(prec));
  } else {
    n.kind = Nurbs::Kind::Balls;
    n.weights = r.weights;
  }
  for (const auto& w : n.weights)
    if (!w.certainly_positive())
      throw BudgetExceeded("the signs of the NURBS weights could not be certified at the working precision: raise --digits");
  // the check against p(r(s)), r(s) = (1 - a) s / ((1 - a) s + a (1 - s))
  const Curve c = b.to_curve();
  const Ball a = r.exact ? r.alpha_exact->to_ball(prec) : r.alpha;
  for (long q = 0; q <= 8; ++q) {
    const Ball s(Rational(q, 8), prec);
    Ball t;
    detail::moebius_alpha_map(detail::BallMapArith{prec}, t.get(), nullptr, s.get(), a.get());
    clamp_unit(t.get(), prec);
    if (!overlaps(nurbs_eval(n, s, prec), c.eval(t, prec))) internal("at s = " + Rational(q, 8).str());
  }
  return n;
}

std::vector<Rational> nurbs_eval(const Nurbs& n, const Rational& s) {
  if (n.kind != Nurbs::Kind::Exact) throw InvalidArgument("nurbs_eval: exact evaluation needs an exact NURBS");
  if (s.sign() < 0 || s > Rational(1)) throw InvalidArgument("nurbs_eval: s must lie in [0, 1]");
  const std::size_t d = static_cast<std::size_t>(n.degree);
  std::size_t seg = 0;
  while (seg + 1 < n.segments && s > n.knots_exact[break_index(n, seg + 1)]) ++seg;
  const Rational& lo = n.knots_exact[break_index(n, seg)];
  const Rational& hi = n.knots_exact[break_index(n, seg + 1)];
  const QField f;
  return eval_segment(f, n.points_exact, n.weights_exact, d * seg, n.degree, (s - lo) / (hi - lo));
}

std::vector<Ball> nurbs_eval(const Nurbs& n, const Ball& s, long prec) {
  const Ball zero(0), one(1);
  if (!s.is_finite() || arb_lt(s.get(), zero.get()) || arb_gt(s.get(), one.get()))
    throw InvalidArgument("nurbs_eval: s must lie in [0, 1]");
  const std::size_t d = static_cast<std::size_t>(n.degree);
  const BField f{prec};
  std::vector<Ball> out;
  bool any = false;
  for (std::size_t seg = 0; seg < n.segments; ++seg) {
    const Ball& lo = n.knots[break_index(n, seg)];
    const Ball& hi = n.knots[break_index(n, seg + 1)];
    if (arb_lt(s.get(), lo.get()) || arb_gt(s.get(), hi.get())) continue;
    Ball u = f.div(f.sub(s, lo), f.sub(hi, lo));
    if (s.is_exact() && lo.is_exact() && arb_equal(s.get(), lo.get())) u = Ball(0);
    if (s.is_exact() && hi.is_exact() && arb_equal(s.get(), hi.get())) u = Ball(1);
    clamp_unit(u.get(), prec);
    std::vector<Ball> v = eval_segment(f, n.points, n.weights, d * seg, n.degree, u);
    if (!any) out = v;
    else
      for (std::size_t k = 0; k < v.size(); ++k) arb_union(out[k].get(), out[k].get(), v[k].get(), prec);
    any = true;
  }
  if (!any) throw InvalidArgument("nurbs_eval: s must lie in [0, 1]");
  return out;
}

}  // namespace uniparam
