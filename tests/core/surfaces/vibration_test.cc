// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/surfaces/vibration.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

TEST(Vibration, IsASineAlongItsAxis) {
  const Vibration v{120.0, 0.5, Vec3::UnitY(), true};
  EXPECT_NEAR(CalcVibrationForce(v, 0.0).norm(), 0.0, 1e-15);
  EXPECT_NEAR(CalcVibrationForce(v, 1.0 / 480.0).y(), 0.5, 1e-12);  // quarter period
  EXPECT_NEAR(CalcVibrationForce(v, 3.0 / 480.0).y(), -0.5, 1e-12);
  EXPECT_NEAR(CalcVibrationForce(v, 1.0 / 480.0).x(), 0.0, 1e-15);
  // an hour in, the phase is still exact
  EXPECT_NEAR(CalcVibrationForce(v, 3600.0 + 1.0 / 480.0).y(), 0.5, 1e-9);
}

TEST(Vibration, UnpoweredOrBadTimeIsSilent) {
  Vibration v{100.0, 0.5, Vec3::UnitZ(), false};
  EXPECT_EQ(CalcVibrationForce(v, 0.0025), Vec3::Zero());
  v.powered = true;
  EXPECT_EQ(CalcVibrationForce(v, std::numeric_limits<double>::quiet_NaN()), Vec3::Zero());
  EXPECT_EQ(CalcVibrationForce(v, std::numeric_limits<double>::infinity()), Vec3::Zero());
}

}  // namespace
}  // namespace hapticad
