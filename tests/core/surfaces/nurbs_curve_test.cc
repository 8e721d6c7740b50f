// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/surfaces/nurbs_curve.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

TEST(NurbsCurve2, ALineIsExact) {
  const NurbsCurve2 line(1, {0, 0, 2, 2}, {Vec2(1, 1), Vec2(5, 3)}, {});
  Vec2 p, d;
  line.Evaluate(0.5, &p, &d);
  EXPECT_NEAR((p - Vec2(2, 1.5)).norm(), 0, 1e-15);
  EXPECT_NEAR((d - Vec2(2, 1)).norm(), 0, 1e-15);
}

TEST(NurbsCurve2, ARationalQuarterCircleIsExact) {
  // quadratic, weights 1, sqrt(2)/2, 1: the unit quarter circle
  const double w = std::sqrt(0.5);
  const NurbsCurve2 arc(2, {0, 0, 0, 1, 1, 1}, {Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}, {1, w, 1});
  for (double t : {0.0, 0.1, 0.37, 0.5, 0.9, 1.0}) {
    Vec2 p, d;
    arc.Evaluate(t, &p, &d);
    EXPECT_NEAR(p.norm(), 1.0, 1e-14) << t;
    EXPECT_NEAR(p.dot(d), 0.0, 1e-13) << t;  // tangent orthogonal to the radius
    // derivative against a central difference
    Vec2 a, b, unused;
    const double h = 1e-6;
    arc.Evaluate(std::min(t + h, 1.0), &a, &unused);
    arc.Evaluate(std::max(t - h, 0.0), &b, &unused);
    const double span = std::min(t + h, 1.0) - std::max(t - h, 0.0);
    EXPECT_NEAR(((a - b) / span - d).norm(), 0.0, 1e-5) << t;
  }
}

TEST(NurbsCurve2, ACubicWithInteriorKnotsMatchesFiniteDifferences) {
  const NurbsCurve2 c(3, {0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1},
                      {Vec2(0, 0), Vec2(1, 2), Vec2(2, -1), Vec2(3, 3), Vec2(4, 0), Vec2(5, 1)},
                      {});
  for (double t = 0.01; t < 1.0; t += 0.07) {
    Vec2 p, d, a, b, unused;
    c.Evaluate(t, &p, &d);
    c.Evaluate(t + 1e-7, &a, &unused);
    c.Evaluate(t - 1e-7, &b, &unused);
    EXPECT_NEAR(((a - b) / 2e-7 - d).norm(), 0.0, 1e-6) << t;
  }
}

TEST(NurbsCurve2, RejectsBadDefinitions) {
  EXPECT_THROW(NurbsCurve2(0, {0, 1}, {Vec2(0, 0)}, {}), std::invalid_argument);
  EXPECT_THROW(NurbsCurve2(1, {0, 0, 1}, {Vec2(0, 0), Vec2(1, 1)}, {}), std::invalid_argument);
  EXPECT_THROW(NurbsCurve2(1, {0, 1, 0, 1}, {Vec2(0, 0), Vec2(1, 1)}, {}), std::invalid_argument);
  EXPECT_THROW(NurbsCurve2(1, {0, 0, 1, 1}, {Vec2(0, 0), Vec2(1, 1)}, {1, 0}),
               std::invalid_argument);
  EXPECT_THROW(NurbsCurve2(1, {0, 0, 1, 1}, {Vec2(0, NAN), Vec2(1, 1)}, {}), std::invalid_argument);
  EXPECT_THROW(NurbsCurve2(1, {0, 0, 0, 0}, {Vec2(0, 0), Vec2(1, 1)}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace hapticad
