#include "uniparam/reparam/composite.hpp"

#include <arb.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/parallel.hpp"
#include "uniparam/reparam/radical.hpp"
#include "track.hpp"

namespace uniparam {

namespace {

// Runs f, prefixing the message of a uniparam error with `label` (the type,
// and a ParseError's column, are kept).
template <class F>
auto labelled(const std::string& label, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const ParseError& e) {
    throw ParseError(e.column(), e.expected(), label + ": " + e.what());
  } catch (const TimeLimitExceeded&) {
    throw;  // its message names the time limit, the same for every segment
  } catch (const BudgetExceeded& e) {
    throw BudgetExceeded(label + ": " + e.what());
  } catch (const DomainError& e) {
    throw DomainError(label + ": " + e.what());
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(label + ": " + e.what());
  }
}

// The options each segment is computed with: two more digits, so that the
// sums and quotients over the segments still meet the digits asked for.
Options segment_options(const Options& opt) {
  Options o = opt;
  o.digits = std::min(opt.digits + 2, 10000L);
  return o;
}

// The direction of motion at an end of c (t = 0: leaving it; t = 1:
// arriving): the first nonvanishing derivative of p' there, with the sign
// of (t - 1)^k at t = 1. W(end) > 0 does not change the direction.
std::vector<Rational> end_direction(const Curve& c, long end) {
  std::vector<Poly> d = c.derivative_numerators();
  const Rational at(end);
  for (long k = 0;; ++k) {
    std::vector<Rational> v;
    bool nonzero = false;
    for (const Poly& p : d) {
      v.push_back(p(at));
      if (!v.back().is_zero()) nonzero = true;
    }
    if (nonzero) {
      if (end == 1 && k % 2 == 1)
        for (Rational& x : v) x = -x;
      return v;
    }
    for (Poly& p : d) p = p.derivative();  // terminates: c is not constant
  }
}

// The components of c at the exact parameter x.
std::vector<Rational> point_at(const Curve& c, const Rational& x) {
  std::vector<Rational> v;
  for (const RatFunc& f : c.components()) v.push_back(f(x));
  return v;
}

// x * q (exact q) at prec.
Ball mul_rational(const Ball& x, const Rational& q, long prec) {
  Ball r;
  arb_mul_fmpz(r.get(), x.get(), q.num().get(), prec);
  arb_div_fmpz(r.get(), r.get(), q.den().get(), prec);
  return r;
}

Ball div_rational(const Ball& x, const Rational& q, long prec) {
  Ball r;
  arb_mul_fmpz(r.get(), x.get(), q.den().get(), prec);
  arb_div_fmpz(r.get(), r.get(), q.num().get(), prec);
  return r;
}

// The rational with 53 significant bits nearest to b's midpoint.
Rational rounded_mid(const Ball& b) {
  arf_t m;
  arf_init(m);
  arf_set_round(m, arb_midref(b.get()), 53, ARF_RND_NEAR);
  Ball x;
  arb_set_arf(x.get(), m);
  arf_clear(m);
  return mid_rational(x);
}

long work_prec(const Options& opt) { return 2 * digits_to_bits(opt.digits) + 64; }

void check_knots(const std::vector<Rational>& k, std::size_t m) {
  if (k.size() != m + 1)
    throw InvalidArgument("a composite curve of " + std::to_string(m) + " segments needs " + std::to_string(m + 1) +
                          " knots, got " + std::to_string(k.size()));
  if (!k.front().is_zero() || k.back() != Rational(1))
    throw InvalidArgument("the knots of a composite curve must run from 0 to 1");
  for (std::size_t j = 0; j + 1 < k.size(); ++j)
    if (!(k[j] < k[j + 1]))
      throw InvalidArgument("the knots of a composite curve must increase strictly (knot " + std::to_string(j + 1) +
                            " is " + k[j + 1].str() + " after " + k[j].str() + ")");
}

}  // namespace

