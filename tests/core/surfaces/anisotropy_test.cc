// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/surfaces/anisotropy.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(Eq3, MatchesHandValuesAtZeroQuarterAndHalfPi) {
  // mu_a = 0.3, mu_n = 0.9: 0.3 + 2 theta (0.6) / pi
  const auto linear = AnisotropyInterpolation::kLinear;
  EXPECT_DOUBLE_EQ(InterpolateFriction(0.3, 0.9, 0.0, linear), 0.3);
  EXPECT_DOUBLE_EQ(InterpolateFriction(0.3, 0.9, kPi / 4, linear), 0.6);
  EXPECT_DOUBLE_EQ(InterpolateFriction(0.3, 0.9, kPi / 2, linear), 0.9);
}

TEST(FrictionEllipse, MatchesHandValues) {
  const auto ellipse = AnisotropyInterpolation::kEllipse;
  EXPECT_DOUBLE_EQ(InterpolateFriction(0.3, 0.9, 0.0, ellipse), 0.3);
  EXPECT_NEAR(InterpolateFriction(0.3, 0.9, kPi / 2, ellipse), 0.9, 1e-15);
  // at 45 degrees: 0.27 / sqrt((0.81 + 0.09) / 2) = 0.27 / sqrt(0.45)
  EXPECT_NEAR(InterpolateFriction(0.3, 0.9, kPi / 4, ellipse), 0.27 / std::sqrt(0.45), 1e-15);
  EXPECT_EQ(InterpolateFriction(0.0, 0.0, 0.7, ellipse), 0.0);  // no 0/0
}

TEST(FrictionEllipse, ADegenerateEllipseKeepsItsAxesValues) {
  // mu_n = 0 (no friction across the stripes): 0/0 along them gave 0, not mu_a; as eq. 3,
  // the ellipse is mu_a at 0 and mu_n at pi/2, and off its one axis 0 (its limit)
  const auto ellipse = AnisotropyInterpolation::kEllipse;
  EXPECT_EQ(InterpolateFriction(0.3, 0.0, 0.0, ellipse), 0.3);
  EXPECT_EQ(InterpolateFriction(0.3, 0.0, 1e-9, ellipse), 0.0);
  EXPECT_EQ(InterpolateFriction(0.3, 0.0, kPi / 2, ellipse), 0.0);
  EXPECT_NEAR(InterpolateFriction(0.3, 1e-12, 1e-9, ellipse), 0.3 / std::sqrt(1.0 + 0.09e6), 1e-15);
  // mu_a = 0 (none along them): mu_n across, and cos(pi/2) = 6e-17 gave 0 there
  EXPECT_EQ(InterpolateFriction(0.0, 0.9, kPi / 2, ellipse), 0.9);
  EXPECT_EQ(InterpolateFriction(0.0, 0.9, 0.0, ellipse), 0.0);
  EXPECT_EQ(InterpolateFriction(0.0, 0.9, kPi / 2 - 1e-9, ellipse), 0.0);
  EXPECT_EQ(InterpolateFriction(0.0, 0.0, 0.0, ellipse), 0.0);
}

