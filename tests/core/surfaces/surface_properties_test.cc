// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/surfaces/surface_properties.h"

#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

TEST(SurfaceTable, UntaggedFacesGetTheDocumentedDefault) {
  SurfaceProperties rubber;
  rubber.friction.static_coefficient = 1.2;
  rubber.friction.dynamic_coefficient = 1.0;
  const SurfaceTable table({kUntaggedSurface, rubber});
  EXPECT_EQ(table.surface(1).friction.dynamic_coefficient, 1.0);
  EXPECT_EQ(table.surface(0).friction.static_coefficient, 0.5);
  EXPECT_EQ(table.surface(7).friction.dynamic_coefficient, 0.4);
  EXPECT_EQ(table.surface(-1).stiffness_n_per_m, 400.0);
}

TEST(SurfaceTable, RejectsBadValuesNamingFaceAndField) {
  SurfaceProperties bad;
  bad.friction.dynamic_coefficient = -0.1;
  try {
    SurfaceTable table({kUntaggedSurface, bad});
    FAIL() << "accepted a negative friction coefficient";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("CAD face 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("dynamic friction"), std::string::npos) << e.what();
  }
  SurfaceProperties nan_stiffness;
  nan_stiffness.stiffness_n_per_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(SurfaceTable({nan_stiffness}), std::invalid_argument);
  SurfaceProperties zero_eps;
  zero_eps.friction.stick_speed_mps = 0.0;
  EXPECT_THROW(SurfaceTable({zero_eps}), std::invalid_argument);
}

}  // namespace
}  // namespace hapticad

namespace hapticad {
namespace {

TEST(SurfaceTable, CompilesEachFaceIntoTheEffectsItUses) {
  SurfaceProperties plain;
  SurfaceProperties patterned;
  patterned.pattern = LinearPattern{Vec3::UnitX()};
  SurfaceProperties rough;
  rough.roughness = MakeRoughnessGrid(4, SurfaceFrame{});
  SurfaceProperties textured;
  textured.texture = ViscousGrating{PaperPreset(0, 2), SurfaceFrame{}};
  SurfaceProperties shaking;
  shaking.vibration = 0;
  SurfaceProperties sticky;
  sticky.friction_mode = FrictionMode::kCone;
  const SurfaceTable table({plain, patterned, rough, textured, shaking, sticky},
                           {Vibration{100.0, 0.3, Vec3::UnitZ(), true}});
  EXPECT_EQ(table.effects(0), 0u);
  EXPECT_EQ(table.effects(1), kEffectPattern);
  EXPECT_EQ(table.effects(2), kEffectRoughness);
  EXPECT_EQ(table.effects(3), kEffectTexture);
  EXPECT_EQ(table.effects(4), kEffectVibration);
  EXPECT_EQ(table.effects(5), kEffectCone);
  EXPECT_EQ(table.effects(99), 0u);
}

TEST(SurfaceTable, RejectsBadEffectsWithTheirName) {
  auto message = [](const SurfaceProperties& s, std::vector<Vibration> v = {}) {
    try {
      SurfaceTable table({s}, std::move(v));
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  SurfaceProperties linear;
  linear.pattern = LinearPattern{Vec3(0, 0, 0)};
  EXPECT_NE(message(linear).find("linear pattern direction"), std::string::npos);
  SurfaceProperties circular;
  circular.pattern = CircularPattern{Vec3::Zero(), Vec3::UnitZ(), 0.0};
  EXPECT_NE(message(circular).find("blend radius"), std::string::npos);
  SurfaceProperties rough;
  rough.roughness = MakeRoughnessGrid(2, SurfaceFrame{});
  rough.roughness->spacing_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message(rough).find("roughness grid spacing"), std::string::npos);
  SurfaceProperties texture;
  texture.texture = ViscousGrating{PaperPreset(0, 0), SurfaceFrame{}};
  texture.texture->params.alpha_h = std::numeric_limits<double>::infinity();
  EXPECT_NE(message(texture).find("texture parameter"), std::string::npos);
  SurfaceProperties shaking;
  shaking.vibration = 2;
  EXPECT_NE(message(shaking).find("vibration index"), std::string::npos);
  EXPECT_NE(
      message(SurfaceProperties{}, {Vibration{-5.0, 0.3, Vec3::UnitZ(), true}}).find("vibration 0"),
      std::string::npos);
  SurfaceProperties across;
  across.anisotropy.across_factor = -1.0;
  EXPECT_NE(message(across).find("across friction factor"), std::string::npos);
}

}  // namespace
}  // namespace hapticad