CompositeCurve::CompositeCurve(std::vector<Curve> segments, std::vector<Rational> knots,
                               std::vector<std::string> labels)
    : segments_(std::move(segments)), knots_(std::move(knots)), labels_(std::move(labels)) {
  if (segments_.empty()) throw InvalidArgument("a composite curve needs at least one segment");
  check_knots(knots_, segments_.size());
  for (std::size_t j = 1; j < segments_.size(); ++j)
    if (segments_[j].dimension() != segments_.front().dimension())
      throw InvalidArgument("segment " + std::to_string(j) + " has dimension " +
                            std::to_string(segments_[j].dimension()) + ", segment 0 has " +
                            std::to_string(segments_.front().dimension()));
  if (labels_.empty())
    for (std::size_t j = 0; j < segments_.size(); ++j) labels_.push_back("segment " + std::to_string(j + 1));
  if (labels_.size() != segments_.size())
    throw InvalidArgument("a composite curve needs one label per segment");
}

CompositeCurve::CompositeCurve(Curve c) : CompositeCurve(std::vector<Curve>{std::move(c)}, {Rational(0), Rational(1)}) {}

long CompositeCurve::degree() const {
  long d = 0;
  for (const Curve& c : segments_) d = std::max(d, c.degree());
  return d;
}

std::size_t CompositeCurve::segment_of(const Rational& x) const {
  std::size_t j = 0;
  while (j + 2 < knots_.size() && !(x < knots_[j + 1])) ++j;
  return j;
}

std::vector<Ball> CompositeCurve::eval(const Ball& t, long prec) const {
  const auto& k = knots_;
  if (t.is_exact()) {
    const Rational x = mid_rational(t);
    const std::size_t j = segment_of(x);
    return segments_[j].eval(Ball((x - k[j]) / (k[j + 1] - k[j]), prec), prec);
  }
  std::vector<Ball> out;
  for (std::size_t j = 0; j < size(); ++j) {
    // The part of t inside [k_j, k_{j+1}], in the segment's parameter.
    Ball lo(k[j], prec), hi(k[j + 1], prec);
    if (arb_lt(t.get(), lo.get()) || arb_gt(t.get(), hi.get())) continue;
    Ball local;
    arb_sub(local.get(), t.get(), lo.get(), prec);
    local = div_rational(local, k[j + 1] - k[j], prec);
    clamp_unit(local.get(), prec);
    const std::vector<Ball> p = segments_[j].eval(local, prec);
    if (out.empty()) {
      out = p;
    } else {
      for (std::size_t i = 0; i < p.size(); ++i) arb_union(out[i].get(), out[i].get(), p[i].get(), prec);
    }
  }
  if (out.empty()) throw InvalidArgument("the parameter's enclosure lies outside [0, 1]");
  return out;
}

std::vector<Speed> CompositeCurve::speeds(SpeedKind kind) const {
  std::vector<Speed> out;
  out.reserve(size());
  for (std::size_t j = 0; j < size(); ++j)
    out.push_back(labelled(labels_[j], [&] { return Speed(segments_[j], kind); }));
  return out;
}

std::vector<Joint> joints(const CompositeCurve& c, long prec) {
  std::vector<Joint> out;
  for (std::size_t j = 1; j < c.size(); ++j) {
    Joint jt;
    jt.index = j;
    jt.continuous = point_at(c.segment(j - 1), Rational(1)) == point_at(c.segment(j), Rational(0));
    const std::vector<Rational> a = end_direction(c.segment(j - 1), 1), b = end_direction(c.segment(j), 0);
    Rational dot(0), aa(0), bb(0);
    for (std::size_t i = 0; i < a.size(); ++i) {
      dot = dot + a[i] * b[i];
      aa = aa + a[i] * a[i];
      bb = bb + b[i] * b[i];
    }
    const Rational cross2 = aa * bb - dot * dot;  // |a|^2 |b|^2 sin^2
    jt.smooth = jt.continuous && cross2.is_zero() && dot.sign() > 0;
    if (cross2.is_zero() && dot.sign() > 0) {
      jt.angle = Ball(0);
    } else {
      Ball s(cross2, prec), d(dot, prec);
      arb_sqrt(s.get(), s.get(), prec);
      arb_atan2(jt.angle.get(), s.get(), d.get(), prec);
    }
    out.push_back(std::move(jt));
  }
  return out;
}

