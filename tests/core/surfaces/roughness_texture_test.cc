// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/surfaces/roughness_texture.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

RoughnessGrid Grid(int category) {
  SurfaceFrame frame;
  frame.origin_w = Vec3(0.1, 0.2, 0.3);
  return MakeRoughnessGrid(category, frame);
}

TEST(RoughnessGrid, SpacingIsTheTable2BallSize) {
  const double expected_mm[] = {0.1, 0.3, 0.6, 0.9, 1.2, 1.5, 3.0};
  for (int c = 1; c <= 7; ++c) {
    const RoughnessGrid g = Grid(c);
    EXPECT_DOUBLE_EQ(g.spacing_m, expected_mm[c - 1] * 1e-3);
    EXPECT_DOUBLE_EQ(g.amplitude_m, 0.05 * g.spacing_m);
  }
}

TEST(RoughnessGrid, BallsOnTheNodesFlatBetween) {
  const RoughnessGrid g = Grid(6);  // 1.5 mm, 75 um
  const Vec3 o = g.frame.origin_w;
  const RoughnessSample node = SampleRoughness(g, o + Vec3(3 * 1.5e-3, -2 * 1.5e-3, 0));
  EXPECT_NEAR(node.height_m, 0.75 * 75e-6, 1e-15);
  EXPECT_NEAR(node.gradient_w.norm(), 0.0, 1e-12);
  EXPECT_NEAR(node.friction_scale, 1.15, 1e-12);
  const RoughnessSample between = SampleRoughness(g, o + Vec3(0.75e-3, 0.3e-3, 0));
  EXPECT_NEAR(between.height_m, -0.25 * 75e-6, 1e-18);
  EXPECT_NEAR(between.friction_scale, 0.95, 1e-12);
  // halfway along x on a node row: b = 1/2, slope dh/dx = -A pi / g (hand computed)
  const RoughnessSample half = SampleRoughness(g, o + Vec3(0.375e-3, 0, 0));
  EXPECT_NEAR(half.height_m, 0.25 * 75e-6, 1e-15);
  EXPECT_NEAR(half.gradient_w.x(), -75e-6 * 3.14159265358979323846 / 1.5e-3, 1e-12);
}

TEST(RoughnessGrid, GradientMatchesFiniteDifferences) {
  const RoughnessGrid g = Grid(4);
  for (double x = 0.0; x < 2e-3; x += 1.7e-4) {
    const Vec3 p = g.frame.origin_w + Vec3(x, 0.31 * x + 1e-4, 0);
    const double h = 1e-9;
    const double dx = (SampleRoughness(g, p + Vec3(h, 0, 0)).height_m -
                       SampleRoughness(g, p - Vec3(h, 0, 0)).height_m) /
                      (2 * h);
    const double dy = (SampleRoughness(g, p + Vec3(0, h, 0)).height_m -
                       SampleRoughness(g, p - Vec3(0, h, 0)).height_m) /
                      (2 * h);
    const Vec3 grad = SampleRoughness(g, p).gradient_w;
    EXPECT_NEAR(grad.x(), dx, 1e-6);
    EXPECT_NEAR(grad.y(), dy, 1e-6);
  }
}

TEST(RoughnessGrid, HeightAndFrictionScaleAverageToZeroAndOneOverTheGrid) {
  const RoughnessGrid g = Grid(5);
  double height = 0.0, scale = 0.0;
  const int n = 64;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const RoughnessSample s =
          SampleRoughness(g, g.frame.origin_w + Vec3(i, j, 0) * (g.spacing_m / n));
      height += s.height_m / (n * n);
      scale += s.friction_scale / (n * n);
    }
  }
  EXPECT_NEAR(height, 0.0, 1e-18);
  EXPECT_NEAR(scale, 1.0, 1e-14);
}

TEST(RoughnessGrid, IsPeriodicFarFromTheFrameOrigin) {
  const RoughnessGrid g = Grid(3);
  const Vec3 near = g.frame.origin_w + Vec3(1.23e-4, 4.5e-5, 0);
  const Vec3 far = near + Vec3(1000 * 0.6e-3, -2000 * 0.6e-3, 0);
  EXPECT_NEAR(SampleRoughness(g, near).height_m, SampleRoughness(g, far).height_m, 1e-15);
}

TEST(RoughnessGrid, NonFinitePointsAreFlat) {
  const RoughnessSample s =
      SampleRoughness(Grid(2), Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0));
  EXPECT_EQ(s.height_m, 0.0);
  EXPECT_EQ(s.gradient_w, Vec3::Zero());
  EXPECT_EQ(s.friction_scale, 1.0);
}

TEST(RoughnessGrid, KeepsItsSpacingAllRoundACylinder) {
  // a category 3 grid (0.6 mm) on a 15 mm handle: a ball every 0.6 mm of arc all round
  // it (laid on the centre's tangent plane, the balls were 1.2 mm apart 60 degrees round)
  SurfaceFrame frame;
  frame.radius_m = 0.015;
  frame.axis_point_w = Vec3(0.0, 0.0, 0.0);
  frame.axis_w = Vec3::UnitZ();
  frame.origin_w = Vec3(0.015, 0.0, 0.0);
  frame.e1_w = Vec3::UnitY();
  frame.e2_w = Vec3::UnitX().cross(frame.e1_w);
  const RoughnessGrid g = MakeRoughnessGrid(3, frame);
  for (int node : {-78, -60, 17, 60, 78}) {  // (the seam, opposite the origin, is at 78.5)
    const double angle = node * 0.6e-3 / 0.015;
    const Vec3 on = Vec3(0.015 * std::cos(angle), 0.015 * std::sin(angle), 2 * 0.6e-3);
    const RoughnessSample s = SampleRoughness(g, on);
    EXPECT_NEAR(s.height_m, 0.75 * g.amplitude_m, 1e-15) << node;
    // between two balls round the handle: the slope lies in the tangent plane there
    const double half = angle + 0.5 * 0.3e-3 / 0.015;
    const Vec3 between = Vec3(0.015 * std::cos(half), 0.015 * std::sin(half), 2 * 0.6e-3);
    const RoughnessSample b = SampleRoughness(g, between);
    EXPECT_GT(b.gradient_w.norm(), 0.1) << node;
    EXPECT_NEAR(b.gradient_w.dot(Vec3(std::cos(half), std::sin(half), 0)), 0.0, 1e-12) << node;
  }
}

}  // namespace
}  // namespace hapticad
