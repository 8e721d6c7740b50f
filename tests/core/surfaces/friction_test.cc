// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/surfaces/friction.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

FrictionParams Params(double mu_s, double mu_d) {
  FrictionParams p;
  p.static_coefficient = mu_s;
  p.dynamic_coefficient = mu_d;
  p.stick_speed_mps = 0.002;
  p.transition_speed_mps = 0.002;
  return p;
}

TEST(EquivalentFriction, IsZeroAtRestAndExactlyMuStaticAtEps) {
  const FrictionParams p = Params(0.6, 0.4);
  EXPECT_EQ(EquivalentFriction(p, 0.0), 0.0);
  EXPECT_EQ(EquivalentFriction(p, p.stick_speed_mps), 0.6);
}

TEST(EquivalentFriction, IsContinuousAtZeroEpsAndEndOfTransition) {
  const FrictionParams p = Params(0.6, 0.4);
  const double eps = p.stick_speed_mps;
  const double w = p.transition_speed_mps;
  for (double h : {1e-6, 1e-9, 1e-12}) {
    // bounds: the slope mu_s / eps times the step, plus rounding of the step itself
    EXPECT_NEAR(EquivalentFriction(p, h * eps), 0.0, 0.6 * h + 1e-15);
    EXPECT_NEAR(EquivalentFriction(p, eps * (1 - h)), 0.6, 0.6 * h + 1e-15);
    EXPECT_NEAR(EquivalentFriction(p, eps * (1 + h)), 0.6, 3 * h * eps / w + 1e-15);
    EXPECT_NEAR(EquivalentFriction(p, (eps + w) * (1 - h)), 0.4, 1e-3 * std::sqrt(h) + 1e-12);
  }
  EXPECT_EQ(EquivalentFriction(p, eps + w), 0.4);
  EXPECT_EQ(EquivalentFriction(p, 1.0), 0.4);
  EXPECT_EQ(EquivalentFriction(p, 1e300), 0.4);
}

TEST(EquivalentFriction, IsMonotoneThroughTheTransition) {
  const FrictionParams p = Params(0.8, 0.3);
  double previous = EquivalentFriction(p, p.stick_speed_mps);
  for (double s = p.stick_speed_mps; s < 3 * p.stick_speed_mps; s += 1e-5) {
    const double mu = EquivalentFriction(p, s);
    EXPECT_LE(mu, previous + 1e-15);
    previous = mu;
  }
}

TEST(EquivalentFriction, ZeroTransitionWidthIsThePapersJump) {
  FrictionParams p = Params(0.6, 0.4);
  p.transition_speed_mps = 0.0;
  EXPECT_EQ(EquivalentFriction(p, p.stick_speed_mps), 0.6);
  EXPECT_EQ(EquivalentFriction(p, std::nextafter(p.stick_speed_mps, 1.0)), 0.4);
}

TEST(EquivalentFriction, BadSpeedsGiveZero) {
  const FrictionParams p = Params(0.6, 0.4);
  EXPECT_EQ(EquivalentFriction(p, -1.0), 0.0);
  EXPECT_EQ(EquivalentFriction(p, std::numeric_limits<double>::quiet_NaN()), 0.0);
}

TEST(CalcFrictionForce, OpposesVelocityWithMuDynamicWhenSliding) {
  const FrictionParams p = Params(0.6, 0.4);
  const Vec3 v(0.03, -0.04, 0.0);  // 50 mm/s
  const Vec3 f = CalcFrictionForce(p, 2.0, v);
  EXPECT_NEAR(f.norm(), 0.4 * 2.0, 1e-12);
  EXPECT_NEAR(f.normalized().dot(v.normalized()), -1.0, 1e-12);
}

