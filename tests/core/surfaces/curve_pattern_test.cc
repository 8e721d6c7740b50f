// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/surfaces/curve_pattern.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

constexpr double kPi = 3.14159265358979323846;
const PatternPlane kPlane{Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()};

// A wavy stroke climbing in y: x = 5 mm sin(2 pi y / 40 mm), y in 0..40 mm, as a
// cubic B-spline through many samples (control points on the curve are close enough
// for a smooth, y-monotone test curve).
NurbsCurve2 Wave() {
  std::vector<Vec2> poles;
  for (int i = 0; i <= 40; ++i) {
    const double y = 1e-3 * i;
    poles.emplace_back(5e-3 * std::sin(2 * kPi * y / 0.04), y);
  }
  std::vector<double> knots(4, 0.0);
  for (int i = 1; i < 38; ++i) knots.push_back(i / 38.0);
  knots.insert(knots.end(), 4, 1.0);
  return NurbsCurve2(3, knots, poles, {});
}

TEST(CurvePattern, AStraightSlantedLineHasOneAngleEverywhere) {
  const NurbsCurve2 line(1, {0, 0, 1, 1}, {Vec2(0, 0), Vec2(0.01, 0.01)}, {});
  const auto p = CurvePattern::Build(kPlane, line, 16, CurvePattern::Evaluation::kLookupTable);
  for (double y : {-0.01, 0.0, 0.003, 0.01, 0.05}) {
    EXPECT_NEAR(p.LookupAngle(y), kPi / 4, 1e-12);
    EXPECT_NEAR(p.ExactAngle(y), kPi / 4, 1e-12);
  }
  const StripeFrame f = p.Evaluate(Vec3(0.5, 0.004, 0), Vec3::UnitZ());
  EXPECT_NEAR((f.stripe - Vec3(1, 1, 0).normalized()).norm(), 0, 1e-12);
  // the family member through (0.5, 0.004) is the line shifted by 0.5 - 0.004
  EXPECT_NEAR(p.MemberOffset(Vec3(0.5, 0.004, 0)), 0.496, 1e-12);
}

TEST(CurvePattern, TheExactEvaluationFollowsTheCurvesTangent) {
  const NurbsCurve2 wave = Wave();
  const auto p = CurvePattern::Build(kPlane, wave, 8, CurvePattern::Evaluation::kExact);
  for (double t = 0.05; t < 1.0; t += 0.1) {
    Vec2 q, d;
    wave.Evaluate(t, &q, &d);
    EXPECT_NEAR(p.ExactAngle(q.y()), std::atan2(d.y(), d.x()), 1e-10) << t;
  }
}

TEST(CurvePattern, TheLookupTableConvergesToTheExactAngle) {
  double previous = kPi;
  for (int size : {8, 32, 128, 512}) {
    const auto p =
        CurvePattern::Build(kPlane, Wave(), size, CurvePattern::Evaluation::kLookupTable);
    double worst = 0.0;
    for (int i = 0; i <= 997; ++i) {
      const double y = 0.04 * i / 997.0;
      worst = std::max(worst, std::abs(p.LookupAngle(y) - p.ExactAngle(y)));
    }
    EXPECT_LT(worst, previous / 3.0) << size;  // at least a factor 3 per 4x entries
    previous = worst;
  }
  EXPECT_LT(previous, 1e-4);
}

TEST(CurvePattern, ADegenerateCurveIsRejectedClearly) {
  const NurbsCurve2 flat(1, {0, 0, 1, 1}, {Vec2(0, 0.01), Vec2(0.02, 0.01)}, {});
  try {
    CurvePattern::Build(kPlane, flat, 16, CurvePattern::Evaluation::kLookupTable);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("degenerate"), std::string::npos) << e.what();
  }
  const NurbsCurve2 point(1, {0, 0, 1, 1}, {Vec2(0.01, 0.01), Vec2(0.01, 0.01)}, {});
  EXPECT_THROW(CurvePattern::Build(kPlane, point, 16, CurvePattern::Evaluation::kExact),
               std::invalid_argument);
}

