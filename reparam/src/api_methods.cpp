// The facade's computations (uniparam/uniparam.hpp): uniformity, locate and
// the methods, each returning a Reparameterization that owns its curve.
#include "api_impl.hpp"

namespace uniparam {
namespace api {

using detail::guarded;
using detail::unwrap;
using detail::wrap;

namespace {

/// Bits that give a ball meeting `digits` for an exact algebraic number.
long joint_prec(long digits) { return digits_to_bits(digits) + 8; }

const CompositeCurve& cc_of(const Curve& c) { return c.impl().cc; }
bool single(const Curve& c) { return cc_of(c).size() == 1; }

/// The zeros of a segment's speed in the global parameter of cc.
void push_zeros(std::vector<Zero>& out, const CompositeCurve& cc, std::size_t j, const std::vector<SpeedZero>& zs,
                long prec) {
  const uniparam::Rational& a = cc.knots()[j];
  const uniparam::Rational h = cc.knots()[j + 1] - a;
  for (const SpeedZero& z : zs) {
    uniparam::Ball t = z.t.to_ball(prec + 8);
    if (cc.size() > 1) {
      uniparam::Ball hb(h, prec + 16), ab(a, prec + 16);
      arb_mul(t.get(), t.get(), hb.get(), prec + 16);
      arb_add(t.get(), t.get(), ab.get(), prec + 16);
    }
    out.push_back(Zero{wrap(t), z.multiplicity});
  }
}

std::shared_ptr<Reparameterization::Impl> new_impl(const Curve& c, const Options& o) {
  auto impl = std::make_shared<Reparameterization::Impl>(c, o, detail::engine_options(o));
  impl->speeds = cc_of(c).speeds(detail::kind_of(o));
  return impl;
}

Reparameterization finish(std::shared_ptr<Reparameterization::Impl> impl) {
  return Reparameterization(std::shared_ptr<const Reparameterization::Impl>(std::move(impl)));
}

/// A single curve: the map `make` computes; a composite curve: composite_map
/// with the method `m`.
template <class Make>
Reparameterization run_method(const Curve& c, const Options& o, const CompositeMethod& m, Make make) {
  return guarded(o, [&] {
    auto impl = new_impl(c, o);
    if (single(c)) {
      impl->map.emplace(make(cc_of(c).segment(0), detail::kind_of(o), impl->iopt));
    } else {
      impl->cmap.emplace(composite_map(cc_of(c), impl->speeds, m, impl->iopt));
      impl->cmethod = m;
    }
    return finish(std::move(impl));
  });
}

void check_count(const char* what, long v, long lo, long hi) {
  if (v < lo || v > hi)
    throw InvalidArgument(std::string(what) + " must be from " + std::to_string(lo) + " to " + std::to_string(hi) +
                          ", got " + std::to_string(v));
}

/// The engine's sampler of r (a single curve) or of the composite map.
template <class Sink>
void sample_at(const Reparameterization::Impl& r, const std::vector<uniparam::Rational>& s, Sink sink) {
  if (r.map) {
    Sampler smp(cc_of(r.curve).segment(0), r.speeds[0], *r.map, r.iopt.digits, r.iopt.max_prec);
    for (std::size_t k = 0; k < s.size(); ++k) sink(k, smp.at(s[k]));
  } else {
    CompositeSampler smp(cc_of(r.curve), r.speeds, *r.cmap, r.iopt.digits, r.iopt.max_prec);
    for (std::size_t k = 0; k < s.size(); ++k) sink(k, smp.at(s[k]));
  }
}

Reparameterization::Sample to_sample(const SamplePoint& p) {
  Reparameterization::Sample out;
  out.s = wrap(p.s);
  out.t = wrap(p.t);
  out.point = wrap(p.point);
  out.speed = wrap(p.speed);
  out.at_joint = p.at_joint;
  return out;
}

void check_unit(const uniparam::Rational& s) {
  if (s < uniparam::Rational(0) || s > uniparam::Rational(1))
    throw InvalidArgument("s must lie in [0, 1], got " + s.str());
}

}  // namespace

// ---- uniformity, locate ----

Uniformity uniformity(const Curve& c, const Options& o) {
  return guarded(o, [&] {
    const uniparam::Options io = detail::engine_options(o);
    const uniparam::SpeedKind kind = detail::kind_of(o);
    const CompositeCurve& cc = cc_of(c);
    const long prec = joint_prec(o.digits);
    Uniformity out;
    if (single(c)) {
      const UniformityResult r = uniparam::uniformity(cc.segment(0), kind, io);
      out.mu = wrap(r.mu);
      out.mean_square = wrap(r.mean_square);
      out.u = wrap(r.u);
      out.identically_zero = r.identically_zero;
      push_zeros(out.zeros, cc, 0, r.zeros, prec);
    } else {
      const CompositeUniformity r = uniparam::uniformity(cc, kind, io);
      out.mu = wrap(r.mu);
      out.mean_square = wrap(r.mean_square);
      out.u = wrap(r.u);
      out.identically_zero = r.identically_zero;
      for (std::size_t j = 0; j < r.segments.size(); ++j) push_zeros(out.zeros, cc, j, r.segments[j].zeros, prec);
    }
    return out;
  });
}

Located locate(const Curve& c, const Rational& value, bool fraction, const Options& o) {
  return guarded(o, [&] {
    const uniparam::Options io = detail::engine_options(o);
    const CompositeCurve& cc = cc_of(c);
    const std::vector<Speed> sp = cc.speeds(detail::kind_of(o));
    const LocateTarget target = fraction ? LocateTarget::Fraction : LocateTarget::Integral;
    const LocateResult r = single(c) ? uniparam::locate(cc.segment(0), sp[0], unwrap(value), target, io)
                                     : uniparam::locate(cc, sp, unwrap(value), target, io);
    return Located{wrap(r.at.t), wrap(r.at.point)};
  });
}

std::vector<Located> exact_samples(const Curve& c, long K, const Options& o) {
  return guarded(o, [&] {
    const uniparam::Options io = detail::engine_options(o);
    check_count("exact_samples: K", K, 2, 1000000);
    const CompositeCurve& cc = cc_of(c);
    const std::vector<Speed> sp = cc.speeds(detail::kind_of(o));
    std::vector<Located> out;
    uniparam::Ball mu;
    auto sink = [&](long, const LocatedPoint& p) { out.push_back(Located{wrap(p.t), wrap(p.point)}); };
    if (single(c)) uniparam::exact_samples_each(cc.segment(0), sp[0], K, io, mu, sink);
    else uniparam::exact_samples_each(cc, sp, K, io, mu, sink);
    return out;
  });
}

// ---- the methods ----

Reparameterization identity(const Curve& c, const Options& o) {
  CompositeMethod m;
  m.kind = CompositeMethod::Kind::None;
  return run_method(c, o, m, [](const uniparam::Curve& cv, uniparam::SpeedKind kind, const uniparam::Options& io) {
    const UniformityResult u = uniparam::uniformity(cv, kind, io);
    return uniparam::Reparameterization::identity(u.mu, u.u);
  });
}

Reparameterization radical(const Curve& c, const Options& o) {
  CompositeMethod m;
  m.kind = CompositeMethod::Kind::Radical;
  return run_method(c, o, m, [](const uniparam::Curve& cv, uniparam::SpeedKind kind, const uniparam::Options& io) {
    return uniparam::Reparameterization(uniparam::radical(cv, kind, io));
  });
}

Reparameterization moebius(const Curve& c, const Options& o) {
  CompositeMethod m;
  m.kind = CompositeMethod::Kind::Moebius;
  return run_method(c, o, m, [](const uniparam::Curve& cv, uniparam::SpeedKind kind, const uniparam::Options& io) {
    return uniparam::Reparameterization(moebius_optimal(cv, kind, io));
  });
}

Reparameterization moebius_pieces(const Curve& c, long pieces, const Options& o) {
  CompositeMethod m;
  m.kind = CompositeMethod::Kind::Pieces;
  m.pieces = pieces;
  return guarded(o, [&] {
    check_count("moebius_pieces: pieces", pieces, 1, 1000);
    return run_method(c, o, m, [&](const uniparam::Curve& cv, uniparam::SpeedKind kind, const uniparam::Options& io) {
      return uniparam::Reparameterization(reparam_c0(cv, kind, pieces, io));
    });
  });
}

Reparameterization moebius_breakpoints(const Curve& c, const std::vector<Rational>& breakpoints, const Options& o) {
  CompositeMethod m;
  m.kind = CompositeMethod::Kind::Breakpoints;
  for (const auto& b : breakpoints) m.breakpoints.push_back(unwrap(b));
  return guarded(o, [&] {
    const auto& T = m.breakpoints;
    bool ok = T.size() >= 2 && T.front() == uniparam::Rational(0) && T.back() == uniparam::Rational(1);
    for (std::size_t i = 1; ok && i < T.size(); ++i) ok = T[i - 1] < T[i];
    if (!ok)
      throw InvalidArgument("moebius_breakpoints: the breakpoints must increase strictly from exactly 0 to exactly 1");
    return run_method(c, o, m, [&](const uniparam::Curve& cv, uniparam::SpeedKind kind, const uniparam::Options& io) {
      std::vector<RealAlgebraic> ra;
      for (const auto& t : T) ra.emplace_back(t);
      return uniparam::Reparameterization(moebius_c0(cv, kind, ra, io));
    });
  });
}

Reparameterization moebius_target(const Curve& c, const Rational& target, long max_pieces, const Options& o) {
  CompositeMethod m;
  m.kind = CompositeMethod::Kind::Target;
  m.target = unwrap(target);
  m.max_pieces = max_pieces;
  return guarded(o, [&] {
    if (m.target <= uniparam::Rational(0) || m.target >= uniparam::Rational(1))
      throw InvalidArgument("moebius_target: the target must lie strictly between 0 and 1, got " + m.target.str());
    check_count("moebius_target: max_pieces", max_pieces, 1, 1000);
    return run_method(c, o, m, [&](const uniparam::Curve& cv, uniparam::SpeedKind kind, const uniparam::Options& io) {
      return uniparam::Reparameterization(reparam_c1(cv, kind, m.target, io, max_pieces));
    });
  });
}

Reparameterization bezier_bilinear(const Curve& c, const Options& o) {
  return guarded(o, [&] {
    if (!c.is_bezier())
      throw InvalidArgument("bezier_bilinear needs a curve given as one Bezier curve (Curve::bezier, or a path or "
                            "spline of one segment)");
    if (o.speed != SpeedKind::Parametric)
      throw InvalidArgument("bezier_bilinear makes the parametric speed uniform: set Options::speed to "
                            "SpeedKind::Parametric");
    auto impl = new_impl(c, o);
    BezierResult br = bezier_optimal(*c.impl().bezier, impl->iopt);
    // The same map as the single Moebius map on T = (0, 1) with br.alpha
    // (Juettler's optimum is that of docs/math.md (2.2) for the parametric
    // speed): evaluation, sampling and refinement go through it.
    MoebiusResult m;
    m.kind = uniparam::SpeedKind::Parametric;
    m.continuity = Continuity::C0;
    m.T = {Breakpoint{RealAlgebraic(uniparam::Rational(0))}, Breakpoint{RealAlgebraic(uniparam::Rational(1))}};
    m.integrals.resize(1);
    m.integrals[0].alpha = br.alpha;
    m.S = {uniparam::Ball(0), uniparam::Ball(1)};
    m.alpha = {br.alpha};
    m.mu = br.mu;
    m.u_before = br.u_before;
    m.u_after = br.u_after;
    impl->map.emplace(std::move(m));
    impl->bezier = std::move(br);
    return finish(std::move(impl));
  });
}

// ---- Reparameterization ----

std::string Reparameterization::method() const {
  if (p_->bezier) return "Bezier bilinear";
  return p_->map ? p_->map->method() : p_->cmap->method();
}

const Curve& Reparameterization::curve() const { return p_->curve; }
const Options& Reparameterization::options() const { return p_->opt; }
std::size_t Reparameterization::pieces() const { return p_->map ? p_->map->pieces() : p_->cmap->pieces(); }
Ball Reparameterization::mu() const { return wrap(p_->map ? p_->map->mu() : p_->cmap->mu()); }
Ball Reparameterization::u_before() const { return wrap(p_->map ? p_->map->u_before() : p_->cmap->u_before()); }
Ball Reparameterization::u_after() const { return wrap(p_->map ? p_->map->u_after() : p_->cmap->u_after()); }

bool Reparameterization::target_reached() const {
  if (p_->map) {
    const MoebiusResult* m = p_->map->moebius_result();
    return !(m && m->target) || m->target->reached;
  }
  return p_->cmethod->kind != CompositeMethod::Kind::Target || p_->cmap->target_reached();
}

bool Reparameterization::is_rational() const {
  if (p_->map) {
    const MoebiusResult* m = p_->map->moebius_result();
    return m && m->exact.has_value();
  }
  return p_->cmethod->rational;
}

std::vector<Reparameterization::Joint> Reparameterization::breakpoints() const {
  return guarded(p_->opt, [&] {
    const long prec = joint_prec(p_->opt.digits);
    std::vector<Joint> out;
    if (p_->map) {
      for (std::size_t i = 0; i < p_->map->joints_s().size(); ++i)
        out.push_back(Joint{wrap(p_->map->joints_s()[i]), wrap(p_->map->joints_t()[i].to_ball(prec))});
    } else {
      for (const auto& [s, t] : p_->cmap->joints(cc_of(p_->curve), prec)) out.push_back(Joint{wrap(s), wrap(t)});
    }
    return out;
  });
}

Reparameterization::Sample Reparameterization::at(const Rational& s) const {
  return guarded(p_->opt, [&] {
    check_unit(unwrap(s));
    Sample out;
    sample_at(*p_, {unwrap(s)}, [&](std::size_t, const SamplePoint& p) { out = to_sample(p); });
    return out;
  });
}

Ball Reparameterization::eval_r(const Rational& s) const { return at(s).t; }

std::vector<Reparameterization::Sample> Reparameterization::samples(long K) const {
  return guarded(p_->opt, [&] {
    check_count("samples: K", K, 2, 1000000);
    std::vector<uniparam::Rational> s;
    for (long k = 0; k < K; ++k) s.emplace_back(k, K - 1);
    std::vector<Sample> out;
    sample_at(*p_, s, [&](std::size_t, const SamplePoint& p) {
      check_time_budget();
      out.push_back(to_sample(p));
    });
    return out;
  });
}

std::vector<Reparameterization::Formula> Reparameterization::formulas(api::Format f) const {
  return guarded(p_->opt, [&] {
    const uniparam::Format fmt =
        f == api::Format::Latex ? uniparam::Format::Latex
                                : (f == api::Format::Maple ? uniparam::Format::Maple : uniparam::Format::Text);
    const long digits = p_->opt.digits;
    std::vector<Formula> out;
    auto add = [&](std::size_t j, const uniparam::Curve& cv, const uniparam::Reparameterization& r) {
      if (const RadicalResult* x = r.radical_result()) {
        for (const auto& pf : radical_formulas(cv, *x, fmt, digits)) out.push_back(Formula{j, pf.z_interval, pf.r, pf.p_r, false});
      } else if (const MoebiusResult* x = r.moebius_result()) {
        for (const auto& pf : moebius_formulas(cv, *x, fmt, digits))
          out.push_back(Formula{j, pf.s_interval, pf.r, pf.p_r, pf.exact});
      } else {
        std::vector<std::string> p;
        for (const auto& comp : cv.components()) p.push_back(comp.str("s"));
        out.push_back(Formula{j, "[0, 1]", "s", p, true});
      }
    };
    if (p_->map) {
      add(0, cc_of(p_->curve).segment(0), *p_->map);
    } else {
      for (std::size_t j = 0; j < p_->cmap->parts().size(); ++j)
        add(j, cc_of(p_->curve).segment(j), p_->cmap->parts()[j]);
    }
    return out;
  });
}

Nurbs Reparameterization::nurbs() const {
  return guarded(p_->opt, [&] {
    const long prec = digits_to_bits(p_->opt.digits) + 32;
    auto impl = std::make_shared<Nurbs::Impl>();
    const std::string no = "nurbs: p o r is a NURBS for the Moebius methods and bezier_bilinear only; this map is " +
                           method();
    if (p_->bezier) {
      impl->n = bezier_nurbs(*p_->curve.impl().bezier, *p_->bezier, prec);
    } else if (p_->map) {
      const MoebiusResult* m = p_->map->moebius_result();
      if (!m) throw InvalidArgument(no);
      impl->n = moebius_nurbs(cc_of(p_->curve).segment(0), *m, prec);
    } else {
      if (p_->cmethod->kind == CompositeMethod::Kind::None || p_->cmethod->kind == CompositeMethod::Kind::Radical)
        throw InvalidArgument(no);
      impl->n = composite_nurbs(cc_of(p_->curve), *p_->cmap, prec);
    }
    return Nurbs(std::shared_ptr<const Nurbs::Impl>(std::move(impl)));
  });
}

Reparameterization Reparameterization::rational(long rational_digits) const {
  return guarded(p_->opt, [&] {
    check_count("rational: rational_digits", rational_digits, 1, 100);
    if (p_->bezier || (p_->map && !p_->map->moebius_result()) ||
        (p_->cmethod && (p_->cmethod->kind == CompositeMethod::Kind::None ||
                         p_->cmethod->kind == CompositeMethod::Kind::Radical)))
      throw InvalidArgument("rational: only the Moebius methods (moebius, moebius_pieces, moebius_breakpoints, "
                            "moebius_target) have a rational form; this map is " + method());
    auto impl = std::make_shared<Impl>(p_->curve, p_->opt, p_->iopt);
    impl->speeds = p_->speeds;
    if (p_->map) {
      impl->map.emplace(make_rational(cc_of(p_->curve).segment(0), *p_->map->moebius_result(), rational_digits,
                                      p_->iopt));
    } else {
      CompositeMethod m = *p_->cmethod;
      m.rational = true;
      m.rational_digits = rational_digits;
      impl->cmap.emplace(composite_map(cc_of(p_->curve), impl->speeds, m, p_->iopt));
      impl->cmethod = m;
    }
    return finish(std::move(impl));
  });
}

}  // namespace api
}  // namespace uniparam
