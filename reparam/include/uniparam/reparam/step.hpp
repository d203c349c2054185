// uniparam/reparam/step.hpp -- a NURBS curve as a STEP AP214 file.
#pragma once

#include <string>

#include "uniparam/reparam/nurbs.hpp"

namespace uniparam {

/// The NURBS as a STEP AP214 file named `name` (the FILE_NAME entry): one
/// rational B-spline curve (the complex entity B_SPLINE_CURVE_WITH_KNOTS +
/// RATIONAL_B_SPLINE_CURVE) in a GEOMETRIC_CURVE_SET of a
/// GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION, with the product
/// structure CAD readers expect. Numbers are the balls' midpoints with 17
/// significant digits (STEP carries doubles). 2D curves get z = 0.
/// \pre name holds no quote, backslash or control character.
/// \throws InvalidArgument for a dimension above 3.
std::string step_text(const Nurbs& n, const std::string& name);

}  // namespace uniparam
