// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/surfaces/viscous_texture.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

TEST(Eq2, MatchesHandValuesAtChosenPositionsAndSpeeds) {
  ViscousTextureParams p;  // f_DC 0.5, beta_h 0.125, alpha_h 2.5, period 2.5 mm
  p.f_vis = 0.2;
  // x = lambda/4: sin(pi/2 i) = 1, 0, -1, 0 -> 1 - 3^-2.5
  const double h = 1.0 - std::pow(3.0, -2.5);
  EXPECT_NEAR(ViscousTextureLevel(p, 0.625e-3, 0.0), 0.5 + 0.125 * h, 1e-15);
  // at 200 mm/s, v = 0.5 units: + 0.5 * 0.2
  EXPECT_NEAR(ViscousTextureLevel(p, 0.625e-3, 0.2), 0.6 + 0.125 * h, 1e-15);
  // x = 0: every sine is 0
  EXPECT_NEAR(ViscousTextureLevel(p, 0.0, 0.4), 0.7, 1e-15);
  // x = lambda/8: sum sin(i pi / 4) i^-2.5, written out
  const double s = std::sin(M_PI / 4) + std::pow(2.0, -2.5) * 1.0 +
                   std::pow(3.0, -2.5) * std::sin(3 * M_PI / 4) + 0.0;
  EXPECT_NEAR(ViscousTextureLevel(p, 0.3125e-3, 0.0), 0.5 + 0.125 * s, 1e-15);
}

TEST(Eq2, VelocityDependentHarmonicsFollowBetaVisAndAlphaVis) {
  ViscousTextureParams p;
  p.beta_vis = 0.1;
  p.alpha_vis = -1.0;
  // v = 1 unit (400 mm/s): beta 0.225, alpha 1.5 at x = lambda/4
  const double expected = 0.5 + 0.225 * (1.0 - std::pow(3.0, -1.5));
  EXPECT_NEAR(ViscousTextureLevel(p, 0.625e-3, 0.4), expected, 1e-15);
}

TEST(Eq2, PaperPresetsAreTheNineExperimentTextures) {
  int count = 0;
  for (int dc = 0; dc < 3; ++dc) {
    for (int vis = 0; vis < 3; ++vis) {
      const ViscousTextureParams p = PaperPreset(dc, vis);
      EXPECT_EQ(p.f_dc, (std::array<double, 3>{0.325, 0.5, 0.675})[dc]);
      EXPECT_EQ(p.f_vis, (std::array<double, 3>{-0.2, 0.0, 0.2})[vis]);
      EXPECT_EQ(p.beta_h, 0.125);
      EXPECT_EQ(p.alpha_h, 2.5);
      EXPECT_EQ(p.beta_vis, 0.0);
      EXPECT_EQ(p.alpha_vis, 0.0);
      ++count;
    }
  }
  EXPECT_EQ(count, 9);
  EXPECT_THROW(PaperPreset(3, 0), std::out_of_range);
}

TEST(ViscousTextureForce, ResistsMotionWithinTheDevicesRange) {
  const ViscousTextureParams p = PaperPreset(1, 1);
  const Vec3 f = CalcViscousTextureForce(p, 3.3, 0.0, Vec3(0.05, 0, 0), 0.002);
  EXPECT_NEAR(f.x(), -0.5 * 3.3, 1e-12);
  // a level above 1 is capped, below 0 is floored
  ViscousTextureParams big = p;
  big.f_dc = 3.0;
  EXPECT_NEAR(CalcViscousTextureForce(big, 3.3, 0.0, Vec3(0, 0.05, 0), 0.002).norm(), 3.3, 1e-12);
  ViscousTextureParams negative = p;
  negative.f_dc = -1.0;
  EXPECT_EQ(CalcViscousTextureForce(negative, 3.3, 0.0, Vec3(0, 0.05, 0), 0.002), Vec3::Zero());
}

TEST(ViscousTextureForce, IsZeroAtRestAndFiniteForTinyAndBadInputs) {
  const ViscousTextureParams p = PaperPreset(2, 2);
  EXPECT_EQ(CalcViscousTextureForce(p, 3.3, 0.0, Vec3::Zero(), 0.002), Vec3::Zero());
  const Vec3 tiny = CalcViscousTextureForce(p, 3.3, 0.0, Vec3(1e-300, 0, 0), 0.002);
  EXPECT_TRUE(tiny.allFinite());
  EXPECT_LT(tiny.norm(), 1e-290);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(CalcViscousTextureForce(p, 3.3, nan, Vec3(0.1, 0, 0), 0.002), Vec3::Zero());
  EXPECT_EQ(CalcViscousTextureForce(p, 3.3, 0.0, Vec3(nan, 0, 0), 0.002), Vec3::Zero());
}

TEST(ViscousTexture, HarmonicsGrowingWithTheirOrderStayFinite) {
  // alpha_h -650 or -1100 (a typo, or a fit gone wild): i^650 overflowed to inf and
  // inf - inf made the force NaN at half the positions, and the renderer then dropped the
  // whole force, the push with it. Now a square wave of the strongest harmonic, 0 or full.
  for (double alpha : {-650.0, -1100.0, -1e6}) {
    ViscousTextureParams p;
    p.alpha_h = alpha;
    p.beta_h = 0.125;
    p.f_dc = 0.5;
    int full = 0, none = 0;
    for (int k = 0; k < 1000; ++k) {
      const Vec3 f =
          CalcViscousTextureForce(p, 2.0, k * p.period_m / 1000.0, Vec3(0.1, 0, 0), 1e-3);
      ASSERT_TRUE(f.allFinite()) << alpha << " at " << k;
      if (std::abs(f.x() + 2.0) < 1e-12) ++full;
      if (f.norm() == 0.0) ++none;
    }
    EXPECT_GT(full, 300) << alpha;
    EXPECT_GT(none, 300) << alpha;
  }
}

}  // namespace
}  // namespace hapticad
