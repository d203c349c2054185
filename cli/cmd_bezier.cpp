// cli/cmd_bezier.cpp -- `uniparam bezier --control POINTS [--weights LIST]`:
// the optimal bilinear reparameterization of a Bezier curve for the
// parametric speed (Juettler 1997, eqs. 21-22; docs/math.md section 2).
#include <iostream>

#include "commands.hpp"
#include "output.hpp"
#include "nurbs_out.hpp"
#include "json_reports.hpp"
#include "report.hpp"
#include "uniparam/reparam/bezier.hpp"

namespace uniparam::cli {

CommandSpec bezier_spec() {
  std::vector<OptionSpec> opts;
  for (auto& o : common_options())
    if (o.name != "speed") opts.push_back(o);  // always the parametric speed
  opts.push_back({"format", "F", "exact values (P, Q, alpha, weights): text, latex, maple (or json, the same as --json)", "text"});
  opts.push_back({"exact-weights", "FORM",
                  "integral curves: the exact new weights as 'expanded' surds, as the 'formula' in alpha, or "
                  "'auto' (expanded while each has at most 4096 characters; their size grows like the degree squared)",
                  "auto"});
  opts.push_back(nurbs_output_option());
  return {"bezier",
          "Optimal bilinear (Moebius) reparameterization of a Bezier curve for the parametric speed.",
          "Integral curves (no --weights): P and Q of Juettler 1997, eq. (21) as exact rationals,\n"
          "alpha, the root in (0, 1) of P (1-alpha)^2 + Q alpha^2 = 0, as an exact quadratic\n"
          "surd, and the new weights w_i = (1-alpha)^i alpha^(n-i) exactly. Rational curves\n"
          "(--weights): P, Q and alpha by certified quadrature, new weights v_i w_i.\n"
          "Also the arc length mu and the uniformity u of |p'| before and after.\n"
          "Control points are exact rationals in any dimension >= 2, e.g.\n"
          "--control \"[[0,0],[1/3,1],[1,0.25]]\".",
          {},
          opts};
}

namespace {

/// The exact weights' formula in alpha, in format f, for degree n.
std::string weights_formula(long n, Format f) {
  const std::string N = std::to_string(n);
  switch (f) {
    case Format::Latex: return "w_i = (1-\\alpha)^{i}\\,\\alpha^{" + N + "-i}";
    case Format::Maple: return "w[i] = (1-alpha)^i*alpha^(" + N + "-i)";
    default: return "w_i = (1-alpha)^i * alpha^(" + N + "-i)";
  }
}

}  // namespace

// 'auto' bounds the size of the largest, w_0 = alpha^n, by n times the size
// of alpha's own text (without forming it).
bool expand_weights(const std::string& form, const BezierResult& r, long n) {
  if (form == "expanded") return true;
  if (form == "formula") return false;
  if (form != "auto")
    throw InvalidArgument("--exact-weights expects expanded, formula or auto, got '" + form + "'");
  if (!r.exact || r.alpha_exact->is_rational()) return true;
  return static_cast<double>(r.alpha_exact->str(Format::Text).size()) * static_cast<double>(n) <= 4096.0;
}


Json bezier_json(const BezierCurve& bz, const BezierResult& r, long digits, bool expanded) {
  const long pd = printed_digits(digits);
  const Curve c = bz.to_curve();
  const std::size_t n1 = r.weights.size();
  Json j = Json::object();
  j.set("control", Json::string(bz.str()));
  if (bz.is_rational()) {
    Json w = Json::array();
    for (const auto& v : bz.weights()) w.push(Json::string(v.str()));
    j.set("input_weights", w);
  }
  j.set("degree", Json::number(bz.degree()));
  j.set("dimension", Json::number(static_cast<long>(bz.dimension())));
  j.set("curve", Json::string(c.str()));
  j.set("speed", Json::string("parametric"));
  j.set("digits", Json::number(digits));
  j.set("exact", Json::boolean(r.exact));
  if (r.exact) {
    j.set("P", json_rational(*r.P_exact, pd));
    j.set("Q", json_rational(*r.Q_exact, pd));
    Json al = json_surd(*r.alpha_exact, r.alpha, pd);
    if (!r.alpha_exact->is_rational()) {
      // the surd's text, plus its defining polynomial and isolating interval
      Json e = Json::object();
      e.set("text", Json::string(r.alpha_exact->str(Format::Text)));
      e.set("latex", Json::string(r.alpha_exact->str(Format::Latex)));
      e.set("maple", Json::string(r.alpha_exact->str(Format::Maple)));
      e.set("poly", Json::string(r.alpha_algebraic->poly().str()));
      auto [lo, hi] = short_interval(*r.alpha_algebraic);
      e.set("interval", Json::array().push(Json::string(lo.str())).push(Json::string(hi.str())));
      al.set("exact", e);
    }
    j.set("alpha", al);
    Json w = Json::array();
    for (std::size_t i = 0; i < n1; ++i)
      w.push(expanded ? json_surd(r.weights_exact[i], r.weights[i], pd) : json_ball(r.weights[i], pd));
    j.set("weights", w);
    if (!expanded) {
      Json e = Json::object();
      e.set("text", Json::string(weights_formula(bz.degree(), Format::Text)));
      e.set("latex", Json::string(weights_formula(bz.degree(), Format::Latex)));
      e.set("maple", Json::string(weights_formula(bz.degree(), Format::Maple)));
      j.set("weights_formula", e);
    }
    j.set("mean_square", json_rational(*r.mean_square_exact, pd));
  } else {
    j.set("P", json_ball(r.P, pd));
    j.set("Q", json_ball(r.Q, pd));
    j.set("alpha", json_ball(r.alpha, pd));
    j.set("weights", json_balls(r.weights, pd));
  }
  j.set("mu", json_ball(r.mu, pd));
  j.set("u_before", json_ball(r.u_before, pd));
  j.set("u_after", json_ball(r.u_after, pd));
  return j;
}

int run_bezier(int argc, char** argv) {
  const CommandSpec spec = bezier_spec();
  Args a = parse_args(spec, argc, argv, 2);
  if (a.help) { answer() << help_text(spec); return 0; }
  const Options opt = read_options(a);
  const Format fmt = read_format(a);
  const NurbsOutput no = read_nurbs_output(a);
  const BezierCurve bz = read_bezier(a);
  const Curve c = bz.to_curve();
  const BezierResult r = bezier_optimal(bz, opt);
  const long pd = printed_digits(opt.digits);
  const std::size_t n1 = r.weights.size();
  const bool expanded = expand_weights(a.get("exact-weights", "auto"), r, bz.degree());
  if (no.form != NurbsOutput::Form::None) {
    Nurbs n = bezier_nurbs(bz, r, nurbs_prec(opt));
    if (!expanded && n.kind == Nurbs::Kind::Surd) {
      // --exact-weights: surds too long to print; the certified balls instead
      n.kind = Nurbs::Kind::Balls;
      n.weights_surd.clear();
    }
    write_nurbs(n, no, opt.digits);
    if (no.replaces_report()) return 0;
  }

  if (wants_json(a)) {
    answer() << bezier_json(bz, r, opt.digits, expanded).dump(2) << "\n";
    return 0;
  }

  answer() << "control    " << bz.str() << "\n";
  if (bz.is_rational()) {
    answer() << "weights in [";
    const auto v = bz.weights();
    for (std::size_t i = 0; i < v.size(); ++i) answer() << (i ? ", " : "") << format_rational(v[i], fmt);
    answer() << "]\n";
  }
  answer() << "bezier     degree " << bz.degree() << ", dimension " << bz.dimension() << ", "
            << (bz.is_rational() ? "rational" : "integral") << "\n"
            << "curve      " << c.str() << "\n"
            << "speed      parametric\n";
  if (r.exact) {
    answer() << "P          " << format_rational(*r.P_exact, fmt) << "  (-int (1-t)^2 |p'|^2, exact)\n"
              << "Q          " << format_rational(*r.Q_exact, fmt) << "  (int t^2 |p'|^2, exact)\n"
              << "alpha      " << r.alpha_exact->str(fmt);
    if (!r.alpha_exact->is_rational()) answer() << " = " << format_ball(r.alpha, pd, Format::Text);
    answer() << "\n";
    if (expanded) {
      for (std::size_t i = 0; i < n1; ++i) {
        answer() << (i ? "           w_" : "weights    w_") << i << " = " << r.weights_exact[i].str(fmt);
        if (!r.weights_exact[i].is_rational()) answer() << " = " << format_ball(r.weights[i], pd, Format::Text);
        answer() << "\n";
      }
    } else {
      answer() << "weights    " << weights_formula(bz.degree(), fmt) << "  (exact; --exact-weights expanded to expand)\n";
      for (std::size_t i = 0; i < n1; ++i)
        answer() << "           w_" << i << " = " << format_ball(r.weights[i], pd, Format::Text) << "\n";
    }
  } else {
    answer() << "P          " << format_ball(r.P, pd, Format::Text) << "  (-int (1-t)^2 |p'|^2, certified quadrature)\n"
              << "Q          " << format_ball(r.Q, pd, Format::Text) << "  (int t^2 |p'|^2, certified quadrature)\n"
              << "alpha      " << format_ball(r.alpha, pd, Format::Text) << "\n";
    for (std::size_t i = 0; i < n1; ++i)
      answer() << (i ? "           w_" : "weights    w_") << i << " = " << format_ball(r.weights[i], pd, Format::Text)
                << "\n";
  }
  answer() << "mu         " << format_ball(r.mu, pd, Format::Text) << "  (arc length)\n"
            << "u before   " << format_ball(r.u_before, pd, Format::Text) << "\n"
            << "u after    " << format_ball(r.u_after, pd, Format::Text) << "\n";
  return 0;
}

}  // namespace uniparam::cli
