// SVG path data to exact Bezier segments (path.hpp; docs/inputs.md).
#include "uniparam/reparam/path.hpp"

#include <optional>

#include "svg_arc.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {

namespace {

struct Pt {
  Rational x, y;
  bool operator==(const Pt& o) const { return x == o.x && y == o.y; }
  bool operator!=(const Pt& o) const { return !(*this == o); }
};

std::vector<Rational> vec(const Pt& p) { return {p.x, p.y}; }

bool is_constant(const BezierCurve& b) {
  const auto& p = b.points();
  for (const auto& q : p)
    if (q != p.front()) return false;
  return true;
}

class SvgReader {
 public:
  SvgReader(const std::string& d, const SvgLimits& lim) : d_(d), lim_(lim) {}

  std::vector<PathInput> run() {
    if (d_.size() > lim_.max_length)
      throw InvalidArgument("SVG path data has " + std::to_string(d_.size()) + " characters, more than the limit of " +
                            std::to_string(lim_.max_length));
    skip_wsp();
    if (i_ >= d_.size()) throw InvalidArgument("empty SVG path data (expected a moveto 'M x y')");
    if (d_[i_] != 'M' && d_[i_] != 'm') fail(i_, "'M' or 'm'", "SVG path data must start with a moveto");
    while (i_ < d_.size()) {
      const char cmd = d_[i_];
      const std::size_t cmd_at = i_;
      if (!is_command(cmd)) fail(i_, "an SVG path command letter", "unexpected " + shown_char(cmd));
      ++i_;
      skip_wsp();
      command(cmd, cmd_at);
      skip_wsp();
    }
    finish_subpath();
    return std::move(out_);
  }

 private:
  const std::string& d_;
  const SvgLimits& lim_;
  std::size_t i_ = 0;
  std::vector<PathInput> out_;
  // The subpath being read.
  bool open_ = false;          // a subpath is started (by M, or by a command after Z)
  std::size_t subpath_at_ = 0;  // column of its first command
  std::vector<BezierCurve> segs_;
  std::vector<std::string> labels_;
  Pt cur_{Rational(0), Rational(0)}, start_{Rational(0), Rational(0)};
  std::optional<Pt> last_cubic_ctrl_, last_quad_ctrl_;  // for S and T
  std::size_t total_segments_ = 0, arcs_ = 0;
  std::size_t total_commands_seen_ = 0;  // drawing and moveto commands read so far

