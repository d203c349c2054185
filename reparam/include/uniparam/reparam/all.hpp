// uniparam/reparam/all.hpp -- every header of the engine in one (the CLI,
// the Python module, the tests). Internal: the public API is
// uniparam/uniparam.hpp.
#pragma once

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/algebra/squarefree.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/decimal.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/json.hpp"
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