CompositeUniformity uniformity(const CompositeCurve& c, SpeedKind kind, const Options& opt) {
  validate(opt);
  const Options so = segment_options(opt);
  const std::size_t m = c.size();
  CompositeUniformity r;
  r.kind = kind;
  r.segments.resize(m);
  parallel_for(m, worker_count(), [&](std::size_t, std::size_t j) {
    r.segments[j] = labelled(c.label(j), [&] { return uniformity(c.segment(j), kind, so); });
  });
  const long prec = work_prec(opt);
  r.joints = joints(c, prec);
  r.mu = Ball(0);
  r.mean_square = Ball(0);
  r.corner_turning = Ball(0);
  bool all_zero = true;
  for (std::size_t j = 0; j < m; ++j) {
    const UniformityResult& s = r.segments[j];
    all_zero = all_zero && s.identically_zero;
    arb_add(r.mu.get(), r.mu.get(), s.mu.get(), prec);
    const Ball part = div_rational(s.mean_square, c.knots()[j + 1] - c.knots()[j], prec);
    arb_add(r.mean_square.get(), r.mean_square.get(), part.get(), prec);
  }
  for (const Joint& jt : r.joints) arb_add(r.corner_turning.get(), r.corner_turning.get(), jt.angle.get(), prec);
  r.identically_zero = all_zero;
  if (all_zero) {
    r.u = Ball(1);
  } else {
    arb_sqr(r.u.get(), r.mu.get(), prec);
    arb_div(r.u.get(), r.u.get(), r.mean_square.get(), prec);
  }
  if (!r.mu.meets_digits(opt.digits) || !r.mean_square.meets_digits(opt.digits) || !r.u.meets_digits(opt.digits))
    throw BudgetExceeded("the composite curve's mu and u could not be certified to " + std::to_string(opt.digits) +
                         " digits from its segments' (raise --max-prec)");
  return r;
}

// ---------------------------------------------------------------------------
// Maps.

std::string CompositeMap::method() const { return parts_.front().method(); }

std::size_t CompositeMap::pieces() const {
  std::size_t n = 0;
  for (const Reparameterization& p : parts_) n += p.pieces();
  return n;
}

bool CompositeMap::target_reached() const {
  for (const Reparameterization& p : parts_) {
    const MoebiusResult* m = p.moebius_result();
    if (!m || !m->target.used || !m->target.reached) return false;
  }
  return true;
}

namespace {

// Calls f(j, local) for every segment j whose [S_j, S_{j+1}] meets the ball
// s, with local = (s - S_j) / (S_{j+1} - S_j) clipped to [0, 1].
template <class F>
void for_segments_at(const std::vector<Rational>& S, const Ball& s, long prec, F&& f) {
  if (arb_is_exact(s.get())) {
    const Rational x = mid_rational(s);
    std::size_t j = 0;
    while (j + 2 < S.size() && !(x < S[j + 1])) ++j;
    f(j, Ball((x - S[j]) / (S[j + 1] - S[j]), prec));
    return;
  }
  bool any = false;
  for (std::size_t j = 0; j + 1 < S.size(); ++j) {
    Ball lo(S[j], prec), hi(S[j + 1], prec);
    if (arb_lt(s.get(), lo.get()) || arb_gt(s.get(), hi.get())) continue;
    Ball local;
    arb_sub(local.get(), s.get(), lo.get(), prec);
    local = div_rational(local, S[j + 1] - S[j], prec);
    clamp_unit(local.get(), prec);
    f(j, local);
    any = true;
  }
  if (!any) throw InvalidArgument("the parameter s must lie in [0, 1]");
}

void unite(Ball& acc, bool& first, const Ball& x, long prec) {
  if (first) acc = x;
  else arb_union(acc.get(), acc.get(), x.get(), prec);
  first = false;
}

}  // namespace

Ball CompositeMap::eval_r(const CompositeCurve& c, const Ball& s, long prec) const {
  Ball out;
  bool first = true;
  for_segments_at(S_, s, prec, [&](std::size_t j, const Ball& local) {
    Ball t = mul_rational(parts_[j].eval_r(local, prec), c.knots()[j + 1] - c.knots()[j], prec);
    arb_add(t.get(), t.get(), Ball(c.knots()[j], prec).get(), prec);
    unite(out, first, t, prec);
  });
  return out;
}

