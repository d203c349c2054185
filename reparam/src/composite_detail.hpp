// Internal to the composite curves (not installed): what composite.cpp (the
// curve and its uniformity), composite_map.cpp, composite_sample.cpp and
// composite_locate.cpp share: segment error labels, the segments' options
// and working precision, and exact rational scalings of balls.
#pragma once

#include <arb.h>

#include <algorithm>
#include <string>

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
  o.digits = std::min(opt.digits + 2, 10000L);
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

}  // namespace uniparam::composite_detail
