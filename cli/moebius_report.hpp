// cli/moebius_report.hpp -- printing a piecewise Moebius result (the
// `moebius` and `reparam` commands): JSON, text and formulas.
#pragma once

#include "uniparam/uniparam.hpp"

namespace uniparam::cli {

struct MoebiusPrint {
  bool json = false;
  Format format = Format::Text;  ///< of the formulas
  bool formulas = true;          ///< print the pieces' formulas
};

struct Args;
/// --format (text, latex, maple, json) and --json.
MoebiusPrint read_moebius_print(const Args& a);

/// Prints r (computed for c) to stdout. JSON keys: curve, speed, digits,
/// continuity, t, s, alpha (arrays; exact rationals carry "exact"), mu,
/// u_before, u_after, speed_vanishes, rational, pieces (with formulas), and
/// optimiser / target when set.
void print_moebius(const Curve& c, const MoebiusResult& r, long digits, const MoebiusPrint& how);

}  // namespace uniparam::cli