Ball CompositeMap::eval_speed(const CompositeCurve& c, const std::vector<Speed>& sp, const Ball& s, long prec) const {
  (void)c;
  Ball out;
  bool first = true;
  for_segments_at(S_, s, prec, [&](std::size_t j, const Ball& local) {
    unite(out, first, div_rational(parts_[j].eval_speed(sp[j], local, prec), S_[j + 1] - S_[j], prec), prec);
  });
  return out;
}

std::vector<std::pair<Ball, Ball>> CompositeMap::joints(const CompositeCurve& c, long prec) const {
  std::vector<std::pair<Ball, Ball>> out;
  for (std::size_t j = 0; j < parts_.size(); ++j) {
    const Reparameterization& p = parts_[j];
    for (std::size_t i = j ? 1 : 0; i < p.joints_s().size(); ++i) {
      Ball s = mul_rational(p.joints_s()[i], S_[j + 1] - S_[j], prec);
      arb_add(s.get(), s.get(), Ball(S_[j], prec).get(), prec);
      Ball t = mul_rational(p.joints_t()[i].to_ball(prec), c.knots()[j + 1] - c.knots()[j], prec);
      arb_add(t.get(), t.get(), Ball(c.knots()[j], prec).get(), prec);
      out.emplace_back(s, t);
    }
  }
  return out;
}

namespace {

// sqrt(E_j) = mu_j / sqrt(u_j) of a part, as a ball (0 for mu_j = 0).
Ball root_energy(const Reparameterization& r, long prec) {
  if (r.mu().certainly_zero()) return Ball(0);
  Ball e;
  arb_sqrt(e.get(), r.u_after().get(), prec);
  arb_div(e.get(), r.mu().get(), e.get(), prec);
  return e;
}

double mid_double_of(const Ball& b) { return arf_get_d(arb_midref(b.get()), ARF_RND_NEAR); }

// Breakpoints of segment j: the global list's points strictly inside
// (k_j, k_{j+1}), in the segment's own parameter, with 0 and 1.
std::vector<RealAlgebraic> local_breakpoints(const std::vector<Rational>& T, const Rational& a, const Rational& b) {
  std::vector<RealAlgebraic> out{RealAlgebraic(0)};
  for (const Rational& t : T)
    if (a < t && t < b) out.emplace_back((t - a) / (b - a));
  out.emplace_back(1);
  return out;
}

void check_global_breakpoints(const std::vector<Rational>& T) {
  if (T.size() < 2 || !T.front().is_zero() || T.back() != Rational(1))
    throw InvalidArgument("the breakpoints must start at 0 and end at 1");
  for (std::size_t i = 0; i + 1 < T.size(); ++i)
    if (!(T[i] < T[i + 1])) throw InvalidArgument("the breakpoints must increase strictly");
}

}  // namespace

