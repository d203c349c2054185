// cli/svg.hpp -- a small, deterministic SVG writer for the plots: a document
// of primitives, panels mapping data to pixels, nice axis ticks, and PNG
// output through rsvg-convert (Debian package librsvg2-bin).
//
// Deterministic: the same calls give byte-identical output (fixed number
// formatting, no time stamps, no locale). Self-contained: no external
// references, fonts named by family only.
#pragma once

#include <cstddef>
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
/// them exactly. Each value is mantissas[i] x 10^exponent exactly (as far as
/// a double holds it): the integers from which the labels are formed.
struct Ticks {
  std::vector<double> values;
  double step = 1;
  int decimals = 0;
  std::vector<long long> mantissas;  ///< values[i] = mantissas[i] * 10^exponent
  int exponent = 0;                  ///< the power of ten of the step
};
/// \pre lo < hi (otherwise a range of width 1 around lo is used); infinite
/// or NaN bounds are replaced by a unit range. The step is at least 10^-15 of
/// max(|lo|, |hi|), so the ticks stay distinct doubles and |mantissas| < 10^16.
/// Gives at most 2 * target + 2 ticks.
Ticks nice_ticks(double lo, double hi, int target = 5);
/// A tick label: value with `decimals` decimals, "-0" printed as "0".
std::string tick_label(double v, int decimals);

/// The labels of an axis's ticks and the note that scales them.
/// Plain decimals (tick_label) when none is longer than kMaxTickGlyphs
/// characters; otherwise scientific: the labels are integers L_i and the note
/// says value_i = L_i x 10^E + O ("\u00d710\u207b\u2076 + 1\u00d710\u00b9\u2070",
/// O omitted when 0), with |L_i| < 10^4, so no label is longer than
/// kMaxTickGlyphs characters whatever the magnitude of the values or the
/// digits they need.
struct AxisLabels {
  std::vector<std::string> labels;  ///< one per tick, in order
  std::string note;                 ///< empty for plain labels
};
constexpr int kMaxTickGlyphs = 6;
AxisLabels axis_labels(const Ticks& t);
/// Number of characters (Unicode code points) of UTF-8 text.
std::size_t glyphs(const std::string& s);

/// Estimated advance width in pixels of UTF-8 text set in DejaVu Sans (the
/// first font of the documents; the usual fallbacks are narrower) at `size`
/// pixels: per-character widths of that font, "_{...}" subscripts at 0.75 x.
double text_width(const std::string& s, double size, bool bold = false);
/// `s` broken into lines of estimated width (text_width) at most `max_width`:
/// at spaces where possible, else inside a word (never inside a UTF-8
/// sequence or a "_{...}" subscript). At most `max_lines` lines
/// (max_lines >= 1): text beyond them is elided in the middle of the last
/// line with " \u2026 " so that its start and end stay visible.
std::vector<std::string> wrap_text(const std::string& s, double size, double max_width, bool bold = false,
                                   std::size_t max_lines = 4);

/// A rectangle of the page showing the data range [x0, x1] x [y0, y1].
struct Panel {
  double left, top, width, height;  ///< pixels
  double x0, x1, y0, y1;            ///< data
  Point map(double x, double y) const;
  Point map(Point p) const { return map(p.first, p.second); }
};

/// Frame, grid lines, ticks with labels (axis_labels; a scientific note at
/// the top left of the frame for y and below the right end for x) and the
/// axis labels of a panel. The y axis label moves left of the widest tick
/// label, staying within 100 px of the frame (the gap between the panels).
void draw_axes(Document& d, const Panel& p, const Ticks& xt, const Ticks& yt, const std::string& xlabel,
               const std::string& ylabel);

/// Checks, before any computing, that `path` can be written as write_file
/// will: opens it for writing without changing it (a new file is created and
/// removed again).
/// \throws std::runtime_error "cannot write PATH: REASON" (REASON the
///         strerror text: No such file or directory, Is a directory, ...).
void check_writable(const std::string& path);

/// Writes `bytes` to `path` (created or truncated). If the process is ended
/// by SIGINT, SIGTERM, SIGHUP or SIGQUIT while writing, a file that this call
/// created is removed before the signal takes effect.
/// \throws std::runtime_error "cannot write PATH: REASON" (strerror text).
void write_file(const std::string& path, const std::string& bytes);

/// The path of rsvg-convert found on PATH, checked before computing.
/// \throws std::runtime_error naming the Debian package librsvg2-bin when
///         there is none.
std::string find_rsvg_convert();

/// Converts an SVG document to PNG at `zoom` x its pixel size with
/// rsvg-convert (no shell involved) and writes it to `png_path` (write_file).
/// The document goes to the child's stdin and the PNG comes back on its
/// stdout: no temporary file. The child dies with this process
/// (PR_SET_PDEATHSIG), is killed and reaped when the calling thread's time
/// budget runs out (then BudgetExceeded is thrown and nothing is written) or
/// when SIGINT, SIGTERM, SIGHUP or SIGQUIT ends the process, and only this
/// process writes `png_path`, after the child has exited successfully.
/// \throws std::runtime_error naming the Debian package librsvg2-bin when
///         rsvg-convert is not installed, or with its message when it fails;
///         BudgetExceeded as above.
void write_png(const std::string& svg_text, const std::string& png_path, double zoom);

}  // namespace uniparam::cli::svg
