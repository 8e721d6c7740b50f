// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/simulated_device.h"

#include <stdexcept>

#include <gtest/gtest.h>

#include "scripted_paths.h"

namespace hapticad {
namespace {

TEST(SimulatedDevice, InterpolatesPositionWithExactSegmentVelocity) {
  SimulatedDevice d(testing::ThreeWaypointPath(), DeviceLimits{});
  DeviceState s;
  ASSERT_EQ(d.ReadState(0.25, &s), ReadStatus::kOk);
  EXPECT_NEAR((s.position_d - Vec3(0.025, 0, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((s.velocity_d - Vec3(0.1, 0, 0)).norm(), 0, 1e-15);
  ASSERT_EQ(d.ReadState(2.0, &s), ReadStatus::kOk);
  EXPECT_NEAR((s.position_d - Vec3(0.1, 0.1, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((s.velocity_d - Vec3(0, 0.1, 0)).norm(), 0, 1e-15);
  EXPECT_EQ(s.time_s, 2.0);
}

TEST(SimulatedDevice, RestsBeforeTheStartAndAfterTheEnd) {
  SimulatedDevice d(testing::ThreeWaypointPath(), DeviceLimits{});
  DeviceState s;
  d.ReadState(5.0, &s);
  EXPECT_EQ(s.position_d, Vec3(0.1, 0.2, 0));
  EXPECT_EQ(s.velocity_d, Vec3::Zero());
  d.ReadState(-1.0, &s);  // a rewound clock restarts the path
  EXPECT_EQ(s.position_d, Vec3::Zero());
  d.ReadState(0.5, &s);
  EXPECT_NEAR(s.position_d.x(), 0.05, 1e-15);
}

TEST(SimulatedDevice, RecordsTheLastForce) {
  SimulatedDevice d(testing::ThreeWaypointPath(), DeviceLimits{});
  d.WriteForce(Vec3(1, 2, 3));
  EXPECT_EQ(d.last_force_d(), Vec3(1, 2, 3));
  EXPECT_EQ(d.info().kind, "sim");
}

TEST(SimulatedDevice, ItsWorkspaceHoldsTheWholePath) {
  ScriptedPath p = testing::ThreeWaypointPath();
  p.positions[2] = Vec3(0.3, -0.2, 0);  // beyond the default +-0.08 m box
  SimulatedDevice d(p, DeviceLimits{});
  EXPECT_EQ(d.info().limits.workspace_max_d, Vec3(0.3, 0.08, 0.08));
  EXPECT_EQ(d.info().limits.workspace_min_d, Vec3(-0.08, -0.2, -0.08));
}

TEST(SimulatedDevice, RefusesAnInvalidPath) {  // what is invalid: scripted_path_test.cc
  EXPECT_THROW(SimulatedDevice(ScriptedPath{}, DeviceLimits{}), std::invalid_argument);
  ScriptedPath back = testing::ThreeWaypointPath();
  back.times_s[2] = 0.5;
  EXPECT_THROW(SimulatedDevice(back, DeviceLimits{}), std::invalid_argument);
}

}  // namespace
}  // namespace hapticad