TEST(CalcFrictionForce, IsFiniteAndContinuousNearZeroVelocity) {
  const FrictionParams p = Params(0.6, 0.4);
  const double denormal = std::numeric_limits<double>::denorm_min();
  for (double s : {0.0, 1e-300, denormal, -1e-300, -denormal}) {
    const Vec3 f = CalcFrictionForce(p, 1.0, Vec3(s, 0.0, 0.0));
    EXPECT_TRUE(f.allFinite()) << s;
    EXPECT_LE(f.norm(), 1e-290) << s;
  }
  // in the static band the force is linear in v: mu_s f_n v / eps
  const Vec3 f = CalcFrictionForce(p, 1.0, Vec3(0.001, 0.0, 0.0));
  EXPECT_NEAR(f.x(), -0.6 * 0.5, 1e-15);
}

TEST(CalcFrictionForce, MagnitudeIsContinuousAcrossEps) {
  const FrictionParams p = Params(0.6, 0.4);
  const double eps = p.stick_speed_mps;
  const double below = CalcFrictionForce(p, 1.0, Vec3(eps * (1 - 1e-12), 0, 0)).norm();
  const double at = CalcFrictionForce(p, 1.0, Vec3(eps, 0, 0)).norm();
  const double above = CalcFrictionForce(p, 1.0, Vec3(eps * (1 + 1e-12), 0, 0)).norm();
  EXPECT_NEAR(below, 0.6, 1e-11);
  EXPECT_NEAR(at, 0.6, 1e-15);
  EXPECT_NEAR(above, 0.6, 1e-11);
}

TEST(CalcFrictionForce, NonFiniteInputsGiveZero) {
  const FrictionParams p = Params(0.6, 0.4);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(CalcFrictionForce(p, nan, Vec3(0.1, 0, 0)), Vec3::Zero());
  EXPECT_EQ(CalcFrictionForce(p, 1.0, Vec3(nan, 0, 0)), Vec3::Zero());
  EXPECT_EQ(CalcFrictionForce(p, 1.0, Vec3(inf, 0, 0)), Vec3::Zero());
  EXPECT_EQ(CalcFrictionForce(p, -1.0, Vec3(0.1, 0, 0)), Vec3::Zero());
}

}  // namespace
}  // namespace hapticad

namespace hapticad {
namespace {

TEST(StribeckFriction, DecaysContinuouslyFromMuStaticTowardMuDynamic) {
  FrictionParams p;
  p.static_coefficient = 0.8;
  p.dynamic_coefficient = 0.4;
  p.stick_speed_mps = 0.002;
  p.stribeck_speed_mps = 0.01;
  const double eps = p.stick_speed_mps;
  EXPECT_EQ(EquivalentFriction(p, eps), 0.8);
  EXPECT_NEAR(EquivalentFriction(p, eps * (1 + 1e-12)), 0.8, 1e-12);
  EXPECT_NEAR(EquivalentFriction(p, eps + 0.01), 0.4 + 0.4 * std::exp(-1.0), 1e-15);
  EXPECT_NEAR(EquivalentFriction(p, 10.0), 0.4, 1e-15);
  EXPECT_GT(EquivalentFriction(p, 0.05), 0.4);  // approaches, never reaches
}

TEST(FrictionExtremes, ZeroHugeAndInvertedCoefficientsStayFinite) {
  for (double mu_s : {0.0, 0.3, 1e3}) {
    for (double mu_d : {0.0, 0.6, 1e3}) {  // includes mu_d > mu_s
      FrictionParams p;
      p.static_coefficient = mu_s;
      p.dynamic_coefficient = mu_d;
      for (double v : {0.0, 1e-300, 0.002, 0.003, 0.05, 1e3}) {
        const Vec3 f = CalcFrictionForce(p, 2.0, Vec3(v, -v, 0));
        ASSERT_TRUE(f.allFinite()) << mu_s << " " << mu_d << " " << v;
        EXPECT_LE(f.norm(), 2.0 * std::max(mu_s, mu_d) * (1 + 1e-12) + 1e-300);
      }
      EXPECT_EQ(CalcFrictionForce(p, 2.0, Vec3(0.05, 0, 0)).norm(), 0.0 * mu_d + 2.0 * mu_d);
    }
  }
}

}  // namespace
}  // namespace hapticad
