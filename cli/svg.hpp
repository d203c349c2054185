// cli/svg.hpp -- a small, deterministic SVG writer for the plots: a document
// of primitives, panels mapping data to pixels, nice axis ticks, and PNG
// output through rsvg-convert (Debian package librsvg2-bin).
//
// Deterministic: the same calls give byte-identical output (fixed number
// formatting, no time stamps, no locale). Self-contained: no external
// references, fonts named by family only.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace uniparam::cli::svg {

using Point = std::pair<double, double>;

/// Text with &, <, >, " and ' escaped for XML.
std::string escape(const std::string& s);
/// x rounded to 2 decimals, without trailing zeros ("12.5", "-3", "0").
std::string num(double x);

/// Style of a stroke or a mark.
struct Style {
  std::string stroke = "none";
  std::string fill = "none";
  double width = 1;
  std::string dash;  ///< SVG dash array, e.g. "4 3"; empty for solid
  double opacity = 1;
};

enum class Anchor { Start, Middle, End };

/// An SVG document of a fixed pixel size, with a white background.
class Document {
 public:
  Document(double width, double height);
  double width() const { return w_; }
  double height() const { return h_; }

  void line(Point a, Point b, const Style& st);
  /// An open polyline (nothing is drawn for fewer than two points).
  void polyline(const std::vector<Point>& pts, const Style& st);
  void rect(double x, double y, double w, double h, const Style& st);
  void circle(Point c, double r, const Style& st);
  /// A square turned by 45 degrees, centre c, half-diagonal r.
  void diamond(Point c, double r, const Style& st);
  /// Text at `at` (baseline); "_{...}" in s is set as a subscript.
  void text(Point at, const std::string& s, double size, Anchor anchor = Anchor::Start,
            const std::string& color = "#222", bool bold = false, double rotate = 0);
  /// Opens / closes a group carrying a class name (for structure checks and
  /// styling: <g class="panel">).
  void begin_group(const std::string& cls);
  void end_group();
  /// Clips what follows (until end_clip) to a rectangle.
  void begin_clip(double x, double y, double w, double h);
  void end_clip();
  /// An SVG comment (escaped so it cannot close early).
  void comment(const std::string& s);

  /// The complete document.
  std::string str() const;

 private:
  double w_, h_;
  std::string body_;
  int clips_ = 0;
  int depth_ = 0;
};

/// Tick positions for an axis over [lo, hi]: multiples of a step from
/// {1, 2, 5} x 10^k giving about `target` ticks, and the decimals that label
/// them exactly.
struct Ticks {
  std::vector<double> values;
  double step = 1;
  int decimals = 0;
};
/// \pre lo < hi (otherwise a range of width 1 around lo is used).
Ticks nice_ticks(double lo, double hi, int target = 5);
/// A tick label: value with `decimals` decimals, "-0" printed as "0".
std::string tick_label(double v, int decimals);

/// A rectangle of the page showing the data range [x0, x1] x [y0, y1].
struct Panel {
  double left, top, width, height;  ///< pixels
  double x0, x1, y0, y1;            ///< data
  Point map(double x, double y) const;
  Point map(Point p) const { return map(p.first, p.second); }
};

/// Frame, grid lines, ticks with labels and the axis labels of a panel.
void draw_axes(Document& d, const Panel& p, const Ticks& xt, const Ticks& yt, const std::string& xlabel,
               const std::string& ylabel);

/// Converts an SVG document to PNG at `zoom` x its pixel size by running
/// rsvg-convert (no shell involved).
/// \throws std::runtime_error naming the Debian package librsvg2-bin when
///         rsvg-convert is not installed, or with its message when it fails.
void write_png(const std::string& svg_text, const std::string& png_path, double zoom);

}  // namespace uniparam::cli::svg
