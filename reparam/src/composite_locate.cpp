// Locating on a composite curve: the Track over all its segments (its mu,
// integrals of the speed, estimates and points), locate and exact samples.
#include "uniparam/reparam/composite.hpp"

#include <arb.h>

#include <memory>
#include <vector>

#include "composite_detail.hpp"
#include "uniparam/algebra/algebraic.hpp"
#include "track.hpp"

namespace uniparam {

using namespace composite_detail;

namespace {

class CompositeTrack final : public Track {
 public:
  CompositeTrack(const CompositeCurve& c, const std::vector<Speed>& s, long max_prec)
      : c_(c), s_(s), max_prec_(max_prec) {}
  bool identically_zero() const override {
    for (const Speed& s : s_)
      if (!s.identically_zero()) return false;
    return true;
  }
  SpeedKind kind() const override { return s_.front().kind(); }
  Ball mu(long bits, const Options& opt) const override {
    const long prec = 2 * bits + 64;
    Ball sum(0);
    for (std::size_t j = 0; j < c_.size(); ++j) {
      if (s_[j].identically_zero()) continue;
      const Ball mj = labelled(c_.label(j), [&] { return mean_speed(s_[j], bits, opt); });
      arb_add(sum.get(), sum.get(), mj.get(), prec);
    }
    return sum;
  }
  Ball integral(const Rational& a, const Rational& b, long bits) const override {
    const long prec = 2 * bits + 64;
    const auto& k = c_.knots();
    Ball sum(0);
    for (std::size_t j = 0; j < c_.size(); ++j) {
      const Rational lo = a < k[j] ? k[j] : a, hi = k[j + 1] < b ? k[j + 1] : b;
      if (!(lo < hi) || s_[j].identically_zero()) continue;
      const Rational d = k[j + 1] - k[j];
      const Ball part = integrate_speed(s_[j], RealAlgebraic((lo - k[j]) / d), RealAlgebraic((hi - k[j]) / d),
                                        bits, max_prec_);
      arb_add(sum.get(), sum.get(), part.get(), prec);
    }
    return sum;
  }
  double sigma_estimate(const Rational& x) const override {
    const auto& k = c_.knots();
    const std::size_t j = c_.segment_of(x);
    if (s_[j].identically_zero()) return 0;
    const Rational d = k[j + 1] - k[j];
    const double dd = mid_double_of(Ball(d, 64));
    return uniparam::sigma_estimate(s_[j], (x - k[j]) / d) / dd;
  }
  std::vector<Ball> eval(const Ball& t, long prec) const override { return c_.eval(t, prec); }
  std::vector<Segment> segments() const override {
    std::vector<Segment> out;
    for (std::size_t j = 0; j < c_.size(); ++j) out.push_back(Segment{c_.knots()[j], c_.knots()[j + 1], &s_[j]});
    return out;
  }

 private:
  const CompositeCurve& c_;
  const std::vector<Speed>& s_;
  long max_prec_;
};

// A straight segment among curved ones has angular speed 0 on a whole
// interval: int_0^t sigma is constant there, and a value it takes there
// determines no parameter.
void check_no_flat_segment(const CompositeCurve& c, const std::vector<Speed>& speeds) {
  bool all = true;
  for (const Speed& s : speeds) all = all && s.identically_zero();
  if (all) return;
  for (std::size_t j = 0; j < c.size(); ++j)
    if (speeds[j].identically_zero())
      throw DomainError(c.label(j) +
                        " is straight: its angular speed is 0 on a whole interval, where the turning angle "
                        "determines no parameter (use the parametric speed, arc length)");
}

}  // namespace

std::shared_ptr<const Track> composite_track(const CompositeCurve& c, const std::vector<Speed>& speeds,
                                             long max_prec) {
  return std::make_shared<CompositeTrack>(c, speeds, max_prec);
}

LocateResult locate(const CompositeCurve& c, const std::vector<Speed>& speeds, const Rational& value,
                    LocateTarget target, const Options& opt) {
  validate(opt);
  if (speeds.size() != c.size()) throw InvalidArgument("locate: one speed per segment is needed");
  check_no_flat_segment(c, speeds);
  return locate_on(CompositeTrack(c, speeds, opt.max_prec), value, target, opt);
}

void exact_samples_each(const CompositeCurve& c, const std::vector<Speed>& speeds, long K, const Options& opt,
                        Ball& mu, const LocatedSink& sink) {
  validate(opt);
  if (speeds.size() != c.size()) throw InvalidArgument("exact_samples_each: one speed per segment is needed");
  check_no_flat_segment(c, speeds);
  exact_samples_on(CompositeTrack(c, speeds, opt.max_prec), K, opt, mu, sink);
}

}  // namespace uniparam
