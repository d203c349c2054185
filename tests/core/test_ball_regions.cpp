// Tests of core/ball_regions.hpp: which radii make a ball a region of the
// quadrature and which a wide (coarsely bounded) ball, on either side of each
// threshold and in either component.
#include <acb.h>
#include <gtest/gtest.h>

#include "uniparam/core/ball_regions.hpp"

namespace uniparam {
namespace {

// z = 1/3 + i/5 with real (or imaginary) radius 2^e (times 1 - 2^-20 for
// "just below").
void ball(acb_t z, long e, bool below, bool imaginary) {
  acb_set_si(z, 1);
  arb_div_ui(acb_realref(z), acb_realref(z), 3, 64);
  arb_set_si(acb_imagref(z), 1);
  arb_div_ui(acb_imagref(z), acb_imagref(z), 5, 64);
  mag_zero(arb_radref(acb_realref(z)));
  mag_zero(arb_radref(acb_imagref(z)));
  mag_struct* r = arb_radref(imaginary ? acb_imagref(z) : acb_realref(z));
  if (below) mag_set_ui_2exp_si(r, (1UL << 20) - 1, e - 20);
  else mag_set_ui_2exp_si(r, 1, e);
}

TEST(BallRegions, ThresholdsSplitRadiiInEitherComponent) {
  acb_t z;
  acb_init(z);
  for (bool im : {false, true}) {
    ball(z, kCoarseBallLog2, false, im);
    EXPECT_TRUE(is_wide_ball(z));
    EXPECT_TRUE(is_region_ball(z));
    ball(z, kCoarseBallLog2, true, im);
    EXPECT_FALSE(is_wide_ball(z));
    EXPECT_TRUE(is_region_ball(z));  // between the thresholds: a region bounded accurately
    ball(z, kRegionBallLog2, false, im);
    EXPECT_FALSE(is_wide_ball(z));
    EXPECT_TRUE(is_region_ball(z));
    ball(z, kRegionBallLog2, true, im);
    EXPECT_FALSE(is_wide_ball(z));
    EXPECT_FALSE(is_region_ball(z));
  }
  acb_clear(z);
  // every wide ball is a region (a quadrature node is never bounded coarsely)
  static_assert(kRegionBallLog2 < kCoarseBallLog2, "wide balls must be regions");
}

TEST(BallRegions, BallRadiusBoundsBothComponents) {
  acb_t z;
  acb_init(z);
  ball(z, -10, false, false);
  mag_set_ui_2exp_si(arb_radref(acb_imagref(z)), 1, -10);
  mag_t r;
  mag_init(r);
  ball_radius(r, z);
  EXPECT_GE(mag_cmp_2exp_si(r, -10), 0);      // >= 2^-10 sqrt(2)
  EXPECT_LT(mag_cmp_2exp_si(r, -9), 0);       // < 2^-9
  mag_clear(r);
  acb_clear(z);
}

}  // namespace
}  // namespace uniparam