TEST(FoldAngle, IsEvenPiPeriodicAndExactOnBoundaries) {
  EXPECT_EQ(FoldAngle(0.0), 0.0);
  EXPECT_DOUBLE_EQ(FoldAngle(kPi / 2), kPi / 2);
  EXPECT_NEAR(FoldAngle(kPi), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(FoldAngle(-kPi / 2), kPi / 2);
  EXPECT_NEAR(FoldAngle(3 * kPi / 2), kPi / 2, 1e-15);
  EXPECT_NEAR(FoldAngle(-kPi), 0.0, 1e-15);
  for (double t : {0.1, 0.7, 1.3, 1.5}) {
    EXPECT_NEAR(FoldAngle(t), FoldAngle(-t), 1e-15);
    EXPECT_NEAR(FoldAngle(t), FoldAngle(t + kPi), 1e-14);
    EXPECT_NEAR(FoldAngle(kPi - t), t, 1e-15);
  }
  EXPECT_TRUE(std::isnan(FoldAngle(std::numeric_limits<double>::quiet_NaN())));
}

class Directional : public ::testing::Test {
 protected:
  FrictionParams along_;
  AnisotropicFriction a_;
  void SetUp() override {
    along_.static_coefficient = 0.4;
    along_.dynamic_coefficient = 0.3;
    a_.across_factor = 3.0;  // mu_n = 1.2 / 0.9
  }
  double MuD(const Vec3& v, double weight = 1.0) const {
    return DirectionalFriction(along_, a_, Vec3::UnitX(), weight, v).dynamic_coefficient;
  }
};

TEST_F(Directional, AlongAcrossAndDiagonal) {
  EXPECT_DOUBLE_EQ(MuD(Vec3(0.05, 0, 0)), 0.3);
  EXPECT_DOUBLE_EQ(MuD(Vec3(0, 0.05, 0)), 0.9);
  EXPECT_NEAR(MuD(Vec3(0.05, 0.05, 0)), 0.6, 1e-15);
  EXPECT_NEAR(MuD(Vec3(-0.05, -0.05, 0)), 0.6, 1e-15);  // even
  EXPECT_DOUBLE_EQ(
      DirectionalFriction(along_, a_, Vec3::UnitX(), 1.0, Vec3(0, 1, 0)).static_coefficient, 1.2);
}

TEST_F(Directional, BackwardFactorAppliesAgainstTheStripeDirection) {
  a_.backward_factor = 2.0;
  EXPECT_DOUBLE_EQ(MuD(Vec3(0.05, 0, 0)), 0.3);
  EXPECT_DOUBLE_EQ(MuD(Vec3(-0.05, 0, 0)), 0.6);
  EXPECT_DOUBLE_EQ(MuD(Vec3(0, 0.05, 0)), 0.9);  // across: unchanged
}

TEST_F(Directional, AnEllipseWithoutFrictionAcrossKeepsItAlongTheStripes) {
  // a stroke exactly along the stripes (a scripted one) felt none of mu_a
  a_.interpolation = AnisotropyInterpolation::kEllipse;
  a_.across_factor = 0.0;
  EXPECT_EQ(MuD(Vec3(0.05, 0, 0)), 0.3);
  EXPECT_EQ(MuD(Vec3(0.05, 1e-6, 0)), 0.0);
  EXPECT_EQ(MuD(Vec3(0, 0.05, 0)), 0.0);
  // none against them either (backward 0): friction across them only
  a_.across_factor = 3.0;
  a_.backward_factor = 0.0;
  EXPECT_EQ(MuD(Vec3(-0.05, 0, 0)), 0.0);
  EXPECT_DOUBLE_EQ(MuD(Vec3(0, 0.05, 0)), 0.9);  // 3 x 0.3
  EXPECT_EQ(MuD(Vec3(-1e-6, 0.05, 0)), 0.0);
}

TEST_F(Directional, ZeroWeightIsTheIsotropicMean) {
  EXPECT_DOUBLE_EQ(MuD(Vec3(0.05, 0, 0), 0.0), 0.6);
  EXPECT_DOUBLE_EQ(MuD(Vec3(0, 0.05, 0), 0.0), 0.6);
}

TEST_F(Directional, ZeroAndTinyVelocitiesStayFinite) {
  const double denormal = std::numeric_limits<double>::denorm_min();
  for (const Vec3& v :
       {Vec3(0, 0, 0), Vec3(1e-300, 0, 0), Vec3(0, denormal, 0), Vec3(-denormal, denormal, 0)}) {
    const double mu = MuD(v);
    EXPECT_TRUE(std::isfinite(mu));
    EXPECT_GE(mu, 0.3 - 1e-15);
    EXPECT_LE(mu, 0.9 + 1e-15);
  }
}

}  // namespace
}  // namespace hapticad