  static bool is_command(char c) {
    switch (c) {
      case 'M': case 'm': case 'L': case 'l': case 'H': case 'h': case 'V': case 'v': case 'C': case 'c':
      case 'S': case 's': case 'Q': case 'q': case 'T': case 't': case 'Z': case 'z': case 'A': case 'a':
        return true;
      default:
        return false;
    }
  }
  static bool is_wsp(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f'; }
  static bool digit(char c) { return c >= '0' && c <= '9'; }

  [[noreturn]] void fail(std::size_t at, const std::string& expected, const std::string& detail) const {
    throw ParseError(at + 1, expected, "SVG path: " + detail);
  }

  void skip_wsp() {
    while (i_ < d_.size() && is_wsp(d_[i_])) ++i_;
  }
  // comma-wsp?: whitespace, at most one comma, whitespace. True when a comma was read.
  bool skip_comma_wsp() {
    skip_wsp();
    if (i_ < d_.size() && d_[i_] == ',') {
      ++i_;
      skip_wsp();
      return true;
    }
    return false;
  }
  bool number_starts_here() const {
    if (i_ >= d_.size()) return false;
    const char c = d_[i_];
    return digit(c) || c == '-' || c == '+' || c == '.';
  }

  Rational number(const char* what) {
    const std::size_t start = i_;
    if (i_ < d_.size() && (d_[i_] == '+' || d_[i_] == '-')) ++i_;
    bool digits = false;
    while (i_ < d_.size() && digit(d_[i_])) { ++i_; digits = true; }
    if (i_ < d_.size() && d_[i_] == '.') {
      ++i_;
      while (i_ < d_.size() && digit(d_[i_])) { ++i_; digits = true; }
    }
    if (!digits) {
      if (start >= d_.size()) fail(start, what, "the path data ends where a number was expected");
      fail(start, what, "unexpected " + shown_char(d_[start]) + " where a number was expected");
    }
    std::string text = d_.substr(start, i_ - start);
    if (i_ < d_.size() && (d_[i_] == 'e' || d_[i_] == 'E')) {
      ++i_;
      const bool negative = i_ < d_.size() && d_[i_] == '-';
      if (i_ < d_.size() && (d_[i_] == '+' || d_[i_] == '-')) ++i_;
      std::size_t e0 = i_;
      while (i_ < d_.size() && digit(d_[i_])) ++i_;
      if (e0 == i_) fail(i_, "a digit", "malformed exponent");
      while (e0 + 1 < i_ && d_[e0] == '0') ++e0;  // leading zeros of the exponent
      if (i_ - e0 > 3) fail(start, "", "the number '" + d_.substr(start, std::min<std::size_t>(i_ - start, 40)) +
                                          "' has a decimal exponent of 1000 or more in absolute value");
      text += std::string(negative ? "e-" : "e") + d_.substr(e0, i_ - e0);
    }
    return Rational::parse(text);
  }

  bool flag() {
    if (i_ >= d_.size() || (d_[i_] != '0' && d_[i_] != '1'))
      fail(i_, "an arc flag '0' or '1'",
           i_ >= d_.size() ? "the path data ends where an arc flag was expected"
                           : "unexpected " + shown_char(d_[i_]) + " where an arc flag was expected");
    return d_[i_++] == '1';
  }

  // Reads the parameters of one repetition of `cmd` (count numbers, arcs: 7 with flags).
  std::vector<Rational> params(char cmd, std::size_t count) {
    std::vector<Rational> v;
    const bool arc = cmd == 'A' || cmd == 'a';
    for (std::size_t k = 0; k < count; ++k) {
      if (k > 0) skip_comma_wsp();
      if (arc && (k == 3 || k == 4)) v.emplace_back(flag() ? 1 : 0);
      else v.push_back(number(k == 0 ? "a number after the command" : "a number"));
    }
    return v;
  }

  void start_subpath_if_needed(std::size_t at) {
    if (open_) return;
    open_ = true;
    subpath_at_ = at;
  }

  void finish_subpath() {
    if (!open_) return;
    open_ = false;
    if (segs_.empty())
      throw InvalidArgument("SVG path: subpath " + std::to_string(out_.size() + 1) + " at column " +
                            std::to_string(subpath_at_ + 1) + " has no segment (a lone moveto, or only zero-length segments)");
    PathInput p;
    const long m = static_cast<long>(segs_.size());
    for (long j = 0; j <= m; ++j) p.knots.push_back(Rational(j, m));
    p.segments = std::move(segs_);
    p.labels = std::move(labels_);
    segs_.clear();
    labels_.clear();
    out_.push_back(std::move(p));
  }

  void add(BezierCurve b, const std::string& what, std::size_t at, const std::string& suffix = "") {
    if (is_constant(b)) return;
    if (++total_segments_ > lim_.max_segments)
      throw InvalidArgument("SVG path: more than " + std::to_string(lim_.max_segments) + " segments");
    segs_.push_back(std::move(b));
    labels_.push_back("segment " + std::to_string(segs_.size()) + ": " + what + " at column " +
                      std::to_string(at + 1) + suffix);
  }

  void command(char cmd, std::size_t cmd_at) {
    const bool rel = cmd >= 'a' && cmd <= 'z';
    const char up = static_cast<char>(rel ? cmd - 'a' + 'A' : cmd);
    if (up == 'Z') {
      if (open_) {
        if (cur_ != start_) add(BezierCurve({vec(cur_), vec(start_)}), std::string(1, cmd), cmd_at);
        finish_subpath();
      }
      cur_ = start_;
      last_cubic_ctrl_.reset();
      last_quad_ctrl_.reset();
      if (number_starts_here() || (i_ < d_.size() && d_[i_] == ','))
        fail(i_, "a command letter", "closepath '" + std::string(1, cmd) + "' takes no parameters");
      return;
    }
    std::size_t count = 0;
    switch (up) {
      case 'M': case 'L': case 'T': count = 2; break;
      case 'H': case 'V': count = 1; break;
      case 'C': count = 6; break;
      case 'S': case 'Q': count = 4; break;
      case 'A': count = 7; break;
    }
    std::size_t at = cmd_at;
    bool first = true;
    for (;;) {
      check_time_budget();
      const std::vector<Rational> v = params(cmd, count);
      apply(cmd, up, rel, first, v, at);
      first = false;
      const bool comma = skip_comma_wsp();
      if (!number_starts_here()) {
        if (comma) fail(i_, "a number", "a ',' must be followed by a number");
        return;
      }
      at = i_;  // an implicit repetition starts here
    }
  }

  Pt point(bool rel, const Rational& x, const Rational& y) const {
    return rel ? Pt{cur_.x + x, cur_.y + y} : Pt{x, y};
  }

  // The first control point of a smooth S or T: the previous command's last
  // control point reflected about the current point, or the current point
  // when the previous command was not of the same kind.
  Pt reflected(const std::optional<Pt>& ctrl) const {
    return ctrl ? Pt{cur_.x + cur_.x - ctrl->x, cur_.y + cur_.y - ctrl->y} : cur_;
  }

  void apply(char cmd, char up, bool rel, bool first, const std::vector<Rational>& v, std::size_t at) {
    const std::string name(1, cmd);
    if (up == 'M' && first) {
      finish_subpath();
      // The first moveto of the path is absolute even when written 'm'.
      cur_ = (rel && total_commands_seen_) ? point(true, v[0], v[1]) : Pt{v[0], v[1]};
      start_ = cur_;
      ++total_commands_seen_;
      open_ = true;
      subpath_at_ = at;
      last_cubic_ctrl_.reset();
      last_quad_ctrl_.reset();
      return;
    }
    ++total_commands_seen_;
    start_subpath_if_needed(at);
    std::optional<Pt> cubic_ctrl, quad_ctrl;
    switch (up) {
      case 'M':  // implicit lineto after a moveto
      case 'L': {
        const Pt p = point(rel, v[0], v[1]);
        add(BezierCurve({vec(cur_), vec(p)}), first ? name : std::string(1, rel ? 'l' : 'L'), at,
            first ? "" : (up == 'M' ? " (implicit lineto after " + name + ")" : ""));
        cur_ = p;
        break;
      }
      case 'H': {
        const Pt p{rel ? cur_.x + v[0] : v[0], cur_.y};
        add(BezierCurve({vec(cur_), vec(p)}), name, at);
        cur_ = p;
        break;
      }
      case 'V': {
        const Pt p{cur_.x, rel ? cur_.y + v[0] : v[0]};
        add(BezierCurve({vec(cur_), vec(p)}), name, at);
        cur_ = p;
        break;
      }
      case 'C': {
        const Pt p1 = point(rel, v[0], v[1]), p2 = point(rel, v[2], v[3]), p3 = point(rel, v[4], v[5]);
        add(BezierCurve({vec(cur_), vec(p1), vec(p2), vec(p3)}), name, at);
        cubic_ctrl = p2;
        cur_ = p3;
        break;
      }
      case 'S': {
        const Pt p1 = reflected(last_cubic_ctrl_);
        const Pt p2 = point(rel, v[0], v[1]), p3 = point(rel, v[2], v[3]);
        add(BezierCurve({vec(cur_), vec(p1), vec(p2), vec(p3)}), name, at);
        cubic_ctrl = p2;
        cur_ = p3;
        break;
      }
      case 'Q': {
        const Pt p1 = point(rel, v[0], v[1]), p2 = point(rel, v[2], v[3]);
        add(BezierCurve({vec(cur_), vec(p1), vec(p2)}), name, at);
        quad_ctrl = p1;
        cur_ = p2;
        break;
      }
      case 'T': {
        const Pt p1 = reflected(last_quad_ctrl_);
        const Pt p2 = point(rel, v[0], v[1]);
        add(BezierCurve({vec(cur_), vec(p1), vec(p2)}), name, at);
        quad_ctrl = p1;
        cur_ = p2;
        break;
      }
      case 'A': {
        const Pt p = point(rel, v[5], v[6]);
        const std::string arc_name = "arc " + std::to_string(++arcs_) + " at column " + std::to_string(at + 1);
        std::vector<BezierCurve> pieces =
            detail::svg_arc(cur_.x, cur_.y, v[0], v[1], v[2], !v[3].is_zero(), !v[4].is_zero(), p.x, p.y, arc_name);
        const std::size_t n = pieces.size();
        for (std::size_t k = 0; k < n; ++k)
          add(std::move(pieces[k]), name, at,
              n > 1 ? " (arc " + std::to_string(arcs_) + ", piece " + std::to_string(k + 1) + " of " +
                          std::to_string(n) + ")"
                    : " (arc " + std::to_string(arcs_) + ")");
        cur_ = p;
        break;
      }
    }
    last_cubic_ctrl_ = cubic_ctrl;
    last_quad_ctrl_ = quad_ctrl;
  }
};

}  // namespace

std::vector<PathInput> parse_svg_path(const std::string& d, const SvgLimits& limits) {
  return SvgReader(d, limits).run();
}

}  // namespace uniparam
