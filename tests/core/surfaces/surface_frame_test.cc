// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/surfaces/surface_frame.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A handle: radius 15 mm round the z axis through (0.1, 0.2, 0.3) m, the frame at the
// point on +x, e1 round the handle (+y there) and e2 along it (+z), turned by `turn`.
SurfaceFrame Handle(double turn = 0.0) {
  SurfaceFrame f;
  f.radius_m = 0.015;
  f.axis_point_w = Vec3(0.1, 0.2, 0.3);
  f.axis_w = Vec3::UnitZ();
  f.origin_w = f.axis_point_w + Vec3(0.015, 0.0, 0.004);
  f.e1_w = std::cos(turn) * Vec3::UnitY() + std::sin(turn) * Vec3::UnitZ();
  f.e2_w = Vec3::UnitX().cross(f.e1_w);
  return f;
}

Vec3 OnHandle(const SurfaceFrame& f, double angle, double along) {
  return f.axis_point_w + Vec3(0.015 * std::cos(angle), 0.015 * std::sin(angle), 0.004 + along);
}

TEST(SurfaceFrame, APlaneFrameProjects) {
  SurfaceFrame f;
  f.origin_w = Vec3(1, 2, 3);
  const FrameCoordinates c = CalcFrameCoordinates(f, Vec3(1.5, 1.75, 9));
  EXPECT_DOUBLE_EQ(c.x, 0.5);
  EXPECT_DOUBLE_EQ(c.y, -0.25);
  EXPECT_EQ(c.e1_w, f.e1_w);
  EXPECT_EQ(c.e2_w, f.e2_w);
}

TEST(SurfaceFrame, ACylinderIsUnrolledArcLengthRoundItLengthAlongIt) {
  const SurfaceFrame f = Handle();
  for (double angle : {-2.5, -1.2, 0.0, 0.3, 1.0, 1.5, 3.0}) {
    const FrameCoordinates c = CalcFrameCoordinates(f, OnHandle(f, angle, -0.002));
    EXPECT_NEAR(c.x, 0.015 * angle, 1e-15) << angle;  // a projection gives 0.015 sin(angle)
    EXPECT_NEAR(c.y, -0.002, 1e-15) << angle;
    // the frame rolled with the point: e1 round the handle there, e2 along it, both tangent
    EXPECT_NEAR((c.e1_w - Vec3(-std::sin(angle), std::cos(angle), 0)).norm(), 0.0, 1e-15);
    EXPECT_NEAR((c.e2_w - Vec3::UnitZ()).norm(), 0.0, 1e-15);
  }
  // off the surface (a proxy a little inside): the coordinates of the point above it
  const Vec3 axis_point = f.axis_point_w + Vec3(0, 0, 0.004);
  const Vec3 inside = axis_point + 0.9 * (OnHandle(f, 0.7, 0.0) - axis_point);
  EXPECT_NEAR(CalcFrameCoordinates(f, inside).x, 0.015 * 0.7, 1e-15);
}

TEST(SurfaceFrame, ATurnedFrameOnACylinderTurnsItsCoordinatesAlike) {
  // a pattern angle of 30 degrees: (x, y) are the unrolled (s, t) turned by it
  const double turn = kPi / 6;
  const SurfaceFrame f = Handle(turn);
  const double s = 0.015 * 2.0, t = 0.003;
  const FrameCoordinates c = CalcFrameCoordinates(f, OnHandle(f, 2.0, t));
  EXPECT_NEAR(c.x, s * std::cos(turn) + t * std::sin(turn), 1e-15);
  EXPECT_NEAR(c.y, -s * std::sin(turn) + t * std::cos(turn), 1e-15);
  EXPECT_NEAR(c.e1_w.norm(), 1.0, 1e-15);
  EXPECT_NEAR(c.e1_w.dot(c.e2_w), 0.0, 1e-15);
  EXPECT_NEAR(c.e1_w.dot(Vec3(std::cos(2.0), std::sin(2.0), 0)), 0.0, 1e-15);  // tangent there
}

TEST(SurfaceFrame, ProblemsAreSaid) {
  EXPECT_EQ(std::string(DescribeFrameProblem(Handle())), "");
  EXPECT_EQ(std::string(DescribeFrameProblem(SurfaceFrame{})), "");
  SurfaceFrame tilted = Handle();
  tilted.axis_w = Vec3(1, 0, 1).normalized();
  EXPECT_EQ(std::string(DescribeFrameProblem(tilted)),
            "cylinder axis must lie in the frame's tangent plane");
  SurfaceFrame off = Handle();
  off.radius_m = 0.016;
  EXPECT_EQ(std::string(DescribeFrameProblem(off)),
            "origin must lie on the cylinder (radius from the axis)");
  SurfaceFrame negative = Handle();
  negative.radius_m = -0.015;
  EXPECT_EQ(std::string(DescribeFrameProblem(negative)), "cylinder radius must be > 0");
  SurfaceFrame skew = Handle();
  skew.e2_w = Vec3(1, 1, 0).normalized();
  EXPECT_EQ(std::string(DescribeFrameProblem(skew)), "e1 and e2 must be orthogonal");
}

}  // namespace
}  // namespace hapticad
