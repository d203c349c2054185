// The public header includes no FLINT, Arb, GMP or MPFR header and no engine
// header: this file fails to compile otherwise.
#include "uniparam/uniparam.hpp"

#if defined(FLINT_H) || defined(FMPZ_H) || defined(FMPQ_H) || defined(ARB_H) || defined(ACB_H) || \
    defined(ARF_H) || defined(MAG_H) || defined(__GMP_H__) || defined(__MPFR_H)
#error "uniparam/uniparam.hpp includes a FLINT/Arb/GMP/MPFR header"
#endif

#include <gtest/gtest.h>

// Each alias conflicts with the engine's class of that name, were an engine
// header included above.
namespace uniparam {
using Ball = int;
using Rational = int;
using Curve = int;
using Speed = int;
using Options = int;
using RealAlgebraic = int;
}  // namespace uniparam

namespace {

TEST(ApiHeader, IsSelfContainedWithoutEngineOrFlintHeaders) {
  uniparam::Ball engine_names_free = 0;
  uniparam::api::Options o;
  const uniparam::api::Curve c = uniparam::api::Curve::parse("(t, t^2)", o);
  EXPECT_EQ(c.dimension(), 2u);
  EXPECT_EQ(engine_names_free, 0);
}

}  // namespace
