// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/workspace_mapping.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "hapticad/devices/servo_loop.h"
#include "hapticad/devices/simulated_device.h"
#include "test_meshes.h"

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
  limits.max_damping_n_s_per_m = 0.8;
  WorkspaceMapping m;
  m.scale = 2.0;
  const RenderLimits r = RenderLimitsFor(limits, m);
  EXPECT_EQ(r.max_force_n, 3.3);
  // the limits are the handle's, as the device states them, and the renderer divides by
  // the scale in the world: a world spring of 200 N/m felt through a scale of 2 is
  // 400 N/m at the handle
  EXPECT_EQ(r.max_stiffness_n_per_m, 400.0);
  EXPECT_EQ(r.max_damping_n_s_per_m, 0.8);
  EXPECT_EQ(r.workspace_scale, 2.0);
  EXPECT_EQ(r.max_stiffness_n_per_m / r.workspace_scale, 200.0);
  // a device that states no damping limit gets the renderer's default, felt as well
  limits.max_damping_n_s_per_m = 0.0;
  EXPECT_EQ(RenderLimitsFor(limits, m).max_damping_n_s_per_m, RenderLimits{}.max_damping_n_s_per_m);
}

// A 100 mm box, its top at z = 50 mm, pressed by a scripted handle through the servo
// loop, the workspace scaled `scale` times into the world around the top's centre. The
// mean normal force while the handle holds `handle_depth_m` below the top.
double HeldForceThroughTheLoop(const SurfaceProperties& top, double scale, double handle_depth_m,
                               std::uint32_t* flags) {
  DeviceLimits limits = SimulatedProbeLimits();  // 8.9 N, 3 N/mm
  ScriptedPath path;  // device frame: from 10 mm above down to the depth, then held
  path.times_s = {0.0, 0.1, 0.4, 1.0};
  path.positions = {Vec3(0, 0, 0.01), Vec3(0, 0, 0.01), Vec3(0, 0, -handle_depth_m),
                    Vec3(0, 0, -handle_depth_m)};
  SimulatedDevice device(path, limits);
  std::vector<SurfaceProperties> faces(6, kUntaggedSurface);
  faces[5] = top;
  WorkspaceMapping mapping;
  mapping.scale = scale;
  mapping.offset_w = Vec3(0, 0, 0.05);  // the handle's origin on the top
  auto renderer = std::make_shared<ForceRenderer>(
      HapticScene::Build(testing::MakeBoxSoup(Vec3(-50, -50, -50), Vec3(50, 50, 50)), 1e-3),
      std::make_shared<SurfaceTable>(faces), RenderLimitsFor(limits, mapping));
  ServoConfig config;
  config.trace_capacity = 2048;
  ServoLoop loop(device, renderer, config);
  loop.SetMapping(mapping);
  loop.BeginTicks();
  std::vector<TraceSample> trace;
  for (int i = 0; i <= 1000; ++i) loop.Tick(i * 1e-3, 1e-3);
  loop.DrainTrace(&trace);
  double sum = 0.0;
  int held = 0;
  *flags = 0;
  for (const TraceSample& s : trace) {
    if (s.time_s < 0.6) continue;  // down at 0.4 s; any ramp after the mapping long over
    sum += s.normal_force_n;
    ++held;
    *flags |= s.flags;
  }
  return held > 0 ? sum / held : -1.0;
}

TEST(WorkspaceMapping, AFaceIsFeltAtItsStiffnessAtTheHandleWhateverTheScale) {
  // seed 000's toothbrush neck (0.556 N/mm) as a face's stiffness, and as a study's
  // force-travel law; a button's operating force at its pretravel; a face stiffer than
  // the device, felt at the device's 3 N/mm. The proxy rests 1e-9 of the part's size off
  // the face: 1.7e-10 m, under 1e-6 N at 3 N/mm, so 1e-6 N is the tolerance.
  SurfaceProperties spring = kUntaggedSurface;
  spring.stiffness_n_per_m = 556.0;
  SurfaceProperties law = kUntaggedSurface;
  law.force_travel = MakeLinearForceTravel(556.0);
  SurfaceProperties button = kUntaggedSurface;
  button.force_travel = MakePushButton({});  // 1.47 N at 0.25 mm, 5.9 N/mm: stretched 2.45x
  const double button_travel_m = 0.25e-3 * button.force_travel->StretchSlope() / 3000.0;
  SurfaceProperties stiff = kUntaggedSurface;
  stiff.stiffness_n_per_m = 5000.0;
  const struct {
    const char* what;
    const SurfaceProperties& top;
    double handle_depth_m, force_n;
    bool clamped;
  } cases[] = {{"spring", spring, 1e-3, 0.556, false},
               {"law", law, 1e-3, 0.556, false},
               {"button", button, button_travel_m, 1.47, true},
               {"stiffer than the device", stiff, 1e-3, 3.0, true}};
  for (const double scale : {1.0, 1.8}) {  // 1.8: a 180 mm toothbrush fitted into 100 mm
    for (const auto& c : cases) {
      std::uint32_t flags = 0;
      const double force = HeldForceThroughTheLoop(c.top, scale, c.handle_depth_m, &flags);
      EXPECT_NEAR(force, c.force_n, 1e-6) << c.what << " at scale " << scale;
      EXPECT_EQ((flags & kStiffnessClamped) != 0, c.clamped) << c.what << " at scale " << scale;
    }
  }
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
