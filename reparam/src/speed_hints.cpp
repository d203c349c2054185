// speed_hints.cpp -- where sigma's singularities lie, for the quadrature:
// Speed::singularity_hints (approximate poles and branch points, uncertified
// hints only) and Speed::scale_bits (a certified bound on how close to the
// ends of [0, 1] they come).
#include <algorithm>
#include <complex>
#include <mutex>

#include "uniparam/algebra/approx_roots.hpp"
#include "uniparam/algebra/newton_polygon.hpp"
#include "uniparam/core/parallel.hpp"
#include "uniparam/reparam/speed.hpp"

namespace uniparam {

namespace {

// singularity_hints: the largest degree of D or sum K^2 whose roots are
// approximated (O(degree^2) per Aberth sweep).
constexpr long kHintMaxDegree = 128;
// ... and the most bits Horner's rule may lose near [0, 1] (the estimates
// of power_basis_loss on [0, 1] for p's power basis, of
// approximate_roots_near_unit_interval on [-1, 1] for the centred one):
// roots from double coefficients are only as good as Horner's rule there,
// and power bases that lose more give hints that would mislead.
constexpr double kHintMaxLoss = 30;

// ... and up to which p's own power basis is taken without trying the
// centred one (its hints then hold ~8 digits already).
constexpr double kHintGoodLoss = 12;

// The hints from p's roots (appended to out): from p's own power basis when
// it loses at most kHintGoodLoss bits on [0, 1], else from the one of p's
// and its power basis centred at 1/2 (approximate_roots_near_unit_interval)
// that loses fewer, if at most kHintMaxLoss. Bezier curves' bases lose ~n
// bits on [0, 1] (D and sum K^2 of bez-rat-space d = 12: 57 and > 100,
// centred 10 and 16), while dense curves' roots, near the
// unit circle, settle in far fewer sweeps on their own basis (3 M
// instructions a run against 19 M on dense-plane d = 50's D centred). False
// when neither basis is good enough.
bool append_hints(const Poly& p, std::vector<std::complex<double>>& out) {
  if (p.degree() <= 0) return true;
  const double own = power_basis_loss(p);
  if (own > kHintGoodLoss) {
    double loss = 0;
    const auto z = approximate_roots_near_unit_interval(p, std::min(kHintMaxLoss, own), &loss);
    if (loss <= std::min(kHintMaxLoss, own)) {  // else refused: below, or no hints
      out.insert(out.end(), z.begin(), z.end());
      return true;
    }
  }
  if (!(own <= kHintMaxLoss)) return false;
  const auto z = approximate_complex_roots(p);
  out.insert(out.end(), z.begin(), z.end());
  return true;
}

}  // namespace

const std::vector<std::complex<double>>& Speed::singularity_hints(bool squared) const {
  std::call_once(lazy_->hints_once, [this] {
    if (zero_) return;
    long k = 0;
    for (const auto& c : K_) k = std::max(k, c.degree());
    if (D_.degree() > kHintMaxDegree || 2 * k > kHintMaxDegree) return;
    // sigma has a square root unless it is a plane curve's angular speed
    const bool root = !(kind_ == SpeedKind::Angular && comp_.size() == 2);
    // the poles and the branch points side by side (independent serial
    // iterations: the same hints on any number of threads)
    const bool branches = root && k > 0;
    std::vector<std::complex<double>> poles, branch;
    bool poles_ok = true, branch_ok = true;
    parallel_for(branches ? 2 : 1, std::min<std::size_t>(worker_count(), branches ? 2 : 1),
                 [&](std::size_t, std::size_t i) {
                   if (i == 0) {
                     poles_ok = append_hints(D_, poles);
                   } else {
                     branch_ok = append_hints(cofactor_square_sum(), branch);
                   }
                 });
    if (!poles_ok) return;  // no hints rather than half of them
    lazy_->hints_squared = poles;
    lazy_->hints_sigma = std::move(poles);
    if (!branch_ok) lazy_->hints_sigma.clear();
    else lazy_->hints_sigma.insert(lazy_->hints_sigma.end(), branch.begin(), branch.end());
  });
  return squared ? lazy_->hints_squared : lazy_->hints_sigma;
}

long Speed::scale_bits() const {
  std::call_once(lazy_->scale_once, [this] {
    if (zero_) return;
    long d = 0;
    for (const Poly* p : {&g_, &D_, &cofactor_square_sum()})
      if (p->degree() >= 1) d = std::max(d, end_root_depth_bits(*p));
    lazy_->scale_bits = d;
  });
  return lazy_->scale_bits;
}

}  // namespace uniparam
