// cli/moebius_report.hpp -- printing a piecewise Moebius result (the
// `moebius` and `reparam` commands): JSON, text and formulas.
#pragma once

#include "uniparam/reparam/all.hpp"

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
/// The JSON document print_moebius prints (how.json is not consulted).
Json moebius_json(const Curve& c, const MoebiusResult& r, long digits, const MoebiusPrint& how);

/// The largest --max-pieces the commands accept.
constexpr long kMaxPiecesLimit = 1000;

/// The uniformity `u` of a map that missed `target` (its midpoint below the
/// target), as the shortest decimal of 8 to `digits` + 3 significant digits
/// that lies below the target, so that it never reads as reaching it
/// ("1" for 0.9999999996); the certified ball when none does.
std::string missed_u_text(const Ball& u, const Rational& target, long digits);

/// The message of a C1 map r (r.target set, not reached) refined up to
/// `max_pieces` pieces: the target, the u reached (missed_u_text), that the
/// best map found is `use`d ("printed" by reparam, "used" by sample and
/// plot), and what to change: where the draft's floating point broke down,
/// --pieces N or a lower --target; else raise --max-pieces below
/// kMaxPiecesLimit, else lower --target.
std::string target_missed_message(const MoebiusResult& r, long max_pieces, long digits,
                                  const std::string& use = "printed");

}  // namespace uniparam::cli