CompositeMap composite_map(const CompositeCurve& c, const std::vector<Speed>& speeds, const CompositeMethod& m,
                           const Options& opt) {
  validate(opt);
  const std::size_t n = c.size();
  if (speeds.size() != n) throw InvalidArgument("composite_map: one speed per segment is needed");
  const Options so = segment_options(opt);
  const long prec = work_prec(opt);
  using K = CompositeMethod::Kind;
  if (m.kind == K::Pieces && (m.pieces < static_cast<long>(n) || m.pieces > 1000))
    throw InvalidArgument("--pieces must be between the number of segments (" + std::to_string(n) +
                          ": every segment is a piece at least) and 1000, got " + std::to_string(m.pieces));
  if (m.kind == K::Target && (m.target <= Rational(0) || m.target >= Rational(1)))
    throw InvalidArgument("--target must lie strictly between 0 and 1, got " + m.target.str());
  if (m.kind == K::Breakpoints) check_global_breakpoints(m.breakpoints);
  bool all_zero = true, some_zero = false;
  for (const Speed& s : speeds) {
    all_zero = all_zero && s.identically_zero();
    some_zero = some_zero || s.identically_zero();
  }
  if (some_zero && !all_zero && m.kind != K::None) {
    std::size_t j = 0;
    while (!speeds[j].identically_zero()) ++j;
    throw DomainError(c.label(j) +
                      " is straight: its angular speed is identically 0, so no reparameterization gives it a "
                      "share of the new parameter with a positive speed (use --speed parametric, or methods on "
                      "the curved segments alone)");
  }
  auto finish = [&](std::size_t j, MoebiusResult r) {
    return m.rational ? labelled(c.label(j), [&] { return make_rational(c.segment(j), r, m.rational_digits, so); })
                      : r;
  };
  auto moebius_part = [&](std::size_t j, long pieces) {
    return labelled(c.label(j), [&] { return reparam_c0(c.segment(j), speeds[j].kind(), pieces, so); });
  };

  CompositeMap out;
  out.parts_.resize(n, Reparameterization::identity(Ball(0), Ball(1)));
  std::vector<Ball> mean_square(n);  // I_j, for None
  if (m.kind == K::Pieces) {
    // One piece per segment, then each next piece where it lowers
    // sum sqrt(E_j) most (by the maps' midpoints: only the choice).
    std::vector<long> count(n, 1);
    std::vector<MoebiusResult> cur(n), next(n);
    parallel_for(2 * n, worker_count(), [&](std::size_t, std::size_t i) {
      if (i < n) cur[i] = moebius_part(i, 1);
      else next[i - n] = moebius_part(i - n, 2);
    });
    auto root_e = [&](const MoebiusResult& r) {
      return mid_double_of(root_energy(Reparameterization(r), prec));
    };
    for (long left = m.pieces - static_cast<long>(n); left > 0; --left) {
      std::size_t best = 0;
      double gain = -std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < n; ++j) {
        if (count[j] >= 1000) continue;
        const double g = root_e(cur[j]) - root_e(next[j]);
        if (g > gain) gain = g, best = j;
      }
      ++count[best];
      cur[best] = std::move(next[best]);
      if (left > 1 && count[best] < 1000) next[best] = moebius_part(best, count[best] + 1);
    }
    for (std::size_t j = 0; j < n; ++j) out.parts_[j] = Reparameterization(finish(j, cur[j]));
  } else {
    parallel_for(n, worker_count(), [&](std::size_t, std::size_t j) {
      const Curve& cj = c.segment(j);
      const SpeedKind kind = speeds[j].kind();
      switch (m.kind) {
        case K::None: {
          const UniformityResult u = labelled(c.label(j), [&] { return uniformity(speeds[j], so); });
          mean_square[j] = u.mean_square;
          out.parts_[j] = Reparameterization::identity(u.mu, u.u);
          break;
        }
        case K::Radical:
          out.parts_[j] = Reparameterization(labelled(c.label(j), [&] { return radical(cj, kind, so); }));
          break;
        case K::Moebius:
          out.parts_[j] = Reparameterization(
              finish(j, labelled(c.label(j), [&] { return moebius_optimal(cj, kind, so); })));
          break;
        case K::Breakpoints: {
          const auto T = local_breakpoints(m.breakpoints, c.knots()[j], c.knots()[j + 1]);
          out.parts_[j] =
              Reparameterization(finish(j, labelled(c.label(j), [&] { return moebius_c0(cj, kind, T, so); })));
          break;
        }
        case K::Target:
          out.parts_[j] = Reparameterization(finish(
              j, labelled(c.label(j), [&] { return reparam_c1(cj, kind, m.target, so, m.max_pieces); })));
          break;
        case K::Pieces:
          break;
      }
    });
  }

  // mu, u_before (from I_j = mu_j^2 / u_j(p)), the joints S and u_after.
  out.mu_ = Ball(0);
  Ball before(0);
  for (std::size_t j = 0; j < n; ++j) {
    const Reparameterization& p = out.parts_[j];
    arb_add(out.mu_.get(), out.mu_.get(), p.mu().get(), prec);
    Ball I = mean_square[j];
    if (m.kind != K::None) {
      if (p.mu().certainly_zero()) I = Ball(0);
      else arb_sqr(I.get(), p.mu().get(), prec), arb_div(I.get(), I.get(), p.u_before().get(), prec);
    }
    arb_add(before.get(), before.get(), div_rational(I, c.knots()[j + 1] - c.knots()[j], prec).get(), prec);
  }
  if (all_zero) {
    out.S_ = c.knots();
    out.u_before_ = Ball(1);
    out.u_after_ = Ball(1);
    return out;
  }
  arb_sqr(out.u_before_.get(), out.mu_.get(), prec);
  arb_div(out.u_before_.get(), out.u_before_.get(), before.get(), prec);
  if (m.kind == K::None) {
    out.S_ = c.knots();
    out.u_after_ = out.u_before_;
  } else {
    std::vector<Ball> w(n);
    std::vector<Rational> wq(n);
    Rational total(0);
    for (std::size_t j = 0; j < n; ++j) {
      w[j] = root_energy(out.parts_[j], prec);
      if (!w[j].certainly_positive())
        throw BudgetExceeded(c.label(j) + ": its share of the new parameter could not be certified positive");
      wq[j] = rounded_mid(w[j]);
      total = total + wq[j];
    }
    out.S_ = {Rational(0)};
    Rational acc(0);
    for (std::size_t j = 0; j + 1 < n; ++j) {
      acc = acc + wq[j];
      out.S_.push_back(acc / total);
    }
    out.S_.push_back(Rational(1));
    Ball sum(0);
    for (std::size_t j = 0; j < n; ++j) {
      Ball e;
      arb_sqr(e.get(), w[j].get(), prec);
      arb_add(sum.get(), sum.get(), div_rational(e, out.S_[j + 1] - out.S_[j], prec).get(), prec);
    }
    arb_sqr(out.u_after_.get(), out.mu_.get(), prec);
    arb_div(out.u_after_.get(), out.u_after_.get(), sum.get(), prec);
  }
  if (!out.mu_.meets_digits(opt.digits) || !out.u_before_.meets_digits(opt.digits) ||
      !out.u_after_.meets_digits(opt.digits))
    throw BudgetExceeded("the composite map's mu and u could not be certified to " + std::to_string(opt.digits) +
                         " digits from its segments' (raise --max-prec)");
  return out;
}

