#include "uniparam/algebra/newton_polygon.hpp"

#include <algorithm>
#include <cmath>

#include <flint/fmpz.h>
#include <flint/fmpz_poly.h>

namespace uniparam {

NewtonPolygon::NewtonPolygon(const Poly& p) {
  for (long k = 0; k <= p.degree(); ++k) {
    const fmpz* c = p.get()->coeffs + k;
    if (fmpz_is_zero(c)) continue;
    slong e = 0;
    const double m = fmpz_get_d_2exp(&e, c);
    const double lk = std::log2(std::fabs(m)) + static_cast<double>(e);
    // drop vertices below the edge to (k, lk) (upper hull, monotone chain)
    while (i_.size() >= 2) {
      const std::size_t n = i_.size();
      if ((l_[n - 1] - l_[n - 2]) * (static_cast<double>(k) - i_[n - 2]) > (lk - l_[n - 2]) * (i_[n - 1] - i_[n - 2]))
        break;
      i_.pop_back();
      l_.pop_back();
    }
    i_.push_back(static_cast<double>(k));
    l_.push_back(lk);
  }
  // the maximiser at x = 0: the first vertex after which the hull falls
  while (at_ + 1 < i_.size() && l_[at_ + 1] >= l_[at_]) ++at_;
}

void NewtonPolygon::breakpoints(std::vector<double>& out) const {
  for (std::size_t v = 0; v + 1 < i_.size(); ++v) {
    const double slope = (l_[v + 1] - l_[v]) / (i_[v + 1] - i_[v]);
    if (slope >= 0) out.push_back(slope);
  }
}

double NewtonPolygon::deepest() const {
  return i_.size() >= 2 ? std::max(0.0, (l_[1] - l_[0]) / (i_[1] - i_[0])) : 0.0;
}

double NewtonPolygon::operator()(double x) {
  while (at_ > 0 && l_[at_ - 1] - i_[at_ - 1] * x >= l_[at_] - i_[at_] * x) --at_;
  return l_[at_] - i_[at_] * x;
}

long root_depth_bits(const Poly& p) {
  // The first hull edge's slope is the largest (log2 |c_{v+i}/c_v|) / i
  // over all i (the hull lies above every point), so 2^-deepest() is
  // min_i |c_v / c_{v+i}|^(1/i) and Fujiwara's bound is 2^-(deepest + 1).
  // Each log2 |c| is that of a double mantissa plus an exact exponent e,
  // accurate to about (1 + |e|) 2^-52: far below the margin of one bit for
  // coefficients of fewer than 2^40 bits.
  const double d = NewtonPolygon(p).deepest();
  if (!std::isfinite(d)) return 0;
  return static_cast<long>(std::ceil(d)) + 2;
}

long end_root_depth_bits(const Poly& p) {
  if (p.degree() < 1) return root_depth_bits(p);
  Poly at1;  // p(1 + t): its roots are p's minus 1
  fmpz_t one;
  fmpz_init_set_ui(one, 1);
  fmpz_poly_taylor_shift(at1.get(), p.get(), one);
  fmpz_clear(one);
  return std::max(root_depth_bits(p), root_depth_bits(at1));
}

}  // namespace uniparam
