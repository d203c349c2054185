// uniparam/reparam/formula.hpp -- the pieces of a reparameterization as
// formulas (text, LaTeX, Maple), ready to paste elsewhere.
//
// Exact data (rational breakpoints) print exactly; certified balls print as
// their midpoints with `digits` significant digits (the balls meet that
// accuracy; the printed coefficients are rounded values, not enclosures: use the
// JSON output or the evaluation functions of radical.hpp for certified numbers).
#pragma once

#include <string>
#include <vector>

#include "uniparam/core/printer.hpp"
#include "uniparam/reparam/curve.hpp"
#include "uniparam/reparam/moebius.hpp"
#include "uniparam/reparam/radical.hpp"

namespace uniparam {

/// The formulas of one piece of r = phi o m on [z_i, z_{i+1}].
struct PieceFormulas {
  std::string s_interval, z_interval;  ///< "[s_i, s_{i+1}]", "[z_i, z_{i+1}]"
  std::string phi;   ///< t = phi_i(s)
  /// s = m_i(z) = s_i + Delta s x(z), the Moebius map in its local form
  /// x = (1 - a)(z - z_i) / (a (z_{i+1} - z) + (1 - a)(z - z_i)), a = alpha_i:
  /// no printed coefficient cancels, however close alpha_i is to 0 or 1.
  /// phi and r use the same local forms.
  std::string m;
  std::string r;     ///< t = r_i(z)
  std::vector<std::string> p_r;  ///< components of p(r_i(z))
};

/// Formulas of every piece of a radical (or piecewise Moebius) result.
std::vector<PieceFormulas> radical_formulas(const Curve& c, const RadicalResult& r, Format f, long digits);

/// The formulas of one piece of a piecewise Moebius map on [s_i, s_{i+1}].
struct MoebiusPieceFormulas {
  std::string s_interval, t_interval;  ///< "[s_i, s_{i+1}]", "[t_i, t_{i+1}]"
  /// t = r_i(s): with exact data (A s + B) / (C s + D), expanded; otherwise
  /// t_i + Delta t x(s), x in the local form of PieceFormulas::m.
  std::string r;
  std::vector<std::string> p_r;        ///< components of p(r_i(s))
  bool exact = false;                  ///< rational data: every formula is exact
};

/// Formulas of every piece of r. With exact data (r.exact) the coefficients are exact
/// rationals and p(r_i(s)) is expanded exactly (same degree as p); otherwise
/// they are midpoints of certified balls with `digits` digits and p(r_i(s))
/// is p with t replaced by r_i(s).
std::vector<MoebiusPieceFormulas> moebius_formulas(const Curve& c, const MoebiusResult& r, Format f, long digits);

/// A decimal for a ball's midpoint in the given format ("1.25e-30" becomes
/// "1.25 \cdot 10^{-30}" in LaTeX, "1.25e-30" in text and Maple).
std::string format_decimal(const Ball& b, long digits, Format f);

}  // namespace uniparam
