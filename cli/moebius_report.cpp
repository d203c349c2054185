#include "moebius_report.hpp"

#include <cstdio>
#include <iostream>

#include "output.hpp"
#include "report.hpp"

namespace uniparam::cli {

Json moebius_json(const Curve& c, const MoebiusResult& r, long digits, const MoebiusPrint& how) {
  const long pd = printed_digits(digits);
  const std::size_t N = r.pieces();
  const auto formulas = moebius_formulas(c, r, how.format, digits);
  {
    Json j = Json::object();
    j.set("curve", Json::string(c.str()));
    j.set("speed", Json::string(to_string(r.kind)));
    j.set("digits", Json::number(digits));
    j.set("continuity", Json::string(to_string(r.continuity)));
    Json t = Json::array(), s = Json::array(), al = Json::array();
    for (const auto& b : r.T) t.push(json_algebraic(b.t, digits));
    for (std::size_t i = 0; i <= N; ++i) s.push(r.exact.has_value() ? json_rational(r.exact->S[i], pd) : json_ball(r.S[i], pd));
    for (std::size_t i = 0; i < N; ++i)
      al.push(r.exact.has_value() ? json_rational(r.exact->alpha[i], pd) : json_ball(r.alpha[i], pd));
    j.set("t", t);
    j.set("s", s);
    j.set("alpha", al);
    j.set("mu", json_ball(r.mu, pd));
    j.set("u_before", json_ball(r.u_before, pd));
    j.set("u_after", json_ball(r.u_after, pd));
    j.set("speed_vanishes", Json::boolean(r.speed_vanishes));
    j.set("rational", Json::boolean(r.exact.has_value()));
    if (r.optimiser.has_value()) {
      Json o = Json::object();
      o.set("iterations", Json::number(r.optimiser->iterations));
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.3e", r.optimiser->stationarity);
      o.set("stationarity", Json::number(std::string(buf)));
      o.set("stationarity_certified", Json::boolean(false));
      if (arb_is_finite(r.optimiser->phi.get()) && !r.exact.has_value()) o.set("phi", json_ball(r.optimiser->phi, pd));
      o.set("phi_equal_spacing", json_ball(r.optimiser->phi_equal, 12));
      j.set("optimiser", o);
    }
    if (r.target.has_value()) {
      Json o = Json::object();
      o.set("value", json_rational(r.target->value, pd));
      o.set("reached", Json::boolean(r.target->reached));
      o.set("refinement_rounds", Json::number(r.target->rounds));
      j.set("target", o);
    }
    if (how.formulas) {
      Json pieces = Json::array();
      for (std::size_t i = 0; i < N; ++i) {
        Json p = Json::object();
        p.set("t_interval", Json::array().push(json_algebraic(r.T[i].t, digits)).push(json_algebraic(r.T[i + 1].t, digits)));
        p.set("s_interval", Json::string(formulas[i].s_interval));
        p.set("r", Json::string(formulas[i].r));
        Json pr = Json::array();
        for (const auto& x : formulas[i].p_r) pr.push(Json::string(x));
        p.set("p_r", pr);
        p.set("exact", Json::boolean(formulas[i].exact));
        pieces.push(p);
      }
      j.set("pieces", pieces);
    }
    return j;
  }
}

void print_moebius(const Curve& c, const MoebiusResult& r, long digits, const MoebiusPrint& how) {
  if (how.json) {
    answer() << moebius_json(c, r, digits, how).dump(2) << "\n";
    return;
  }
  const long pd = printed_digits(digits);
  const std::size_t N = r.pieces();
  const auto formulas = moebius_formulas(c, r, how.format, digits);
  answer() << "curve      " << c.str() << "\nspeed      " << to_string(r.kind) << "\n"
            << "continuity " << to_string(r.continuity) << (r.exact.has_value() ? " (exact rational map)" : "") << "\n";
  if (r.identically_zero) answer() << "the angular speed is identically zero (a straight line): r = id, u = 1\n";
  for (std::size_t i = 0; i < N; ++i) {
    answer() << "piece " << i << "    t in [" << text_algebraic(r.T[i].t, digits) << ", "
              << text_algebraic(r.T[i + 1].t, digits) << "], s in [";
    if (r.exact.has_value())
      answer() << r.exact->S[i].str() << ", " << r.exact->S[i + 1].str() << "], alpha = " << r.exact->alpha[i].str();
    else
      answer() << r.S[i].mid_decimal(pd) << ", " << r.S[i + 1].mid_decimal(pd)
                << "], alpha = " << format_ball(r.alpha[i], pd, Format::Text);
    answer() << "\n";
  }
  answer() << "mu         " << format_ball(r.mu, pd, Format::Text) << "\n"
            << "u before   " << format_ball(r.u_before, pd, Format::Text) << "\n"
            << "u after    " << format_ball(r.u_after, pd, Format::Text) << "\n";
  if (r.optimiser.has_value())
    answer() << "optimiser  " << r.optimiser->iterations << " iterations, stationarity " << r.optimiser->stationarity
              << " (relative gradient, floating point)\n";
  if (r.target.has_value())
    answer() << "target     u >= " << r.target->value.str() << (r.target->reached ? " reached" : " NOT reached")
              << " with " << N << " pieces after " << r.target->rounds << " refinement rounds\n";
  if (r.speed_vanishes)
    answer() << "note: the speed vanishes in [0, 1]; rational maps cannot lift its zeros "
                 "(see 'uniparam radical')\n";
  if (how.formulas) {
    answer() << "\nformulas (" << (r.exact.has_value() ? "exact" : "coefficients rounded to the printed digits") << "):\n";
    for (std::size_t i = 0; i < N; ++i) {
      answer() << "piece " << i << ", s in " << formulas[i].s_interval << ":\n  t = " << formulas[i].r << "\n";
      for (std::size_t k = 0; k < formulas[i].p_r.size(); ++k)
        answer() << "  p_" << k + 1 << "(r(s)) = " << formulas[i].p_r[k] << "\n";
    }
  }
}

std::string missed_u_text(const Ball& u, const Rational& target, long digits) {
  for (long k = 8; k <= printed_digits(digits); ++k) {
    const std::string text = u.mid_decimal(k);
    if (Rational::parse(text) < target) return text;
  }
  return format_ball(u, printed_digits(digits), Format::Text);
}

std::string target_missed_message(const MoebiusResult& r, long max_pieces, long digits, const std::string& use) {
  std::string m = "the target u >= " + r.target->value.str() + " was not reached with at most " +
                  std::to_string(max_pieces) + (max_pieces == 1 ? " piece" : " pieces") + "; the best map found is " +
                  use + " (" + std::to_string(r.pieces()) +
                  (r.pieces() == 1 ? " piece" : " pieces") + ", u = " +
                  missed_u_text(r.u_after, r.target->value, digits) + "); ";
  if (r.target->draft_failed)
    return m + "the floating-point search for more breakpoints cannot represent this curve's integrals "
               "(beyond double's range): lower --target, or choose the pieces with --pieces N";
  if (max_pieces < kMaxPiecesLimit)
    return m + "raise --max-pieces (at most " + std::to_string(kMaxPiecesLimit) + ") to try more pieces";
  return m + std::to_string(kMaxPiecesLimit) + " pieces is the most --max-pieces allows: lower --target";
}

}  // namespace uniparam::cli
