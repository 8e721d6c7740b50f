// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/clutch.h"

#include <gtest/gtest.h>

namespace hapticad {
namespace {

TEST(Clutch, WalksA190MillimetrePartWithA160MillimetreWorkspace) {
  // a device reaching x in [-80, 80] mm, unscaled, strokes a part from 0 to 190 mm by
  // indexing: stroke right, hold the clutch, come back left, release, stroke again
  WorkspaceMapping m;
  m.offset_w = Vec3(0.08, 0, 0);  // handle at -80 mm is the part's end at 0
  Clutch clutch;
  double reached = 0.0;
  double x_d = -0.08;
  for (int stroke = 0; stroke < 2; ++stroke) {
    for (; x_d <= 0.08 + 1e-12; x_d += 0.001) {  // stroke right
      clutch.Update(false, Vec3(x_d, 0, 0), &m);
      reached = std::max(reached, m.DeviceToWorld(Vec3(x_d, 0, 0)).x());
    }
    x_d = 0.08;
    const double tool = m.DeviceToWorld(Vec3(x_d, 0, 0)).x();
    EXPECT_EQ(clutch.Update(true, Vec3(x_d, 0, 0), &m), Clutch::Event::kEngaged);
    for (; x_d >= -0.08 - 1e-12; x_d -= 0.001) {  // back, tool frozen
      EXPECT_EQ(clutch.Update(true, Vec3(x_d, 0, 0), &m), Clutch::Event::kNone);
      EXPECT_EQ(clutch.frozen_tool_w().x(), tool);
    }
    x_d = -0.08;
    EXPECT_EQ(clutch.Update(false, Vec3(x_d, 0, 0), &m), Clutch::Event::kReleased);
    EXPECT_NEAR(m.DeviceToWorld(Vec3(x_d, 0, 0)).x(), tool, 1e-12);  // carries on from there
  }
  EXPECT_GE(reached, 0.19);
}

TEST(Clutch, KeepsTheToolStillThroughAScaledTurnedMapping) {
  WorkspaceMapping m;
  m.scale = 1.3;
  m.rotation_wd = Eigen::AngleAxisd(0.5, Vec3::UnitZ()).toRotationMatrix();
  Clutch clutch;
  const Vec3 a(0.01, 0.02, 0.0), b(-0.03, 0.01, 0.02);
  const Vec3 tool = m.DeviceToWorld(a);
  clutch.Update(true, a, &m);
  clutch.Update(false, b, &m);
  EXPECT_NEAR((m.DeviceToWorld(b) - tool).norm(), 0, 1e-15);
  EXPECT_FALSE(clutch.engaged());
}

}  // namespace
}  // namespace hapticad
