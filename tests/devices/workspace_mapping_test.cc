// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/workspace_mapping.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

namespace hapticad {
namespace {

WorkspaceMapping Turned() {
  WorkspaceMapping m;
  m.scale = 1.5;
  m.rotation_wd = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  m.offset_w = Vec3(0.1, -0.2, 0.3);
  return m;
}

TEST(WorkspaceMapping, MapsPositionsVelocitiesAndForcesConsistently) {
  const WorkspaceMapping m = Turned();
  ValidateWorkspaceMapping(m);
  const Vec3 p_d(0.01, 0.02, -0.03);
  EXPECT_NEAR((m.WorldToDevice(m.DeviceToWorld(p_d)) - p_d).norm(), 0, 1e-15);
  const Vec3 v_d(0.1, 0, 0.2);
  const double dt = 1e-3;
  EXPECT_NEAR(
      ((m.DeviceToWorld(p_d + v_d * dt) - m.DeviceToWorld(p_d)) / dt - m.VelocityToWorld(v_d))
          .norm(),
      0, 1e-12);
  // forces are not scaled, only turned: power f . v is the world's times the scale
  const Vec3 f_w(1, -2, 0.5);
  EXPECT_NEAR(m.ForceToDevice(f_w).norm(), f_w.norm(), 1e-12);
  EXPECT_NEAR(m.ForceToWorld(m.ForceToDevice(f_w)).dot(f_w), f_w.squaredNorm(), 1e-12);
  EXPECT_NEAR(m.ForceToDevice(f_w).dot(v_d) * m.scale, f_w.dot(m.VelocityToWorld(v_d)), 1e-12);
}

TEST(WorkspaceMapping, RenderLimitsKeepTheDeviceWithinItsStiffness) {
  DeviceLimits limits;
  limits.max_force_n = 3.3;
  limits.max_stiffness_n_per_m = 400.0;
  WorkspaceMapping m;
  m.scale = 2.0;
  const RenderLimits r = RenderLimitsFor(limits, m);
  EXPECT_EQ(r.max_force_n, 3.3);
  // a world spring of 200 N/m felt through a scale of 2 is 400 N/m at the handle
  EXPECT_EQ(r.max_stiffness_n_per_m, 200.0);
}

TEST(WorkspaceMapping, FitsA190MillimetrePartIntoA160MillimetreWorkspace) {
  DeviceLimits limits;
  limits.workspace_min_d = Vec3(-0.08, -0.06, -0.05);
  limits.workspace_max_d = Vec3(0.08, 0.06, 0.05);
  const Vec3 lo(0.0, -0.01, 0.0), hi(0.19, 0.01, 0.02);  // a toothbrush lying along x
  const WorkspaceMapping m = FitWorkspace(limits, lo, hi);
  EXPECT_NEAR(m.scale, 0.19 / 0.16, 1e-12);
  EXPECT_NEAR((m.DeviceToWorld(Vec3(-0.08, 0, 0)) - Vec3(0.0, 0.0, 0.01)).norm(), 0, 1e-12);
  EXPECT_NEAR((m.DeviceToWorld(Vec3(0.08, 0, 0)) - Vec3(0.19, 0.0, 0.01)).norm(), 0, 1e-12);
  // a small part is not magnified unless asked
  EXPECT_EQ(FitWorkspace(limits, Vec3::Zero(), Vec3::Constant(0.01)).scale, 1.0);
  EXPECT_NEAR(FitWorkspace(limits, Vec3::Zero(), Vec3::Constant(0.01), 0.1).scale, 0.1, 1e-15);
  EXPECT_THROW(FitWorkspace(limits, hi, lo), std::invalid_argument);
}

TEST(WorkspaceMapping, RejectsWhatIsNotAScaledRigidMotion) {
  WorkspaceMapping m;
  m.scale = 0.0;
  EXPECT_THROW(ValidateWorkspaceMapping(m), std::invalid_argument);
  m = WorkspaceMapping{};
  m.rotation_wd(2, 2) = -1.0;  // a mirror
  EXPECT_THROW(ValidateWorkspaceMapping(m), std::invalid_argument);
  m = WorkspaceMapping{};
  m.offset_w.x() = NAN;
  EXPECT_THROW(ValidateWorkspaceMapping(m), std::invalid_argument);
}

}  // namespace
}  // namespace hapticad
