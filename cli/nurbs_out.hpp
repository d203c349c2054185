// cli/nurbs_out.hpp -- --output nurbs | step | FILE.stp: the reparameterized
// curve p o r as NURBS JSON or as a STEP AP214 file (docs/nurbs.md).
#pragma once

#include <string>
#include <vector>

#include "args.hpp"
#include "uniparam/reparam/all.hpp"
#include "uniparam/reparam/nurbs.hpp"
#include "uniparam/reparam/step.hpp"

namespace uniparam::cli {

/// Where --output sends the NURBS of p o r.
struct NurbsOutput {
  enum class Form { None, Json, Step };
  Form form = Form::None;
  std::string file;  ///< STEP file (empty: stdout)
  /// True when the NURBS replaces the command's report on stdout.
  bool replaces_report() const { return form != Form::None && file.empty(); }
};

/// The --output option of the Moebius commands.
OptionSpec nurbs_output_option();

/// Reads --output: "nurbs" (JSON on stdout), "step" (STEP on stdout) or a
/// file name ending in .stp or .step (STEP written there; checked writable
/// before any computing). \throws InvalidArgument for anything else or a
/// file that cannot be written.
NurbsOutput read_nurbs_output(const Args& a);
/// The form named by the value `v` of --output, as read_nurbs_output (a
/// file is checked writable). \throws InvalidArgument as read_nurbs_output.
NurbsOutput parse_nurbs_output(const std::string& v);

/// The NURBS as JSON: degree, dimension, kind ("rational", "surd" or "balls"),
/// knots, control_points, weights (every number exact {"mid", "rad", "exact"}
/// or a certified ball {"mid", "rad"}), segments, subdivided_segments.
Json nurbs_json(const Nurbs& n, long digits);

/// The NURBS as a STEP AP214 file: one rational B-spline curve (the complex
/// entity B_SPLINE_CURVE_WITH_KNOTS + RATIONAL_B_SPLINE_CURVE) in a
/// GEOMETRIC_CURVE_SET of a GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION,
/// with the product structure CAD readers expect. Numbers are the balls'
/// midpoints with 17 significant digits (STEP carries doubles). 2D curves get
/// z = 0. \throws InvalidArgument for a dimension above 3.
std::string nurbs_step(const Nurbs& n, const std::string& name);

/// Writes n as `o` asks (stdout or the STEP file). \throws InvalidArgument for
/// a dimension STEP cannot carry; std::runtime_error when the file cannot be
/// written.
void write_nurbs(const Nurbs& n, const NurbsOutput& o, long digits);

/// Ball precision of a NURBS built in ball arithmetic for --digits.
long nurbs_prec(const Options& opt);

/// When o asks for it, the NURBS of p o r for the Moebius map r (exact for a
/// --rational map) written as o says. \throws as moebius_nurbs, write_nurbs.
void write_moebius_nurbs(const Curve& c, const MoebiusResult& r, const NurbsOutput& o, const Options& opt);

}  // namespace uniparam::cli