// ---------------------------------------------------------------------------
// Samples.

CompositeSampler::CompositeSampler(const CompositeCurve& c, const std::vector<Speed>& speeds, const CompositeMap& r,
                                   long digits, long max_prec)
    : c_(c), sp_(speeds), r_(r), digits_(digits), max_prec_(max_prec), parts_(c.size()) {
  if (speeds.size() != c.size() || r.parts().size() != c.size())
    throw InvalidArgument("CompositeSampler: the curve, speeds and map do not belong together");
  part(0);  // checks digits and max_prec as Sampler does
}

Sampler& CompositeSampler::part(std::size_t j) {
  if (!parts_[j])
    parts_[j] = std::make_unique<Sampler>(c_.segment(j), sp_[j], r_.parts()[j], digits_, max_prec_);
  return *parts_[j];
}

std::size_t CompositeSampler::segment_of(const Rational& s) const {
  const auto& S = r_.S();
  std::size_t j = 0;
  while (j + 2 < S.size() && !(s < S[j + 1])) ++j;
  return j;
}

SamplePoint CompositeSampler::at(const Rational& s) {
  if (s.sign() < 0 || Rational(1) < s) throw InvalidArgument("the sample parameter must lie in [0, 1]");
  const auto& S = r_.S();
  const auto& k = c_.knots();
  const std::size_t j = segment_of(s);
  const long prec = 2 * digits_to_bits(digits_) + 64;
  const Rational dS = S[j + 1] - S[j];
  SamplePoint local = part(j).at((s - S[j]) / dS);
  SamplePoint out;
  out.s = s;
  out.point = std::move(local.point);
  out.t = mul_rational(local.t, k[j + 1] - k[j], prec);
  {
    Ball kj(k[j], prec);
    arb_add(out.t.get(), out.t.get(), kj.get(), prec);
  }
  out.speed = div_rational(local.speed, dS, prec);
  out.at_joint = local.at_joint;
  if (j > 0 && s == S[j]) {
    const SamplePoint left = part(j - 1).at(Rational(1));
    const Ball ls = div_rational(left.speed, S[j] - S[j - 1], prec);
    arb_union(out.speed.get(), out.speed.get(), ls.get(), prec);
    out.at_joint = true;
  }
  return out;
}

// ---------------------------------------------------------------------------
// Locating on a composite curve.

