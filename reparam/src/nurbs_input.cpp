// NURBS / B-spline input to exact Bezier segments (path.hpp; docs/inputs.md).
//
// The segment of the knot span [a, b] = [u_j, u_{j+1}] has the control
// points f(a^(p-k), b^k), k = 0..p, of the curve's blossom f there (de Boor
// 1972; Ramshaw 1989). The blossom of the homogeneous (w P, w) is evaluated
// by de Boor's recursion with one argument per level:
//     d_i <- (1 - alpha) d_{i-1} + alpha d_i,  alpha = (t_r - u_i) / (u_{i+p+1-r} - u_i),
// for r = 1..p and i = j down to j - p + r, starting from d_i = (w_i P_i, w_i),
// i = j-p..j; the denominators are positive for a nonempty span and alpha
// lies in [0, 1] for t_r in {a, b}, so positive weights stay positive.
#include <algorithm>

#include "uniparam/core/error.hpp"
#include "uniparam/reparam/path.hpp"

namespace uniparam {

namespace {

std::string index_name(const char* what, std::size_t i) { return std::string(what) + " " + std::to_string(i); }

}  // namespace

PathInput parse_nurbs_json(const JsonValue& j, const NurbsLimits& limits) {
  const auto& members = j.as_object("a NURBS description");
  for (const auto& m : members)
    if (m.first != "degree" && m.first != "knots" && m.first != "control" && m.first != "weights")
      throw InvalidArgument("NURBS: unknown key " + json_quote(m.first) +
                            " (expected \"degree\", \"knots\", \"control\" and optionally \"weights\")");
  auto need = [&](const char* key) -> const JsonValue& {
    const JsonValue* v = j.find(key);
    if (!v) throw InvalidArgument(std::string("NURBS: missing key \"") + key + "\"");
    return *v;
  };
  const long p = need("degree").as_long("NURBS \"degree\"", 1, limits.max_degree);
  const auto& control = need("control").as_array("NURBS \"control\"");
  const auto& knots_json = need("knots").as_array("NURBS \"knots\"");
  const JsonValue* weights_json = j.find("weights");

  const std::size_t np = control.size();  // n + 1
  if (np < static_cast<std::size_t>(p) + 1)
    throw InvalidArgument("NURBS: degree " + std::to_string(p) + " needs at least " + std::to_string(p + 1) +
                          " control points, got " + std::to_string(np));
  if (np > limits.max_points)
    throw InvalidArgument("NURBS: more than " + std::to_string(limits.max_points) + " control points");
  std::vector<std::vector<Rational>> pts;
  pts.reserve(np);
  std::size_t dim = 0;
  for (std::size_t i = 0; i < np; ++i) {
    const auto& c = control[i].as_array("NURBS " + index_name("control point", i));
    if (i == 0) {
      dim = c.size();
      if (dim < 2)
        throw InvalidArgument("NURBS: control points need at least 2 coordinates, control point 0 has " +
                              std::to_string(dim));
    } else if (c.size() != dim) {
      throw InvalidArgument("NURBS: control point " + std::to_string(i) + " has " + std::to_string(c.size()) +
                            " coordinates, control point 0 has " + std::to_string(dim));
    }
    std::vector<Rational> q;
    q.reserve(dim);
    for (std::size_t k = 0; k < dim; ++k)
      q.push_back(c[k].as_rational("NURBS control point " + std::to_string(i) + " coordinate " + std::to_string(k)));
    pts.push_back(std::move(q));
  }

  const std::size_t nk = np + static_cast<std::size_t>(p) + 1;  // n + p + 2
  if (knots_json.size() != nk)
    throw InvalidArgument("NURBS: " + std::to_string(np) + " control points of degree " + std::to_string(p) +
                          " need " + std::to_string(nk) + " knots (control points + degree + 1), got " +
                          std::to_string(knots_json.size()));
  std::vector<Rational> u;
  u.reserve(nk);
  for (std::size_t i = 0; i < nk; ++i) {
    u.push_back(knots_json[i].as_rational("NURBS " + index_name("knot", i)));
    if (i > 0 && u[i] < u[i - 1])
      throw InvalidArgument("NURBS: the knots must be non-decreasing, but knot " + std::to_string(i) + " = " +
                            u[i].str() + " is below knot " + std::to_string(i - 1) + " = " + u[i - 1].str());
  }
  const std::size_t lo = static_cast<std::size_t>(p), hi = np;  // domain [u_p, u_{n+1}]
  if (!(u[lo] < u[hi]))
    throw InvalidArgument("NURBS: empty domain: knot " + std::to_string(lo) + " = knot " + std::to_string(hi) +
                          " = " + u[lo].str() + " (the curve lives on [u_p, u_{n+1}])");
  for (std::size_t i = 0; i < nk;) {
    std::size_t e = i;
    while (e < nk && u[e] == u[i]) ++e;
    const std::size_t mult = e - i;
    const bool inside = u[lo] < u[i] && u[i] < u[hi];
    if (mult > static_cast<std::size_t>(p) + 1 || (inside && mult > static_cast<std::size_t>(p)))
      throw InvalidArgument("NURBS: knot " + u[i].str() + " (knots " + std::to_string(i) + " to " +
                            std::to_string(e - 1) + ") has multiplicity " + std::to_string(mult) + ", above " +
                            std::to_string(inside ? p : p + 1) +
                            (inside ? " (the degree) inside the domain: the curve would break there"
                                    : " (degree + 1)"));
    i = e;
  }

  std::vector<Rational> w;
  bool rational = false;
  if (weights_json) {
    const auto& wj = weights_json->as_array("NURBS \"weights\"");
    if (wj.size() != np)
      throw InvalidArgument("NURBS: " + std::to_string(np) + " control points need " + std::to_string(np) +
                            " weights, got " + std::to_string(wj.size()));
    for (std::size_t i = 0; i < np; ++i) {
      w.push_back(wj[i].as_rational("NURBS " + index_name("weight", i)));
      if (w.back().sign() <= 0)
        throw InvalidArgument("NURBS: weight " + std::to_string(i) + " = " + w.back().str() + " is not positive");
      if (w.back() != w.front()) rational = true;
    }
  }

  // Homogeneous control points (w P, w), or P alone for an integral curve.
  const std::size_t hd = rational ? dim + 1 : dim;
  std::vector<std::vector<Rational>> hom(np, std::vector<Rational>(hd));
  for (std::size_t i = 0; i < np; ++i) {
    for (std::size_t k = 0; k < dim; ++k) hom[i][k] = rational ? w[i] * pts[i][k] : pts[i][k];
    if (rational) hom[i][dim] = w[i];
  }

  PathInput out;
  const Rational width = u[hi] - u[lo];
  out.knots.push_back(Rational(0));
  for (std::size_t jspan = lo; jspan < hi; ++jspan) {
    if (!(u[jspan] < u[jspan + 1])) continue;
    const Rational& a = u[jspan];
    const Rational& b = u[jspan + 1];
    std::vector<std::vector<Rational>> bez_pts;
    std::vector<Rational> bez_w;
    for (long k = 0; k <= p; ++k) {
      // f(a^(p-k), b^k): de Boor with arguments t_r = b for r <= k, a after.
      std::vector<std::vector<Rational>> d(hom.begin() + static_cast<long>(jspan) - p,
                                           hom.begin() + static_cast<long>(jspan) + 1);
      for (long r = 1; r <= p; ++r) {
        const Rational& t = r <= k ? b : a;
        for (long i = static_cast<long>(jspan); i >= static_cast<long>(jspan) - p + r; --i) {
          const Rational alpha = (t - u[i]) / (u[i + p + 1 - r] - u[i]);
          auto& di = d[static_cast<std::size_t>(i - (static_cast<long>(jspan) - p))];
          const auto& dm = d[static_cast<std::size_t>(i - 1 - (static_cast<long>(jspan) - p))];
          for (std::size_t c = 0; c < hd; ++c) di[c] = dm[c] + alpha * (di[c] - dm[c]);
        }
      }
      std::vector<Rational>& h = d[static_cast<std::size_t>(p)];
      if (rational) {
        const Rational wk = h[dim];
        std::vector<Rational> q(dim);
        for (std::size_t c = 0; c < dim; ++c) q[c] = h[c] / wk;
        bez_pts.push_back(std::move(q));
        bez_w.push_back(wk);
      } else {
        bez_pts.push_back(std::move(h));
      }
    }
    const std::string label = "span [" + a.str() + ", " + b.str() + "] (knots " + std::to_string(jspan) + " and " +
                              std::to_string(jspan + 1) + ")";
    if (std::all_of(bez_pts.begin(), bez_pts.end(), [&](const auto& q) { return q == bez_pts.front(); }))
      throw InvalidArgument("NURBS: the " + label +
                            " is a single point (its control points are equal); uniparam does not drop it, since "
                            "that would change the parameterization the knots give");
    out.segments.emplace_back(std::move(bez_pts), std::move(bez_w));
    out.labels.push_back(label);
    out.knots.push_back((b - u[lo]) / width);
  }
  return out;
}

PathInput parse_nurbs(const std::string& text, const NurbsLimits& limits, const JsonLimits& json_limits) {
  return parse_nurbs_json(parse_json(text, json_limits), limits);
}

}  // namespace uniparam
