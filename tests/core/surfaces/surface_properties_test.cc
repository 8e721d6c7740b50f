// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/surfaces/surface_properties.h"

#include <limits>
#include <stdexcept>
#include <string>

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
