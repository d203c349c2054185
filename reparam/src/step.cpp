#include "uniparam/reparam/step.hpp"

#include <cstdio>
#include <sstream>

#include "uniparam/core/error.hpp"

namespace uniparam {

namespace {

// A STEP real: the ball's midpoint with 17 significant digits.
std::string step_real(const Ball& b) {
  const double x = arf_get_d(arb_midref(b.get()), ARF_RND_NEAR);
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.16E", x);
  return buf;
}

}  // namespace

std::string step_text(const Nurbs& n, const std::string& name) {
  if (n.dimension > 3)
    throw InvalidArgument("STEP carries curves in 2 or 3 dimensions; this curve has " + std::to_string(n.dimension));
  std::ostringstream o;
  o << "ISO-10303-21;\nHEADER;\n"
    << "FILE_DESCRIPTION(('uniparam: the reparameterized curve p o r as a rational B-spline; "
       "reals are the midpoints of certified values, rounded to double'),'2;1');\n"
    << "FILE_NAME('" << name << "','',(''),(''),'uniparam','uniparam','');\n"
    << "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n"
    << "#1=APPLICATION_CONTEXT('automotive design');\n"
    << "#2=APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#1);\n"
    << "#3=PRODUCT_CONTEXT('',#1,'mechanical');\n"
    << "#4=PRODUCT('uniparam','uniparam','',(#3));\n"
    << "#5=PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#4));\n"
    << "#6=PRODUCT_DEFINITION_FORMATION('','',#4);\n"
    << "#7=PRODUCT_DEFINITION_CONTEXT('part definition',#1,'design');\n"
    << "#8=PRODUCT_DEFINITION('design','',#6,#7);\n"
    << "#9=PRODUCT_DEFINITION_SHAPE('','',#8);\n"
    << "#10=SHAPE_DEFINITION_REPRESENTATION(#9,#20);\n"
    << "#11=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));\n"
    << "#12=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));\n"
    << "#13=(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT());\n"
    << "#14=UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#11,'distance_accuracy_value','confusion accuracy');\n"
    << "#15=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#14))"
       "GLOBAL_UNIT_ASSIGNED_CONTEXT((#11,#12,#13))REPRESENTATION_CONTEXT('',''));\n"
    << "#20=GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION('',(#21),#15);\n"
    << "#21=GEOMETRIC_CURVE_SET('',(#30));\n";
  // distinct knots and multiplicities
  std::vector<std::string> kv;
  std::vector<int> mult;
  const std::vector<Ball> br = n.breaks();
  const long d = n.degree;
  for (std::size_t i = 0; i < br.size(); ++i) {
    kv.push_back(step_real(br[i]));
    mult.push_back(i == 0 || i + 1 == br.size() ? static_cast<int>(d + 1) : static_cast<int>(d));
  }
  const std::size_t first_point = 100;
  o << "#30=(BOUNDED_CURVE()B_SPLINE_CURVE(" << d << ",(";
  for (std::size_t i = 0; i < n.points.size(); ++i) o << (i ? "," : "") << "#" << first_point + i;
  o << "),.UNSPECIFIED.,.F.,.F.)B_SPLINE_CURVE_WITH_KNOTS((";
  for (std::size_t i = 0; i < mult.size(); ++i) o << (i ? "," : "") << mult[i];
  o << "),(";
  for (std::size_t i = 0; i < kv.size(); ++i) o << (i ? "," : "") << kv[i];
  o << "),.UNSPECIFIED.)CURVE()GEOMETRIC_REPRESENTATION_ITEM()RATIONAL_B_SPLINE_CURVE((";
  for (std::size_t i = 0; i < n.weights.size(); ++i) o << (i ? "," : "") << step_real(n.weights[i]);
  o << "))REPRESENTATION_ITEM(''));\n";
  for (std::size_t i = 0; i < n.points.size(); ++i) {
    o << "#" << first_point + i << "=CARTESIAN_POINT('',(";
    for (std::size_t c = 0; c < 3; ++c)
      o << (c ? "," : "") << (c < n.dimension ? step_real(n.points[i][c]) : std::string("0.E+00"));
    o << "));\n";
  }
  o << "ENDSEC;\nEND-ISO-10303-21;\n";
  return o.str();
}

}  // namespace uniparam
