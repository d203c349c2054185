// Maps of a composite curve: one reparameterization per segment, joined at
// the shares s_j of the new parameter that make the whole map optimal; its
// evaluation, speed, joints, mu and uniformities.
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
#include "composite_detail.hpp"

namespace uniparam {

using namespace composite_detail;

namespace {

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

}  // namespace

std::string CompositeMap::method() const { return parts_.front().method(); }

std::size_t CompositeMap::pieces() const {
  std::size_t n = 0;
  for (const Reparameterization& p : parts_) n += p.pieces();
  return n;
}

bool CompositeMap::target_reached() const {
  for (const Reparameterization& p : parts_) {
    const MoebiusResult* m = p.moebius_result();
    if (!m || !m->target.has_value() || !m->target->reached) return false;
  }
  return true;
}

namespace {


void unite(Ball& acc, bool& first, const Ball& x, long prec) {
  if (first) acc = x;
  else arb_union(acc.get(), acc.get(), x.get(), prec);
  first = false;
}

}  // namespace

Ball CompositeMap::eval_r(const CompositeCurve& c, const Ball& s, long prec) const {
  Ball out;
  bool first = true;
  for_segments_at(S_, s, prec, "the parameter s must lie in [0, 1]", [&](std::size_t j, const Ball& local) {
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
  for_segments_at(S_, s, prec, "the parameter s must lie in [0, 1]", [&](std::size_t j, const Ball& local) {
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
    out.S_ = cumulative_normalised(wq, total);
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

}  // namespace uniparam
