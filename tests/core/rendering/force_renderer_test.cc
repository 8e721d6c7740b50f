// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/rendering/force_renderer.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "alloc_counter.h"
#include "test_meshes.h"

namespace hapticad {
namespace {

// A 100 mm box in mm; the top (+z, CAD face 5) is rubber-like, the rest untagged.
class RendererOnBox : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = HapticScene::Build(testing::MakeBoxSoup(Vec3(-50, -50, -50), Vec3(50, 50, 50)), 1e-3);
    std::vector<SurfaceProperties> faces(6, kUntaggedSurface);
    faces[5].friction.static_coefficient = 1.2;
    faces[5].friction.dynamic_coefficient = 1.0;
    faces[5].stiffness_n_per_m = 300.0;
    surfaces_ = std::make_shared<SurfaceTable>(faces);
    limits_.max_force_n = 8.0;
    limits_.max_stiffness_n_per_m = 3000.0;
  }
  RenderOutput Press(ForceRenderer& r, double depth_m, const Vec3& velocity = Vec3::Zero()) {
    RenderOutput out;
    r.Render({Vec3(0, 0, 0.06), Vec3::Zero()}, &out);
    r.Render({Vec3(0, 0, 0.05 - depth_m), velocity}, &out);
    return out;
  }
  std::shared_ptr<const HapticScene> scene_;
  std::shared_ptr<SurfaceTable> surfaces_;
  RenderLimits limits_;
};

TEST_F(RendererOnBox, NormalForceIsStiffnessTimesDepth) {
  ForceRenderer r(scene_, surfaces_, limits_);
  const RenderOutput out = Press(r, 0.002);
  EXPECT_TRUE(out.flags & kContact);
  EXPECT_EQ(out.cad_face, 5);
  EXPECT_NEAR(out.force_w.z(), 300.0 * 0.002, 1e-6);
  EXPECT_NEAR(out.normal_force_n, 0.6, 1e-6);
  EXPECT_NEAR(out.tangential_force_n, 0.0, 1e-12);
}

TEST_F(RendererOnBox, SlidingFrictionIsMuDynamicTimesNormal) {
  ForceRenderer r(scene_, surfaces_, limits_);
  const RenderOutput out = Press(r, 0.002, Vec3(0.05, 0.0, 0.0));
  EXPECT_NEAR(out.tangential_force_n / out.normal_force_n, 1.0, 1e-9);
  EXPECT_LT(out.force_w.x(), 0.0);  // opposes the motion
}

TEST_F(RendererOnBox, UsesEachFacesOwnProperties) {
  ForceRenderer r(scene_, surfaces_, limits_);
  RenderOutput out;
  r.Render({Vec3(0.06, 0, 0), Vec3::Zero()}, &out);
  r.Render({Vec3(0.049, 0, 0), Vec3(0, 0.05, 0)}, &out);
  EXPECT_EQ(out.cad_face, 1);
  EXPECT_NEAR(out.normal_force_n, 400.0 * 0.001, 1e-6);  // untagged: 0.4 N/mm
  EXPECT_NEAR(out.tangential_force_n / out.normal_force_n, 0.4, 1e-9);
}

TEST_F(RendererOnBox, ClampsForceToTheDeviceMaximum) {
  limits_.max_force_n = 1.0;
  ForceRenderer r(scene_, surfaces_, limits_);
  const RenderOutput out =
      Press(r, 0.010, Vec3(0.05, 0.0, 0.0));  // 3 N normal + 3 N friction asked
  EXPECT_TRUE(out.flags & kForceClamped);
  EXPECT_NEAR(out.force_w.norm(), 1.0, 1e-12);
  EXPECT_NEAR(out.tangential_force_n / out.normal_force_n, 1.0, 1e-9);  // direction kept
}

TEST_F(RendererOnBox, ClampsStiffnessToTheDeviceMaximum) {
  limits_.max_stiffness_n_per_m = 100.0;
  ForceRenderer r(scene_, surfaces_, limits_);
  const RenderOutput out = Press(r, 0.002);
  EXPECT_TRUE(out.flags & kStiffnessClamped);
  EXPECT_NEAR(out.normal_force_n, 0.2, 1e-6);
}

TEST_F(RendererOnBox, NonFiniteInputGivesZeroForceAndAFault) {
  ForceRenderer r(scene_, surfaces_, limits_);
  Press(r, 0.002);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  RenderOutput out;
  r.Render({Vec3(0, nan, 0.04), Vec3::Zero()}, &out);
  EXPECT_EQ(out.force_w, Vec3::Zero());
  EXPECT_TRUE(out.flags & kInputFault);
  r.Render({Vec3(0, 0, 0.048), Vec3(std::numeric_limits<double>::infinity(), 0, 0)}, &out);
  EXPECT_EQ(out.force_w, Vec3::Zero());
  // the proxy was not disturbed: the next good sample is felt normally
  r.Render({Vec3(0, 0, 0.048), Vec3::Zero()}, &out);
  EXPECT_NEAR(out.normal_force_n, 0.6, 1e-6);
}

TEST_F(RendererOnBox, RenderDoesNotAllocate) {
  ForceRenderer r(scene_, surfaces_, limits_);
  Press(r, 0.002);
  RenderOutput out;
  testing::AllocationCounter counter;
  for (int i = 0; i < 1000; ++i) {
    r.Render({Vec3(-0.04 + 8e-5 * i, 0.01, 0.048), Vec3(0.08, 0, 0)}, &out);
  }
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_TRUE(out.flags & kContact);
}

}  // namespace
}  // namespace hapticad
