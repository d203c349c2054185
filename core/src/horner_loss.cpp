// horner_loss.cpp -- the estimate of Horner's cancellation (horner_loss.hpp).
#include "uniparam/core/horner_loss.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "uniparam/core/error.hpp"

namespace uniparam {

double horner_loss_bits(const Poly& p, double lo, double hi, int max_order) {
  if (p.is_zero()) throw InvalidArgument("horner_loss_bits: the zero polynomial");
  if (max_order < 0 || max_order > 2) throw InvalidArgument("horner_loss_bits: the order must be 0, 1 or 2");
  std::vector<double> c = scaled_doubles(p);
  const double step = (hi - lo) / 32;
  double loss = 0;
  std::size_t len = c.size();  // c[0 .. len): the coefficients of p^(j)
  for (int j = 0; j <= max_order; ++j) {
    if (j > 0) {  // the derivative, in double (an estimate)
      for (std::size_t k = 1; k < len; ++k) c[k - 1] = c[k] * static_cast<double>(k);
      if (--len == 0) break;
    }
    double sum = 0, peak = 0;
    for (std::size_t k = 0; k < len; ++k) sum += std::fabs(c[k]);
    for (int i = 0; i <= 32; ++i) {
      const double t = lo + i * step;
      double h = c[len - 1];
      for (std::size_t k = len - 1; k-- > 0;) h = h * t + c[k];
      peak = std::max(peak, std::fabs(h));
    }
    if (!std::isfinite(sum) || !std::isfinite(peak) || !(peak > 0)) return std::numeric_limits<double>::infinity();
    loss = std::max(loss, std::log2(sum / peak));
  }
  return loss;
}

}  // namespace uniparam
