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
  // "c*x", "x" for c = 1, "-x" for c = -1
  std::string times(const Ball& c, const std::string& x) const {
    if (arb_is_one(c.get())) return x;
    return num(c) + mul() + x;
  }
  // a*var + b
  std::string linear(const Ball& a, const Ball& b, const char* var) const { return plus(times(a, var), b); }
  // c + x (c first, omitted when exactly zero)
  std::string offset(const Ball& c, const std::string& x) const {
    if (arb_is_zero(c.get())) return x;
    return format_decimal(c, digits, f) + " + " + x;
  }
};

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
    Ball dt, ds, dz;
    arb_sub(dt.get(), tj.get(), ti.get(), prec);
    arb_sub(ds.get(), sj.get(), si.get(), prec);
    arb_sub(dz.get(), zj.get(), zi.get(), prec);
    pf.s_interval = F.interval(si, sj);
    pf.z_interval = F.interval(zi, zj);
    const int k = r.root_index(i);
    const ZeroSide side = r.side(i);

    // phi_i(s): local s~ = (s - s_i) / Delta s = s/Ds - s_i/Ds
    Ball a1, b1;
    arb_inv(a1.get(), ds.get(), prec);
    arb_div(b1.get(), si.get(), ds.get(), prec);
    arb_neg(b1.get(), b1.get());
    const std::string st = F.linear(a1, b1, "s");
    auto apply_psi = [&](const std::string& x) {
      std::string y;
      if (side == ZeroSide::Left) y = F.root(x, k);
      else if (side == ZeroSide::Right) y = "1 - " + F.root("1 - (" + x + ")", k);
      else y = x;
      // the balancing map on the piece: y -> k y / (k y + 1 - y)
      if (!r.outer_k.empty()) {
        const std::string ky = F.times(r.outer_k[i], "(" + y + ")");
        y = F.frac(ky, ky + " + 1 - (" + y + ")");
      }
      return F.offset(ti, F.times(dt, "(" + y + ")"));
    };
    pf.phi = apply_psi(st);

    // x(z) = (1-a) u / ((1-2a) u + a Dz), u = z - z_i; as (A z + B)/(C z + D)
    Ball one_a, one_2a, A, B, C, D, tmp;
    arb_sub_ui(one_a.get(), alpha.get(), 1, prec);
    arb_neg(one_a.get(), one_a.get());
    arb_mul_2exp_si(one_2a.get(), alpha.get(), 1);
    arb_sub_ui(one_2a.get(), one_2a.get(), 1, prec);
    arb_neg(one_2a.get(), one_2a.get());
    A = one_a;
    arb_mul(B.get(), one_a.get(), zi.get(), prec);
    arb_neg(B.get(), B.get());
    C = one_2a;
    arb_mul(D.get(), alpha.get(), dz.get(), prec);
    arb_mul(tmp.get(), one_2a.get(), zi.get(), prec);
    arb_sub(D.get(), D.get(), tmp.get(), prec);
    const std::string x = F.frac(F.linear(A, B, "z"), F.linear(C, D, "z"));
    // m_i(z) = s_i + Ds x = ((s_i C + Ds A) z + (s_i D + Ds B)) / (C z + D)
    Ball mA, mB;
    arb_mul(mA.get(), si.get(), C.get(), prec);
    arb_addmul(mA.get(), ds.get(), A.get(), prec);
    arb_mul(mB.get(), si.get(), D.get(), prec);
    arb_addmul(mB.get(), ds.get(), B.get(), prec);
    pf.m = F.frac(F.linear(mA, mB, "z"), F.linear(C, D, "z"));
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
    // t = (A s + B) / (C s + D) with C = 1 - 2a, D = a ds - C s_i,
    // A = t_i C + dt (1 - a), B = t_i D - dt (1 - a) s_i.
    if (r.exact.has_value()) {
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
      Ball dt, ds, oma, C, D, A, B, t;
      arb_sub(dt.get(), tj.get(), ti.get(), prec);
      arb_sub(ds.get(), sj.get(), si.get(), prec);
      arb_sub_ui(oma.get(), a.get(), 1, prec);
      arb_neg(oma.get(), oma.get());
      arb_mul_2exp_si(C.get(), a.get(), 1);
      arb_sub_ui(C.get(), C.get(), 1, prec);
      arb_neg(C.get(), C.get());
      arb_mul(D.get(), a.get(), ds.get(), prec);
      arb_submul(D.get(), C.get(), si.get(), prec);
      arb_mul(t.get(), dt.get(), oma.get(), prec);
      arb_mul(A.get(), ti.get(), C.get(), prec);
      arb_add(A.get(), A.get(), t.get(), prec);
      arb_mul(B.get(), ti.get(), D.get(), prec);
      arb_submul(B.get(), t.get(), si.get(), prec);
      pf.s_interval = F.interval(si, sj);
      pf.t_interval = F.interval(ti, tj);
      pf.r = F.frac(F.linear(A, B, "s"), F.linear(C, D, "s"));
      for (const auto& comp : c.components()) pf.p_r.push_back(substitute_t(format_ratfunc(comp, f), pf.r));
    }
    out.push_back(std::move(pf));
  }
  return out;
}

}  // namespace uniparam
