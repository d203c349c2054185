// Composite curves (segments joined at knots): the curve, its evaluation,
// its joints and its certified uniformity. The maps are in composite_map.cpp,
// the samples in composite_sample.cpp, locating in composite_locate.cpp.
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
  std::vector<Ball> out;
  // the part of t inside each [k_j, k_{j+1}] it meets, in the segment's parameter
  for_segments_at(knots_, t, prec, "the parameter's enclosure lies outside [0, 1]",
                  [&](std::size_t j, const Ball& local) {
                    const std::vector<Ball> p = segments_[j].eval(local, prec);
                    if (out.empty()) {
                      out = p;
                    } else {
                      for (std::size_t i = 0; i < p.size(); ++i)
                        arb_union(out[i].get(), out[i].get(), p[i].get(), prec);
                    }
                  });
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

}  // namespace uniparam
