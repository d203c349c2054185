// Internal to the composite curves (not installed): what composite.cpp (the
// curve and its uniformity), composite_map.cpp, composite_sample.cpp and
// composite_locate.cpp share: segment error labels, the segments' options
// and working precision, exact rational scalings of balls, and the segments
// a ball of the global parameter meets.
#pragma once

#include <arb.h>

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "uniparam/core/ball.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/reparam/composite.hpp"

namespace uniparam::composite_detail {

// Runs f, prefixing the message of a uniparam error with `label` (the type,
// and a ParseError's column, are kept).
template <class F>
auto labelled(const std::string& label, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const ParseError& e) {
    throw ParseError(e.column(), e.expected(), label + ": " + e.what());
  } catch (const TimeLimitExceeded&) {
    throw;  // its message names the time limit, the same for every segment
  } catch (const BudgetExceeded& e) {
    throw BudgetExceeded(label + ": " + e.what());
  } catch (const DomainError& e) {
    throw DomainError(label + ": " + e.what());
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(label + ": " + e.what());
  }
}

// The options each segment is computed with: two more digits, so that the
// sums and quotients over the segments still meet the digits asked for.
inline Options segment_options(const Options& opt) {
  Options o = opt;
  o.digits = std::min(opt.digits + 2, kMaxEngineDigits);
  return o;
}

// The working precision of the sums over the segments.
inline long work_prec(const Options& opt) { return 2 * digits_to_bits(opt.digits) + 64; }

// x * q (exact q) at prec.
inline Ball mul_rational(const Ball& x, const Rational& q, long prec) {
  Ball r;
  arb_mul_fmpz(r.get(), x.get(), q.num().get(), prec);
  arb_div_fmpz(r.get(), r.get(), q.den().get(), prec);
  return r;
}

// x / q (exact q, nonzero) at prec.
inline Ball div_rational(const Ball& x, const Rational& q, long prec) {
  Ball r;
  arb_mul_fmpz(r.get(), x.get(), q.den().get(), prec);
  arb_div_fmpz(r.get(), r.get(), q.num().get(), prec);
  return r;
}

// b's midpoint rounded to the nearest double.
inline double mid_double_of(const Ball& b) { return arf_get_d(arb_midref(b.get()), ARF_RND_NEAR); }

// Calls f(j, local) for every segment j whose [S_j, S_{j+1}] meets the ball
// s (S: 0 = S_0 < ... < S_m = 1), with local = (s - S_j) / (S_{j+1} - S_j)
// clipped to [0, 1]; for an exact s, once, for the segment holding it (the
// later one at an interior S_j), local exact. Throws InvalidArgument with the
// message `outside` when s meets no segment.
template <class F>
void for_segments_at(const std::vector<Rational>& S, const Ball& s, long prec, const char* outside, F&& f) {
  if (arb_is_exact(s.get())) {
    const Rational x = mid_rational(s);
    std::size_t j = 0;
    while (j + 2 < S.size() && !(x < S[j + 1])) ++j;
    f(j, Ball((x - S[j]) / (S[j + 1] - S[j]), prec));
    return;
  }
  bool any = false;
  for (std::size_t j = 0; j + 1 < S.size(); ++j) {
    Ball lo(S[j], prec), hi(S[j + 1], prec);
    if (arb_lt(s.get(), lo.get()) || arb_gt(s.get(), hi.get())) continue;
    Ball local;
    arb_sub(local.get(), s.get(), lo.get(), prec);
    local = div_rational(local, S[j + 1] - S[j], prec);
    clamp_unit(local.get(), prec);
    f(j, local);
    any = true;
  }
  if (!any) throw InvalidArgument(outside);
}

}  // namespace uniparam::composite_detail
