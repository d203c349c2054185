// Samples of a composite map: each segment's Sampler, made when first
// asked, its points mapped to the composite curve's parameters.
#include "uniparam/reparam/composite.hpp"

#include <arb.h>

#include <memory>
#include <utility>

#include "composite_detail.hpp"

namespace uniparam {

using namespace composite_detail;

CompositeSampler::CompositeSampler(const CompositeCurve& c, const std::vector<Speed>& speeds, const CompositeMap& r,
                                   long digits, long max_prec)
    : c_(c), sp_(speeds), r_(r), digits_(digits), max_prec_(max_prec), parts_(c.size()) {
  if (speeds.size() != c.size() || r.parts().size() != c.size())
    throw InvalidArgument("CompositeSampler: the curve, speeds and map do not belong together");
  part(0);  // checks digits and max_prec as Sampler does
}

Sampler& CompositeSampler::part(std::size_t j) {
  if (!parts_[j])
    parts_[j] = std::make_unique<Sampler>(c_.segment(j), sp_[j], r_.parts()[j], digits_, max_prec_);
  return *parts_[j];
}

std::size_t CompositeSampler::segment_of(const Rational& s) const {
  const auto& S = r_.S();
  std::size_t j = 0;
  while (j + 2 < S.size() && !(s < S[j + 1])) ++j;
  return j;
}

SamplePoint CompositeSampler::at(const Rational& s) {
  if (s.sign() < 0 || Rational(1) < s) throw InvalidArgument("the sample parameter must lie in [0, 1]");
  const auto& S = r_.S();
  const auto& k = c_.knots();
  const std::size_t j = segment_of(s);
  const long prec = 2 * digits_to_bits(digits_) + 64;
  const Rational dS = S[j + 1] - S[j];
  SamplePoint local = part(j).at((s - S[j]) / dS);
  SamplePoint out;
  out.s = s;
  out.point = std::move(local.point);
  out.t = mul_rational(local.t, k[j + 1] - k[j], prec);
  {
    Ball kj(k[j], prec);
    arb_add(out.t.get(), out.t.get(), kj.get(), prec);
  }
  out.speed = div_rational(local.speed, dS, prec);
  out.at_joint = local.at_joint;
  if (j > 0 && s == S[j]) {
    const SamplePoint left = part(j - 1).at(Rational(1));
    const Ball ls = div_rational(left.speed, S[j] - S[j - 1], prec);
    arb_union(out.speed.get(), out.speed.get(), ls.get(), prec);
    out.at_joint = true;
  }
  return out;
}

}  // namespace uniparam