namespace {

class CompositeTrack final : public Track {
 public:
  CompositeTrack(const CompositeCurve& c, const std::vector<Speed>& s, long max_prec)
      : c_(c), s_(s), max_prec_(max_prec) {}
  bool identically_zero() const override {
    for (const Speed& s : s_)
      if (!s.identically_zero()) return false;
    return true;
  }
  SpeedKind kind() const override { return s_.front().kind(); }
  Ball mu(long bits, const Options& opt) const override {
    const long prec = 2 * bits + 64;
    Ball sum(0);
    for (std::size_t j = 0; j < c_.size(); ++j) {
      if (s_[j].identically_zero()) continue;
      const Ball mj = labelled(c_.label(j), [&] { return mean_speed(s_[j], bits, opt); });
      arb_add(sum.get(), sum.get(), mj.get(), prec);
    }
    return sum;
  }
  Ball integral(const Rational& a, const Rational& b, long bits) const override {
    const long prec = 2 * bits + 64;
    const auto& k = c_.knots();
    Ball sum(0);
    for (std::size_t j = 0; j < c_.size(); ++j) {
      const Rational lo = a < k[j] ? k[j] : a, hi = k[j + 1] < b ? k[j + 1] : b;
      if (!(lo < hi) || s_[j].identically_zero()) continue;
      const Rational d = k[j + 1] - k[j];
      const Ball part = integrate_speed(s_[j], RealAlgebraic((lo - k[j]) / d), RealAlgebraic((hi - k[j]) / d),
                                        bits, max_prec_);
      arb_add(sum.get(), sum.get(), part.get(), prec);
    }
    return sum;
  }
  double sigma_estimate(const Rational& x) const override {
    const auto& k = c_.knots();
    const std::size_t j = c_.segment_of(x);
    if (s_[j].identically_zero()) return 0;
    const Rational d = k[j + 1] - k[j];
    const double dd = mid_double_of(Ball(d, 64));
    return uniparam::sigma_estimate(s_[j], (x - k[j]) / d) / dd;
  }
  std::vector<Ball> eval(const Ball& t, long prec) const override { return c_.eval(t, prec); }
  std::vector<Segment> segments() const override {
    std::vector<Segment> out;
    for (std::size_t j = 0; j < c_.size(); ++j) out.push_back(Segment{c_.knots()[j], c_.knots()[j + 1], &s_[j]});
    return out;
  }

 private:
  const CompositeCurve& c_;
  const std::vector<Speed>& s_;
  long max_prec_;
};

}  // namespace

std::shared_ptr<const Track> composite_track(const CompositeCurve& c, const std::vector<Speed>& speeds,
                                             long max_prec) {
  return std::make_shared<CompositeTrack>(c, speeds, max_prec);
}

namespace {

// A straight segment among curved ones has angular speed 0 on a whole
// interval: int_0^t sigma is constant there, and a value it takes there
// determines no parameter.
void check_no_flat_segment(const CompositeCurve& c, const std::vector<Speed>& speeds) {
  bool all = true;
  for (const Speed& s : speeds) all = all && s.identically_zero();
  if (all) return;
  for (std::size_t j = 0; j < c.size(); ++j)
    if (speeds[j].identically_zero())
      throw DomainError(c.label(j) +
                        " is straight: its angular speed is 0 on a whole interval, where the turning angle "
                        "determines no parameter (use the parametric speed, arc length)");
}

}  // namespace

LocateResult locate(const CompositeCurve& c, const std::vector<Speed>& speeds, const Rational& value,
                    LocateTarget target, const Options& opt) {
  validate(opt);
  if (speeds.size() != c.size()) throw InvalidArgument("locate: one speed per segment is needed");
  check_no_flat_segment(c, speeds);
  return locate_on(CompositeTrack(c, speeds, opt.max_prec), value, target, opt);
}

void exact_samples_each(const CompositeCurve& c, const std::vector<Speed>& speeds, long K, const Options& opt,
                        Ball& mu, const LocatedSink& sink) {
  validate(opt);
  if (speeds.size() != c.size()) throw InvalidArgument("exact_samples_each: one speed per segment is needed");
  check_no_flat_segment(c, speeds);
  exact_samples_on(CompositeTrack(c, speeds, opt.max_prec), K, opt, mu, sink);
}

}  // namespace uniparam
