// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/surfaces/force_travel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace hapticad {
namespace {

TEST(ForceTravelTest, ALinearLawIsStiffnessTimesTravelAndGoesOnPastItsPoint) {
  const ForceTravel law = MakeLinearForceTravel(560.0);
  EXPECT_DOUBLE_EQ(law.Force(0.0), 0.0);
  EXPECT_DOUBLE_EQ(law.Force(-1e-3), 0.0);
  EXPECT_NEAR(law.Force(0.5e-3), 0.28, 1e-12);
  EXPECT_NEAR(law.Force(4e-3), 2.24, 1e-12);  // past the last point: the same slope
  EXPECT_NEAR(law.MaxSlope(), 560.0, 1e-9);
}

TEST(ForceTravelTest, APushButtonRisesSnapsRisesAndBottomsOut) {
  PushButtonParams p;  // 1.47 N at 0.25 mm, snap 50 % over 0.1 mm, bottom at 0.6 mm
  const ForceTravel law = MakePushButton(p);
  EXPECT_NEAR(law.Force(0.125e-3), 0.735, 1e-12);
  EXPECT_NEAR(law.Force(0.25e-3), 1.47, 1e-12);   // the operating point
  EXPECT_NEAR(law.Force(0.35e-3), 0.735, 1e-12);  // after the snap
  EXPECT_NEAR(law.Force(0.6e-3), 1.47, 1e-12);    // bottomed out
  EXPECT_NEAR(law.Force(0.8e-3), 1.47 + p.bottom_stiffness_n_per_m * 0.2e-3, 1e-9);
  // the snap ratio as the field notes define it
  const double snap = (law.Force(0.25e-3) - law.Force(0.35e-3)) / law.Force(0.25e-3);
  EXPECT_NEAR(snap, 0.5, 1e-12);
  EXPECT_NEAR(law.StretchSlope(), 0.735 / 0.1e-3, 1e-6);  // the snap is the mechanism's steepest
  EXPECT_NEAR(law.MaxSlope(), p.bottom_stiffness_n_per_m, 1e-6);  // the housing, steeper still
}

TEST(ForceTravelTest,
     AButtonBottomsOutOnItsHousingAsStiffAsTheDeviceRendersWithoutStretchingTheClick) {
  // the housing (50 N/mm) is far stiffer than a device renders; the click (7.35 N/mm at
  // the snap) a little. The click is stretched for the snap alone, and the housing is
  // felt from where the stretched click ends at the device's stiffness. Before, the
  // housing set the stretch: the operating point at 4.2 mm of handle travel, not 0.6.
  const ForceTravel law = MakePushButton({});
  const double limit = 3000.0;            // the simulated probe's stable stiffness
  const double stretch = 7350.0 / limit;  // handle travel per law travel
  bool clamped = false;
  EXPECT_NEAR(law.ForceClamped(0.25e-3 * stretch, limit, &clamped), 1.47, 1e-9);
  EXPECT_TRUE(clamped);
  EXPECT_NEAR(law.ForceClamped(0.35e-3 * stretch, limit, nullptr), 0.735, 1e-9);
  const double bottom = 0.6e-3 * stretch;  // where the stretched click ends
  EXPECT_NEAR(law.ForceClamped(bottom, limit, nullptr), 1.47, 1e-9);
  for (double past : {1e-6, 0.1e-3, 0.5e-3}) {
    EXPECT_NEAR(law.ForceClamped(bottom + past, limit, nullptr), 1.47 + limit * past, 1e-9) << past;
  }
  // a device stiffer than the click renders the click as it is and the housing at its limit
  EXPECT_NEAR(law.ForceClamped(0.25e-3, 20000.0, nullptr), 1.47, 1e-12);
  EXPECT_NEAR(law.ForceClamped(0.7e-3, 20000.0, nullptr), 1.47 + 20000.0 * 0.1e-3, 1e-9);
  clamped = false;
  EXPECT_NEAR(law.ForceClamped(0.3e-3, 20000.0, &clamped), law.Force(0.3e-3), 1e-12);
  EXPECT_FALSE(clamped);  // the click itself is untouched
  // a housing softer than the device is felt as it is
  PushButtonParams soft;
  soft.bottom_stiffness_n_per_m = 1000.0;
  const ForceTravel mushy = MakePushButton(soft);
  EXPECT_NEAR(mushy.ForceClamped(0.6e-3 * stretch + 0.2e-3, limit, nullptr), 1.47 + 1000.0 * 0.2e-3,
              1e-9);
}

TEST(ForceTravelTest, ADeviceTooSoftForTheLawFeelsItsForcesOverALongerTravel) {
  const ForceTravel law = MakePushButton({});    // steepest: the snap, 7350 N/m
  for (double limit : {400.0, 700.0, 3000.0}) {  // Touch, Omni, the simulated probe
    const double stretch = law.StretchSlope() / limit;
    double previous = 0.0;
    double peak = 0.0;
    for (int i = 1; i <= 20000; ++i) {
      const double x = i * 1e-7 * stretch;
      bool clamped = false;
      const double f = law.ForceClamped(x, limit, &clamped);
      EXPECT_TRUE(clamped);
      EXPECT_LE(std::abs(f - previous), limit * 1e-7 * stretch + 1e-12) << x;
      EXPECT_GE(f, 0.0);
      if (x < 0.35e-3 * stretch) peak = std::max(peak, f);  // up to the snap's end
      previous = f;
    }
    // the operating force and the snap ratio are kept, at a longer travel
    EXPECT_NEAR(peak, 1.47, 1e-9) << limit;
    EXPECT_NEAR(law.ForceClamped(0.25e-3 * stretch, limit, nullptr), 1.47, 1e-9);
    EXPECT_NEAR(law.ForceClamped(0.35e-3 * stretch, limit, nullptr), 0.735, 1e-9);
  }
  // a button pressed 0.1-0.6 mm never loses its force on a soft device (summing
  // clamped slopes did: 0 N from 0.2 to 0.4 mm on a Touch)
  PushButtonParams quick;
  quick.pretravel_m = 0.1e-3;
  quick.snap_travel_m = 0.2e-3;
  const ForceTravel steep = MakePushButton(quick);
  for (int i = 1; i <= 100; ++i) {
    const double x = i * 1e-5;
    EXPECT_GT(steep.ForceClamped(x, 400.0, nullptr), 0.0) << x;
  }
  // a law the device renders is untouched
  bool untouched = false;
  EXPECT_NEAR(law.ForceClamped(0.1e-3, 10000.0, &untouched), law.Force(0.1e-3), 1e-12);
  EXPECT_FALSE(untouched);
}

TEST(ForceTravelTest, ACantileverMatchesTheFieldNotesToothbrush) {
  // PP (1.5 GPa), a 5 x 4 mm neck bent across its 4 mm: 0.56 N/mm over 60 mm, 1.9 over 40
  EXPECT_NEAR(CantileverStiffness(1.5e9, 5e-3, 4e-3, 60e-3), 555.6, 0.1);
  EXPECT_NEAR(CantileverStiffness(1.5e9, 5e-3, 4e-3, 40e-3), 1875.0, 0.1);
  // k goes with h^3 and 1/L^3
  EXPECT_NEAR(
      CantileverStiffness(1.5e9, 5e-3, 8e-3, 60e-3) / CantileverStiffness(1.5e9, 5e-3, 4e-3, 60e-3),
      8.0, 1e-12);
  EXPECT_NEAR(SeriesStiffness(400.0, 400.0), 200.0, 1e-12);
  EXPECT_THROW(CantileverStiffness(1.5e9, 0.0, 4e-3, 60e-3), std::invalid_argument);
}

TEST(ForceTravelTest, BadLawsAndButtonsAreRefusedWithAReason) {
  const auto message = [](const auto& make) {
    try {
      make();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  ForceTravel law = MakePushButton({});
  law.travel_m[2] = law.travel_m[1];
  EXPECT_NE(message([&] { ValidateForceTravel(law); }).find("point 3: travel must increase"),
            std::string::npos);
  law = MakePushButton({});
  law.force_n[1] = -0.1;
  EXPECT_NE(message([&] { ValidateForceTravel(law); }).find("point 2: force must be >= 0"),
            std::string::npos);
  law.points = 0;
  EXPECT_NE(message([&] { ValidateForceTravel(law); }).find("1 to 8 points"), std::string::npos);
  law = MakePushButton({});
  law.force_n[3] = law.force_n[2];  // gives way for good past the bottom
  EXPECT_NE(message([&] { ValidateForceTravel(law); }).find("the last segment must rise"),
            std::string::npos);
  law = MakeLinearForceTravel(500.0);
  law.ends_on_stop = true;
  EXPECT_NE(message([&] { ValidateForceTravel(law); }).find("a stop needs a point before it"),
            std::string::npos);
  PushButtonParams p;
  p.snap_ratio = 1.0;
  EXPECT_NE(message([&] { MakePushButton(p); }).find("snap ratio"), std::string::npos);
  p = {};
  p.total_travel_m = 0.3e-3;
  EXPECT_NE(message([&] { MakePushButton(p); }).find("total travel"), std::string::npos);
  p = {};
  p.operating_force_n = std::nan("");
  EXPECT_NE(message([&] { MakePushButton(p); }).find("operating force"), std::string::npos);
}

}  // namespace
}  // namespace hapticad
