// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/velocity_filter.h"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

TEST(VelocityFilter, ConvergesToAConstantVelocityWhateverTheTimeSteps) {
  VelocityFilter f(40.0);
  const Vec3 v(0.1, -0.05, 0.02);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> step(0.5e-3, 2e-3);  // jittery report times
  double t = 0.0;
  for (int i = 0; i < 400; ++i) {
    ASSERT_TRUE(f.Update(t, v * t));
    t += step(rng);
  }
  EXPECT_NEAR((f.velocity() - v).norm(), 0.0, 1e-9);
}

TEST(VelocityFilter, RejectsTimeThatDoesNotMoveForwardAndNonFiniteInput) {
  VelocityFilter f;
  EXPECT_TRUE(f.Update(1.0, Vec3::Zero()));
  EXPECT_FALSE(f.Update(1.0, Vec3(1, 0, 0)));  // a duplicate report
  EXPECT_FALSE(f.Update(0.5, Vec3(1, 0, 0)));  // time went back
  EXPECT_FALSE(f.Update(2.0, Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0)));
  EXPECT_EQ(f.velocity(), Vec3::Zero());
  EXPECT_THROW(VelocityFilter(0.0), std::invalid_argument);
}

TEST(VelocityFilter, QuietensEncoderQuantisation) {
  // 20 mm/s read through a 0.055 mm encoder at 1 kHz: raw differences jump between 0
  // and 55 mm/s; the filter holds the speed to within a few mm/s
  VelocityFilter f(40.0);
  const double step = 0.055e-3;
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const double t = i * 1e-3;
    f.Update(t, Vec3(std::round(0.02 * t / step) * step, 0, 0));
    if (t > 0.1) worst = std::max(worst, std::abs(f.velocity().x() - 0.02));
  }
  EXPECT_LT(worst, 0.006);
  EXPECT_GT(worst, 0.0);
}

}  // namespace
}  // namespace hapticad
