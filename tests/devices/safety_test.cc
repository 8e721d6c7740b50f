// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/safety.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "hapticad/devices/trace_sample.h"

namespace hapticad {
namespace {

DeviceLimits Limits() {
  DeviceLimits l;
  l.max_force_n = 3.0;
  l.continuous_force_n = 1.0;
  l.workspace_min_d = Vec3::Constant(-0.1);
  l.workspace_max_d = Vec3::Constant(0.1);
  return l;
}

DeviceState Good() {
  DeviceState s;
  s.position_d = Vec3(0.01, 0.02, 0.03);
  s.velocity_d = Vec3(0.1, 0, 0);
  return s;
}

TEST(ForceSafety, PassesAGoodReadingAndFlagsEachBadOne) {
  ForceSafety safety(Limits(), SafetyConfig{});
  EXPECT_EQ(safety.CheckReading(ReadStatus::kOk, Good(), 0.001), 0u);
  EXPECT_EQ(safety.CheckReading(ReadStatus::kNoData, Good(), 0.001), kFaultNoData);
  EXPECT_EQ(safety.CheckReading(ReadStatus::kOutOfRange, Good(), 0.001), kFaultOutOfRange);
  EXPECT_EQ(safety.CheckReading(ReadStatus::kDeviceFault, Good(), 0.001), kFaultReported);
  EXPECT_EQ(safety.CheckReading(ReadStatus::kUnplugged, Good(), 0.001), kFaultUnplugged);
  EXPECT_EQ(safety.CheckReading(ReadStatus::kOk, Good(), 0.0051), kFaultWatchdog);
  DeviceState s = Good();
  s.age_s = 0.006;
  EXPECT_EQ(safety.CheckReading(ReadStatus::kOk, s, 0.001), kFaultStale);
  s = Good();
  s.position_d.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(safety.CheckReading(ReadStatus::kOk, s, 0.001), kFaultNonFinite);
  s = Good();
  s.velocity_d.z() = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(safety.CheckReading(ReadStatus::kOk, s, 0.001), kFaultNonFinite);
  s = Good();
  s.position_d.z() = 0.149;  // inside the workspace grown by 25 % (0.05 m)
  EXPECT_EQ(safety.CheckReading(ReadStatus::kOk, s, 0.001), 0u);
  s.position_d.z() = 0.151;
  EXPECT_EQ(safety.CheckReading(ReadStatus::kOk, s, 0.001), kFaultOutOfRange);
  s = Good();
  s.velocity_d = Vec3(0, 10.1, 0);
  EXPECT_EQ(safety.CheckReading(ReadStatus::kOk, s, 0.001), kFaultOutOfRange);
}

TEST(ForceSafety, RampsInThenClampsToTheMaximum) {
  ForceSafety safety(Limits(), SafetyConfig{});
  safety.BeginSession(0.0);
  for (int i = 0; i <= 300; ++i) {
    const double t = i * 1e-3;
    std::uint32_t flags = 0;
    const Vec3 f = safety.Shape(t, 0, Vec3(0, 0, 0.5), &flags);
    const double expected = 0.5 * std::min(1.0, t / 0.2);
    EXPECT_NEAR(f.z(), expected, 1e-12) << t;
    EXPECT_EQ((flags & kRamping) != 0, t < 0.2 - 1e-12) << t;
  }
  std::uint32_t flags = 0;
  const Vec3 f = safety.Shape(0.301, 0, Vec3(0, 4, 0), &flags);
  EXPECT_NEAR(f.norm(), 3.0, 1e-12);
  EXPECT_TRUE(flags & kSafetyClamped);
}

TEST(ForceSafety, AFaultZeroesTheForceAndTheForceRampsBackAfterIt) {
  ForceSafety safety(Limits(), SafetyConfig{});
  safety.BeginSession(0.0);
  std::uint32_t flags = 0;
  safety.Shape(0.5, 0, Vec3(0, 0, 0.5), &flags);
  flags = 0;
  EXPECT_EQ(safety.Shape(0.501, kFaultStale, Vec3(0, 0, 0.5), &flags), Vec3::Zero());
  EXPECT_EQ(flags, kFaultStale | kDeviceFault);
  flags = 0;
  EXPECT_NEAR(safety.Shape(0.502, 0, Vec3(0, 0, 0.5), &flags).z(), 0.0, 1e-12);  // ramp starts
  EXPECT_TRUE(flags & kRamping);
  flags = 0;
  EXPECT_NEAR(safety.Shape(0.602, 0, Vec3(0, 0, 0.5), &flags).z(), 0.25, 1e-12);
  // the renderer's own NaN is caught too
  flags = 0;
  EXPECT_EQ(safety.Shape(0.7, 0, Vec3(0, NAN, 0), &flags), Vec3::Zero());
  EXPECT_EQ(flags, kFaultNonFinite | kDeviceFault);
}

TEST(ForceSafety, ARampFromTheForceLastSentHasNoStepAndOneFromZeroStopsItAtOnce) {
  ForceSafety safety(Limits(), SafetyConfig{});
  safety.BeginSession(0.0);
  std::uint32_t flags = 0;
  int i = 0;
  for (; i <= 500; ++i) safety.Shape(i * 1e-3, 0, Vec3(0, 0, 1.2), &flags);
  // asked to ramp again (a scene swap) with the same force asked for: it stays
  safety.RestartRamp(RampFrom::kLastSent);
  for (const int end = i + 300; i < end; ++i) {
    flags = 0;
    const Vec3 f = safety.Shape(i * 1e-3, 0, Vec3(0, 0, 1.2), &flags);
    EXPECT_NEAR(f.z(), 1.2, 1e-12) << i;
    EXPECT_EQ((flags & kRamping) != 0, i < 701) << i;
  }
  // asked to ramp again from what was sent with no force asked for: it fades out
  // linearly over the ramp instead of dropping in one tick
  safety.RestartRamp(RampFrom::kLastSent);
  const int start = i;
  for (const int end = i + 300; i < end; ++i) {
    flags = 0;
    const Vec3 f = safety.Shape(i * 1e-3, 0, Vec3::Zero(), &flags);
    EXPECT_NEAR(f.z(), 1.2 * std::max(0.0, 1.0 - (i - start) * 1e-3 / 0.2), 1e-9) << i;
  }
  // and in again, from zero: as the ramp at the start
  safety.RestartRamp(RampFrom::kLastSent);
  const int again = i;
  for (const int end = i + 300; i < end; ++i) {
    flags = 0;
    const Vec3 f = safety.Shape(i * 1e-3, 0, Vec3(0, 0, 0.5), &flags);
    EXPECT_NEAR(f.z(), 0.5 * std::min(1.0, (i - again) * 1e-3 / 0.2), 1e-9) << i;
  }
  // from zero (a new mapping): the force sent stops at once and the new one ramps in
  safety.RestartRamp(RampFrom::kZero);
  const int fresh = i;
  for (const int end = i + 300; i < end; ++i) {
    flags = 0;
    const Vec3 f = safety.Shape(i * 1e-3, 0, Vec3(0, 0, 0.9), &flags);
    EXPECT_NEAR(f.z(), 0.9 * std::min(1.0, (i - fresh) * 1e-3 / 0.2), 1e-9) << i;
  }
  // a fault still zeroes the force at once, and the force ramps in from zero after it
  flags = 0;
  EXPECT_EQ(safety.Shape(i * 1e-3, kFaultStale, Vec3(0, 0, 0.5), &flags), Vec3::Zero());
  ++i;
  EXPECT_EQ(safety.Shape(i * 1e-3, 0, Vec3(0, 0, 0.5), &flags).z(), 0.0);
}

TEST(ForceSafety, HoldsTheContinuousForceOnceTheMotorsAreWarm) {
  SafetyConfig config;
  config.thermal_time_constant_s = 1.0;
  ForceSafety safety(Limits(), config);  // 3 N peak, 1 N continuous
  safety.BeginSession(0.0);
  double warm_at = -1.0;
  double first_limited = -1.0;
  double previous = 0.0;
  for (int i = 0; i < 5000; ++i) {
    const double t = i * 1e-3;
    if (warm_at < 0 && safety.thermal_force_n() > 1.0) warm_at = t;
    std::uint32_t flags = 0;
    const double f = safety.Shape(t, 0, Vec3(0, 0, 2.5), &flags).norm();
    if ((flags & kThermalLimited) && first_limited < 0) first_limited = t;
    if (warm_at >= 0) {
      // the cap comes down from 3 N at (3 - 1) N / 0.2 s: no step, never back up while
      // warm, and the continuous force from 0.2 s on
      EXPECT_NEAR(f, std::clamp(3.0 - 10.0 * (t + 1e-3 - warm_at), 1.0, 2.5), 1e-9) << t;
      EXPECT_LE(f, previous + 1e-12) << t;
    }
    previous = f;
  }
  // 2.5 N heats to (1 N)^2 after tau ln(6.25 / 5.25) = 0.17 s (plus the ramp); the cap
  // meets 2.5 N 0.05 s later
  EXPECT_GT(warm_at, 0.2);
  EXPECT_LT(warm_at, 0.35);
  EXPECT_NEAR(first_limited, warm_at + 0.05, 1.5e-3);
  EXPECT_NEAR(safety.thermal_force_n(), 1.0, 0.01);
  // no ramp: held to the continuous force in the tick the motors are warm, as asked
  config.ramp_s = 0.0;
  ForceSafety at_once(Limits(), config);
  at_once.BeginSession(0.0);
  for (int i = 0; i < 5000; ++i) {
    const bool warm = at_once.thermal_force_n() > 1.0;
    std::uint32_t flags = 0;
    const double f = at_once.Shape(i * 1e-3, 0, Vec3(0, 0, 2.5), &flags).norm();
    EXPECT_NEAR(f, warm ? 1.0 : 2.5, 1e-12) << i;
  }
  // a device that states no continuous force is never held back
  DeviceLimits none = Limits();
  none.continuous_force_n = 0.0;
  ForceSafety free(none, config);
  free.BeginSession(0.0);
  std::uint32_t flags = 0;
  for (int i = 0; i < 5000; ++i) free.Shape(i * 1e-3, 0, Vec3(0, 0, 2.5), &flags);
  EXPECT_FALSE(flags & kThermalLimited);
}

TEST(ForceSafety, CooledMotorsLetTheForceBackUpOverTheRampNotInOneTick) {
  SafetyConfig config;
  config.thermal_time_constant_s = 0.5;
  ForceSafety safety(Limits(), config);  // 3 N peak, 1 N continuous
  safety.BeginSession(0.0);
  std::uint32_t flags = 0;
  int i = 0;
  for (; i < 2000; ++i) safety.Shape(i * 1e-3, 0, Vec3(0, 0, 2.5), &flags);  // warm, held
  // the hand eases off to 0.5 N for 100 ms: the motors cool below the continuous
  // force and the cap climbs back from 1 N, at 10 N/s: under 2 N
  for (; i < 2100; ++i) safety.Shape(i * 1e-3, 0, Vec3(0, 0, 0.5), &flags);
  EXPECT_LT(safety.thermal_force_n(), 1.0);
  // then asks for 2.5 N again: it gets the cap, which climbs no faster until the motors
  // are warm again and it comes back down
  double previous = 0.5;
  double top = 0.0;
  for (; i < 2500; ++i) {
    flags = 0;
    const double f = safety.Shape(i * 1e-3, 0, Vec3(0, 0, 2.5), &flags).norm();
    EXPECT_TRUE(flags & kThermalLimited) << i;
    EXPECT_LE(f, i == 2100 ? 2.0 + 0.01 + 1e-9 : previous + 0.01 + 1e-9) << i;
    previous = f;
    top = std::max(top, f);
  }
  EXPECT_GT(top, 1.5);
  EXPECT_NEAR(previous, 1.0, 1e-9);
}

TEST(ForceSafety, FaultsWithoutABreakTimeOut) {
  SafetyConfig config;
  config.fault_timeout_s = 0.5;
  ForceSafety safety(Limits(), config);
  safety.BeginSession(0.0);
  std::uint32_t flags = 0;
  for (int i = 0; i < 400; ++i) safety.Shape(1.0 + i * 1e-3, kFaultNoData, Vec3::Zero(), &flags);
  safety.Shape(1.4, 0, Vec3::Zero(), &flags);  // one good tick resets the clock
  for (int i = 0; i < 450; ++i) safety.Shape(1.5 + i * 1e-3, kFaultStale, Vec3::Zero(), &flags);
  EXPECT_FALSE(safety.fault_timed_out());
  for (int i = 450; i <= 500; ++i) safety.Shape(1.5 + i * 1e-3, kFaultStale, Vec3::Zero(), &flags);
  EXPECT_TRUE(safety.fault_timed_out());
}

TEST(ForceSafety, RejectsBadSettings) {
  SafetyConfig bad;
  bad.stale_after_s = 0.0;
  EXPECT_THROW(ForceSafety(Limits(), bad), std::invalid_argument);
  DeviceLimits limits = Limits();
  limits.max_force_n = -1.0;
  EXPECT_THROW(ForceSafety(limits, SafetyConfig{}), std::invalid_argument);
  limits = Limits();
  limits.workspace_max_d.x() = -0.2;
  EXPECT_THROW(ForceSafety(limits, SafetyConfig{}), std::invalid_argument);
}

}  // namespace
}  // namespace hapticad
