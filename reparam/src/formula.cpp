#include "uniparam/reparam/formula.hpp"

#include "uniparam/core/decimal.hpp"

namespace uniparam {

std::string format_decimal(const Ball& b, long digits, Format f) {
  std::string s = decimal_enclosure(b, digits).mid;
  if (f == Format::Latex) {
    auto e = s.find('e');
    if (e != std::string::npos) s = s.substr(0, e) + " \\cdot 10^{" + s.substr(e + 1) + "}";
  }
  return s;
}

namespace {

struct Fmt {
  Format f;
  long digits;
  std::string num(const Ball& b) const {
    std::string s = format_decimal(b, digits, f);
    return s[0] == '-' ? "(" + s + ")" : s;
  }
  std::string mul() const { return f == Format::Latex ? " " : "*"; }
  std::string frac(const std::string& a, const std::string& b) const {
    return f == Format::Latex ? "\\frac{" + a + "}{" + b + "}" : "(" + a + ")/(" + b + ")";
  }
  std::string root(const std::string& x, int k) const {
    if (k == 1) return x;
    if (f == Format::Latex) return k == 2 ? "\\sqrt{" + x + "}" : "\\sqrt[" + std::to_string(k) + "]{" + x + "}";
    return "(" + x + ")^(1/" + std::to_string(k) + ")";
  }
  std::string interval(const Ball& a, const Ball& b) const { return "[" + num(a) + ", " + num(b) + "]"; }
  // "x + c", "x - |c|", or "x" when c is exactly zero.
  std::string plus(const std::string& x, const Ball& c) const {
    if (arb_is_zero(c.get())) return x;
    std::string v = format_decimal(c, digits, f);
    if (v[0] == '-') return x + " - " + v.substr(1);
    return x + " + " + v;
  }
  // "c*x", or "x" where c is 1 or prints as "1"
  std::string times(const Ball& c, const std::string& x) const {
    if (arb_is_one(c.get())) return x;
    const std::string n = num(c);
    return n == "1" ? x : n + mul() + x;
  }
  // c + x (c first, omitted when exactly zero)
  std::string offset(const Ball& c, const std::string& x) const {
    if (arb_is_zero(c.get())) return x;
    return format_decimal(c, digits, f) + " + " + x;
  }
  // "c - x"
  std::string from(const Ball& c, const std::string& x) const { return format_decimal(c, digits, f) + " - " + x; }
  // c*(x), without the parentheses when x is a bare variable
  std::string scaled(const Ball& c, const std::string& x) const { return times(c, paren(x)); }
  static std::string paren(const std::string& x) { return x.size() == 1 ? x : "(" + x + ")"; }
  // c*(x), or x alone where c is 1 or prints as "1"
  std::string group(const Ball& c, const std::string& x) const {
    const std::string g = times(c, "(" + x + ")");
    return g == "(" + x + ")" ? x : g;
  }
};

// A Moebius piece of parameter a on [v_i, v_j] in its local variable,
//   x = (1 - a) (v - v_i) / (a (v_j - v) + (1 - a) (v - v_i)),
//   1 - x = a (v_j - v) / (the same denominator),
// a sum of two terms of one sign on the piece: no coefficient cancels, so the
// printed map keeps its shape however close a is to 0 or 1 (the expanded
// (A v + B) / (C v + D) does not: its coefficients differ from those of the
// identity by about a, below the printed digits when a < 10^-digits).
// a = 1/2 exactly gives the linear x = (v - v_i) / (v_j - v_i).
struct LocalMap {
  std::string x, one_minus_x;
};

LocalMap local_moebius(const Fmt& F, const Ball& a, const Ball& one_minus_a, const Ball& vi, const Ball& vj,
                       const std::string& v, long prec) {
  const std::string left = F.plus(v, [&] {
    Ball m;
    arb_neg(m.get(), vi.get());
    return m;
  }());
  const std::string right = F.from(vj, v);
  Ball half;
  arb_set_d(half.get(), 0.5);
  if (arb_equal(a.get(), half.get())) {
    Ball inv;
    arb_sub(inv.get(), vj.get(), vi.get(), prec);
    arb_inv(inv.get(), inv.get(), prec);
    return {F.scaled(inv, left), F.scaled(inv, right)};
  }
  const std::string num_x = F.scaled(one_minus_a, left), num_1x = F.scaled(a, right);
  const std::string den = num_1x + " + " + num_x;
  return {F.frac(num_x, den), F.frac(num_1x, den)};
}

// 1 - alpha to the relative accuracy of the piece's integrals: where alpha is
// their optimum 1/(1 + sqrt(C/A)), 1 - alpha = 1/(1 + sqrt(A/C)) keeps its
// digits when alpha is next to 1, where 1 - alpha from the ball alone would
// not; the result is the intersection of both enclosures.
Ball one_minus_alpha(const Ball& alpha, const PieceIntegrals* pi, long prec) {
  if (pi != nullptr) return pi->one_minus_alpha(prec);
  Ball r;
  arb_sub_ui(r.get(), alpha.get(), 1, prec);
  arb_neg(r.get(), r.get());
  return r;
}

// Replaces every standalone 't' in a component printed in format f by (arg).
std::string substitute_t(const std::string& expr, const std::string& arg) {
  std::string out;
  for (std::size_t i = 0; i < expr.size(); ++i) {
    if (expr[i] == 't' && (i == 0 || !isalpha(static_cast<unsigned char>(expr[i - 1]))) &&
        (i + 1 == expr.size() || !isalpha(static_cast<unsigned char>(expr[i + 1]))))
      out += "(" + arg + ")";
    else
      out += expr[i];
  }
  return out;
}

}  // namespace

std::vector<PieceFormulas> radical_formulas(const Curve& c, const RadicalResult& r, Format f, long digits) {
  const Fmt F{f, digits};
  const long prec = 4 * digits + 64;
  std::vector<PieceFormulas> out;
  for (std::size_t i = 0; i < r.pieces(); ++i) {
    PieceFormulas pf;
    const Ball ti = r.T[i].t.to_ball(prec), tj = r.T[i + 1].t.to_ball(prec);
    const Ball &si = r.S[i], &sj = r.S[i + 1], &zi = r.Z[i], &zj = r.Z[i + 1];
    const Ball& alpha = r.integrals[i].alpha;
    Ball dt, ds;
    arb_sub(dt.get(), tj.get(), ti.get(), prec);
    arb_sub(ds.get(), sj.get(), si.get(), prec);
    pf.s_interval = F.interval(si, sj);
    pf.z_interval = F.interval(zi, zj);
    const int k = r.root_index(i);
    const ZeroSide side = r.side(i);

    // phi_i(s): local s~ = (s - s_i) / Delta s, 1 - s~ = (s_{i+1} - s) / Delta s
    Ball inv_ds, neg_si;
    arb_inv(inv_ds.get(), ds.get(), prec);
    arb_neg(neg_si.get(), si.get());
    const LocalMap st{F.scaled(inv_ds, F.plus("s", neg_si)), F.scaled(inv_ds, F.from(sj, "s"))};
    // psi of the piece applied to a local variable given with its complement,
    // then t = t_i + Delta t psi: each 1 - y taken from the complement where
    // one is at hand, not by cancellation.
    auto apply_psi = [&](const LocalMap& x) {
      std::string y, one_minus_y;
      if (side == ZeroSide::Left) {
        y = F.root(x.x, k);
        one_minus_y = "1 - " + F.root(x.x, k);
      } else if (side == ZeroSide::Right) {
        y = "1 - " + F.root(x.one_minus_x, k);
        one_minus_y = F.root(x.one_minus_x, k);
      } else {
        y = x.x;
        one_minus_y = x.one_minus_x;
      }
      // the balancing map on the piece: y -> k y / (k y + 1 - y)
      if (!r.outer_k.empty()) {
        const std::string ky = F.times(r.outer_k[i], "(" + y + ")");
        y = F.frac(ky, ky + " + " + one_minus_y);
      }
      return F.offset(ti, F.group(dt, y));
    };
    pf.phi = apply_psi(st);

    // m_i(z) = s_i + Delta s x(z), x the piece's Moebius map in local form
    const LocalMap x = local_moebius(F, alpha, one_minus_alpha(alpha, &r.integrals[i], prec), zi, zj, "z", prec);
    pf.m = F.offset(si, F.group(ds, x.x));
    pf.r = apply_psi(x);
    for (const auto& comp : c.components()) pf.p_r.push_back(substitute_t(format_ratfunc(comp, f), pf.r));
    out.push_back(std::move(pf));
  }
  return out;
}

std::vector<MoebiusPieceFormulas> moebius_formulas(const Curve& c, const MoebiusResult& r, Format f, long digits) {
  const Fmt F{f, digits};
  const long prec = 4 * digits + 64;
  std::vector<MoebiusPieceFormulas> out;
  for (std::size_t i = 0; i < r.pieces(); ++i) {
    MoebiusPieceFormulas pf;
    if (r.exact.has_value()) {
      // exact: t = (A s + B) / (C s + D) with C = 1 - 2a, D = a ds - C s_i,
      // A = t_i C + dt (1 - a), B = t_i D - dt (1 - a) s_i.
      const Rational &ti = r.exact->T[i], &tj = r.exact->T[i + 1], &si = r.exact->S[i], &sj = r.exact->S[i + 1];
      const Rational& a = r.exact->alpha[i];
      const Rational dt = tj - ti, ds = sj - si, C = Rational(1) - Rational(2) * a, D = a * ds - C * si;
      const Rational A = ti * C + dt * (Rational(1) - a), B = ti * D - dt * (Rational(1) - a) * si;
      const RatFunc s = RatFunc::t();
      const RatFunc rf = (RatFunc(A) * s + RatFunc(B)) / (RatFunc(C) * s + RatFunc(D));
      pf.exact = true;
      pf.s_interval = "[" + format_rational(si, f) + ", " + format_rational(sj, f) + "]";
      pf.t_interval = "[" + format_rational(ti, f) + ", " + format_rational(tj, f) + "]";
      pf.r = format_ratfunc(rf, f, "s");
      for (const auto& comp : c.components()) pf.p_r.push_back(format_ratfunc(compose(comp, rf), f, "s"));
    } else {
      const Ball ti = r.T[i].t.to_ball(prec), tj = r.T[i + 1].t.to_ball(prec);
      const Ball &si = r.S[i], &sj = r.S[i + 1], &a = r.alpha[i];
      Ball dt;
      arb_sub(dt.get(), tj.get(), ti.get(), prec);
      // t = t_i + Delta t x(s); 1 - alpha from the integrals where alpha is their optimum (C0)
      const PieceIntegrals* pi =
          r.continuity == Continuity::C0 && arb_equal(a.get(), r.integrals[i].alpha.get()) ? &r.integrals[i] : nullptr;
      const LocalMap x = local_moebius(F, a, one_minus_alpha(a, pi, prec), si, sj, "s", prec);
      pf.s_interval = F.interval(si, sj);
      pf.t_interval = F.interval(ti, tj);
      pf.r = F.offset(ti, F.group(dt, x.x));
      for (const auto& comp : c.components()) pf.p_r.push_back(substitute_t(format_ratfunc(comp, f), pf.r));
    }
    out.push_back(std::move(pf));
  }
  return out;
}

}  // namespace uniparam