TEST(CurvePattern, ACurveThatTurnsBackOrTouchesItselfIsRejectedClearly) {
  // a hook: up, then back down past where it started (self-touching in y)
  const NurbsCurve2 hook(2, {0, 0, 0, 0.5, 1, 1, 1},
                         {Vec2(0, 0), Vec2(0.01, 0.03), Vec2(0.02, 0.0), Vec2(0.03, -0.01)}, {});
  try {
    CurvePattern::Build(kPlane, hook, 16, CurvePattern::Evaluation::kLookupTable);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("turns back or touches itself"), std::string::npos)
        << e.what();
  }
  // a closed loop
  const NurbsCurve2 loop(2, {0, 0, 0, 0.5, 1, 1, 1},
                         {Vec2(0, 0), Vec2(0.02, 0.02), Vec2(-0.02, 0.02), Vec2(0, 0)}, {});
  EXPECT_THROW(CurvePattern::Build(kPlane, loop, 16, CurvePattern::Evaluation::kExact),
               std::invalid_argument);
}

TEST(CurvePattern, BeyondItsEndsTheEndTangentsContinue) {
  const auto p = CurvePattern::Build(kPlane, Wave(), 64, CurvePattern::Evaluation::kExact);
  EXPECT_NEAR(p.ExactAngle(-1.0), p.ExactAngle(0.0), 1e-12);
  EXPECT_NEAR(p.LookupAngle(1.0), p.LookupAngle(0.04), 1e-12);
}

// The grating's bars are the family's members: along the stripe direction the member
// offset does not change, inside the curve's height range and beyond its ends, where the
// members continue straight along the end tangents as the stripes do.
TEST(CurvePattern, BeyondItsEndsTheGratingsBarsFollowTheStripes) {
  const NurbsCurve2 line(1, {0, 0, 1, 1}, {Vec2(0, 0), Vec2(0.005, 0.01)}, {});
  const auto straight = CurvePattern::Build(kPlane, line, 16, CurvePattern::Evaluation::kExact);
  for (double y : {-0.02, 0.0, 0.004, 0.01, 0.03}) {  // the member through (x, y): x - y / 2
    EXPECT_NEAR(straight.MemberOffset(Vec3(0.1, y, 0)), 0.1 - 0.5 * y, 1e-12) << y;
  }
  for (auto evaluation :
       {CurvePattern::Evaluation::kExact, CurvePattern::Evaluation::kLookupTable}) {
    const auto p = CurvePattern::Build(kPlane, Wave(), 512, evaluation);
    for (double y : {-0.03, -0.005, 0.001, 0.02, 0.039, 0.045, 0.07}) {
      const Vec3 point(0.013, y, 0);
      const Vec3 stripe = p.Evaluate(point, Vec3::UnitZ()).stripe;
      const double h = 1e-6;  // central difference along the stripe
      const double slope =
          (p.MemberOffset(point + h * stripe) - p.MemberOffset(point - h * stripe)) / (2 * h);
      EXPECT_NEAR(slope, 0.0, 1e-4) << y;
    }
  }
}

TEST(CurvePattern, NonFinitePointsGiveAnIsotropicFrame) {
  const auto p = CurvePattern::Build(kPlane, Wave(), 64, CurvePattern::Evaluation::kExact);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const StripeFrame f = p.Evaluate(Vec3(0, nan, 0), Vec3::UnitZ());
  EXPECT_EQ(f.weight, 0.0);
  EXPECT_TRUE(f.stripe.allFinite());
  EXPECT_EQ(p.MemberOffset(Vec3(std::numeric_limits<double>::infinity(), 0, 0)), 0.0);
}

}  // namespace
}  // namespace hapticad
