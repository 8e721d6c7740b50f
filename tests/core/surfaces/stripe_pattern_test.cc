// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/surfaces/stripe_pattern.h"

#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

TEST(LinearPattern, ProjectsTheDirectionOntoTheTangentPlane) {
  const StripeFrame flat = EvaluateLinear({Vec3(1, 0, 0)}, Vec3::Zero(), Vec3::UnitZ());
  EXPECT_NEAR((flat.stripe - Vec3::UnitX()).norm(), 0, 1e-15);
  EXPECT_EQ(flat.weight, 1.0);
  // a face tilted 30 degrees about y: the stripe follows the slope
  const Vec3 n(-0.5, 0, std::sqrt(0.75));
  const StripeFrame tilted = EvaluateLinear({Vec3(1, 0, 0)}, Vec3::Zero(), n);
  EXPECT_NEAR(tilted.stripe.dot(n), 0.0, 1e-15);
  EXPECT_NEAR((tilted.stripe - Vec3(std::sqrt(0.75), 0, 0.5)).norm(), 0, 1e-15);
}

TEST(LinearPattern, FadesWhereTheDirectionTurnsNormalToTheFace) {
  const StripeFrame along_normal = EvaluateLinear({Vec3(0, 0, 1)}, Vec3::Zero(), Vec3::UnitZ());
  EXPECT_EQ(along_normal.weight, 0.0);
  EXPECT_NEAR(along_normal.stripe.dot(Vec3::UnitZ()), 0.0, 1e-15);
  EXPECT_NEAR(along_normal.stripe.norm(), 1.0, 1e-15);
  const double s = 0.05;  // half the blend: half the weight
  EXPECT_NEAR(
      EvaluateLinear({Vec3(s, 0, std::sqrt(1 - s * s))}, Vec3::Zero(), Vec3::UnitZ()).weight, 0.5,
      1e-12);
}

TEST(LinearPattern, OnACylinderIsRolledRoundTheAxisAllTheWay) {
  // a handle of radius 20 mm along z; at its origin (+x) the stripes run round it (+y) or,
  // turned 30 degrees, along a helix. Projected, the round stripes faded to isotropic a
  // quarter turn away (their direction normal to the face) and reversed beyond it.
  const double radius = 0.02;
  for (const double turn : {0.0, M_PI / 6}) {
    const Vec3 d(0, std::cos(turn), std::sin(turn));
    const LinearPattern p{d, radius, Vec3(radius, 0, 0.005), Vec3(0, 0, 0.005), Vec3::UnitZ()};
    for (int k = 0; k < 24; ++k) {
      const double a = 2 * M_PI * k / 24;
      const Vec3 outward(std::cos(a), std::sin(a), 0);
      const Vec3 round = Vec3::UnitZ().cross(outward);
      const StripeFrame f = EvaluateLinear(p, radius * outward + Vec3(0, 0, 0.03), outward);
      EXPECT_EQ(f.weight, 1.0) << turn << " " << k;
      // the same parts round and along at every angle, the same way round (not reversed)
      EXPECT_NEAR((f.stripe - (std::cos(turn) * round + std::sin(turn) * Vec3::UnitZ())).norm(),
                  0.0, 1e-12)
          << turn << " " << k;
    }
  }
  // on the axis (no round direction there) the origin's
  const LinearPattern p{Vec3::UnitY(), radius, Vec3(radius, 0, 0), Vec3::Zero(), Vec3::UnitZ()};
  const StripeFrame on_axis = EvaluateLinear(p, Vec3(0, 0, 0.01), Vec3::UnitX());
  EXPECT_TRUE(on_axis.stripe.allFinite());
  EXPECT_NEAR((on_axis.stripe - Vec3::UnitY()).norm(), 0.0, 1e-12);
  // a cylinder that does not hold its origin, or a direction not tangent there, is said
  EXPECT_STREQ(DescribeLinearCylinderProblem(p), "");
  EXPECT_STREQ(DescribeLinearCylinderProblem(LinearPattern{Vec3::UnitY()}), "");
  LinearPattern off = p;
  off.origin_w = Vec3(0.03, 0, 0);
  EXPECT_NE(std::string(DescribeLinearCylinderProblem(off)).find("origin"), std::string::npos);
  LinearPattern radial = p;
  radial.direction_w = Vec3::UnitX();
  EXPECT_NE(std::string(DescribeLinearCylinderProblem(radial)).find("tangent"), std::string::npos);
}

TEST(CircularPattern, StripesAreTangentToCirclesAtSeveralPoints) {
  const CircularPattern c{Vec3(0.01, 0.02, 0.0), Vec3::UnitZ(), 1e-3};
  struct Case {
    Vec3 point;
    Vec3 tangent;  // axis x radial, normalised, by hand
  };
  const Case cases[] = {
      {Vec3(0.03, 0.02, 0), Vec3(0, 1, 0)},                          // +x of the centre
      {Vec3(0.01, 0.05, 0), Vec3(-1, 0, 0)},                         // +y
      {Vec3(-0.01, 0.02, 0), Vec3(0, -1, 0)},                        // -x
      {Vec3(0.02, 0.03, 0), Vec3(-1, 1, 0) / std::sqrt(2.0)},        // diagonal
      {Vec3(0.01 + 0.003, 0.02 - 0.004, 0.0), Vec3(0.8, 0.6, 0.0)},  // 3-4-5
  };
  for (const Case& k : cases) {
    const StripeFrame f = EvaluateCircular(c, k.point, Vec3::UnitZ());
    EXPECT_NEAR((f.stripe - k.tangent).norm(), 0.0, 1e-12) << k.point.transpose();
    EXPECT_EQ(f.weight, 1.0);
  }
}

TEST(CircularPattern, AtTheCentreFrictionIsIsotropicAndApproachesItContinuously) {
  const CircularPattern c{Vec3(0, 0, 0), Vec3::UnitZ(), 1e-3};
  const StripeFrame centre = EvaluateCircular(c, Vec3::Zero(), Vec3::UnitZ());
  EXPECT_EQ(centre.weight, 0.0);
  EXPECT_TRUE(centre.stripe.allFinite());
  EXPECT_NEAR(EvaluateCircular(c, Vec3(2.5e-4, 0, 0), Vec3::UnitZ()).weight, 0.25, 1e-12);
  EXPECT_NEAR(EvaluateCircular(c, Vec3(1e-300, 0, 0), Vec3::UnitZ()).weight, 0.0, 1e-290);
  // a point on the axis but off the face's plane is still the centre
  EXPECT_EQ(EvaluateCircular(c, Vec3(0, 0, 0.01), Vec3::UnitZ()).weight, 0.0);
}

TEST(CircularPattern, NonFinitePointsGiveAnIsotropicFrame) {
  const CircularPattern c{Vec3(0, 0, 0), Vec3::UnitZ(), 1e-3};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const StripeFrame f = EvaluateCircular(c, Vec3(nan, 0, 0), Vec3::UnitZ());
  EXPECT_EQ(f.weight, 0.0);
  EXPECT_TRUE(f.stripe.allFinite());
}

}  // namespace
}  // namespace hapticad
