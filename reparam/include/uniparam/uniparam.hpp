// uniparam/uniparam.hpp -- the public C++ API of uniparam, in one header.
//
//   #include <uniparam/uniparam.hpp>
//   uniparam::Curve c = uniparam::parse_curve("(t, t^3)");
//   uniparam::Options o;            // o.digits = 15, budgets
//   auto r = uniparam::uniformity(c, uniparam::SpeedKind::Angular, o);
//   std::cout << r.u.str(20);       // certified ball
//   auto rad = uniparam::radical(c, uniparam::SpeedKind::Angular, o);
//   rad.u_after;                    // u(p o phi o m), certified
//   uniparam::radical_eval_r(rad, uniparam::Ball(uniparam::Rational(1, 2), 128), 128);
//
// Every number is exact (Rational, RatFunc, RealAlgebraic) or a Ball proven to
// contain the true value. Errors are exceptions derived from uniparam::Error:
// ParseError (with column), DomainError (undefined mathematics, e.g. a pole),
// InvalidArgument (an option out of range), BudgetExceeded (a limit reached:
// precision, degree, size, or the time of a TimeBudget). The library never exits.
#pragma once

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/algebra/squarefree.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/decimal.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/core/parser.hpp"
#include "uniparam/core/poly.hpp"
#include "uniparam/core/printer.hpp"
#include "uniparam/core/ratfunc.hpp"
#include "uniparam/reparam/bezier.hpp"
#include "uniparam/reparam/breakpoints.hpp"
#include "uniparam/reparam/composite.hpp"
#include "uniparam/reparam/curve.hpp"
#include "uniparam/reparam/formula.hpp"
#include "uniparam/reparam/locate.hpp"
#include "uniparam/reparam/moebius.hpp"
#include "uniparam/reparam/nurbs.hpp"
#include "uniparam/reparam/path.hpp"
#include "uniparam/reparam/pieces.hpp"
#include "uniparam/reparam/radical.hpp"
#include "uniparam/reparam/sample.hpp"
#include "uniparam/reparam/scaling.hpp"
#include "uniparam/reparam/speed.hpp"
#include "uniparam/reparam/uniformity.hpp"

namespace uniparam {

/// Parses "(x(t), y(t), ...)" into a checked curve (see Curve).
inline Curve parse_curve(const std::string& text) { return Curve::parse(text); }

}  // namespace uniparam
