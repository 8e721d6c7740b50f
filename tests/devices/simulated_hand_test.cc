// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/simulated_hand.h"

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

#include "alloc_counter.h"

namespace hapticad {
namespace {

DeviceLimits Continuous() {
  DeviceLimits l = SimulatedHandLimits();
  l.position_resolution_m = 0.0;
  return l;
}

HandModel NoLatency() {
  HandModel m;
  m.latency_s = 0.0;
  return m;
}

// Reads at 1 kHz for `duration` from `*t`, commanding `force` after each read.
DeviceState ReadFor(SimulatedHand& hand, double* t, double duration,
                    const Vec3& force = Vec3::Zero()) {
  DeviceState s;
  const int n = static_cast<int>(std::lround(duration * 1000));
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(hand.ReadState(*t, &s), ReadStatus::kOk);
    hand.WriteForce(force);
    *t += 1e-3;
  }
  return s;
}

TEST(SimulatedHand, StartsAtItsTargetAndFollowsIt) {
  SimulatedHand hand(Continuous(), NoLatency());
  hand.SetTarget(Vec3(0.01, 0, 0));
  hand.BeginSession();
  double t = 0.0;
  DeviceState s = ReadFor(hand, &t, 0.001);
  EXPECT_EQ(s.position_d, Vec3(0.01, 0, 0));
  hand.SetTarget(Vec3(0.02, -0.01, 0.005));
  s = ReadFor(hand, &t, 1.0);
  EXPECT_NEAR((s.position_d - Vec3(0.02, -0.01, 0.005)).norm(), 0, 1e-6);
  EXPECT_NEAR(s.velocity_d.norm(), 0, 1e-4);
  EXPECT_EQ(hand.info().kind, "sim");
  EXPECT_EQ(hand.info().path, "sim:hand");
}

TEST(SimulatedHand, AForceDisplacesTheHandByItsGripStiffness) {
  SimulatedHand hand(Continuous(), NoLatency());
  hand.BeginSession();
  double t = 0.0;
  const DeviceState s = ReadFor(hand, &t, 2.0, Vec3(0, 0, 2.0));
  // 2 N against a 400 N/m grip: 5 mm
  EXPECT_NEAR(s.position_d.z(), 0.005, 1e-6);
  EXPECT_NEAR(hand.true_state().force_d.z(), 2.0, 1e-12);
}

TEST(SimulatedHand, ItsGripSaturates) {
  HandModel model = NoLatency();
  model.max_grip_force_n = 1.0;
  SimulatedHand hand(Continuous(), model);
  hand.BeginSession();
  double t = 0.0;
  // 1.5 N pushes a hand that can resist only 1 N: it gives way to the end stop
  const DeviceState s = ReadFor(hand, &t, 3.0, Vec3(0, 0, 1.5));
  EXPECT_NEAR(s.position_d.z(), 0.05, 1e-12);
}

TEST(SimulatedHand, ReportsQuantisedPositions) {
  DeviceLimits limits = SimulatedHandLimits();  // 0.055 mm
  SimulatedHand hand(limits, NoLatency());
  hand.SetTarget(Vec3(0.0123456, -0.0201, 0.0));
  hand.BeginSession();
  double t = 0.0;
  const DeviceState s = ReadFor(hand, &t, 1.0);
  for (int a = 0; a < 3; ++a) {
    const double steps = s.position_d[a] / 0.055e-3;
    EXPECT_NEAR(steps, std::round(steps), 1e-6);
  }
  EXPECT_NEAR(s.position_d.x(), 0.0123456, 0.5 * 0.055e-3 + 1e-9);
  EXPECT_NEAR(hand.true_state().position_d.x(), 0.0123456, 1e-6);
}

TEST(SimulatedHand, ReportsPositionsLatencyOld) {
  HandModel model;
  model.latency_s = 0.010;
  SimulatedHand hand(Continuous(), model);
  ScriptedPath path;  // a hand moving steadily at 50 mm/s
  path.times_s = {0.0, 1.0};
  path.positions = {Vec3(-0.025, 0, 0), Vec3(0.025, 0, 0)};
  hand.FollowPath(path);
  hand.BeginSession();
  double t = 0.0;
  DeviceState s = ReadFor(hand, &t, 0.6);
  const double truth = hand.true_state().position_d.x();
  EXPECT_NEAR(s.time_s, hand.true_state().time_s - 0.010, 1e-9);
  EXPECT_NEAR(truth - s.position_d.x(), 0.05 * 0.010, 2e-6);  // 10 ms at 50 mm/s
  EXPECT_NEAR(s.velocity_d.x(), 0.05, 1e-3);
  EXPECT_TRUE(hand.following_path());
}

TEST(SimulatedHand, TheDeviceWatchdogDropsAForceNotRefreshed) {
  SimulatedHand hand(Continuous(), NoLatency());
  hand.BeginSession();
  DeviceState s;
  hand.ReadState(0.0, &s);
  hand.WriteForce(Vec3(0, 0, 2.0));
  // no further command: the force acts for the watchdog's 5 ms, then drops
  for (int i = 1; i <= 200; ++i) {
    hand.ReadState(i * 1e-3, &s);
    EXPECT_EQ(hand.true_state().force_d.z(), i <= 5 ? 2.0 : 0.0) << i;
  }
  // and the hand goes back to its target
  double t = 0.2;
  ReadFor(hand, &t, 1.0, Vec3::Zero());
  EXPECT_NEAR(hand.true_state().position_d.z(), 0.0, 1e-6);
}

TEST(SimulatedHand, StopsAtTheWorkspaceWalls) {
  SimulatedHand hand(Continuous(), NoLatency());
  hand.SetTarget(Vec3(0.5, 0, 0));
  hand.BeginSession();
  double t = 0.0;
  const DeviceState s = ReadFor(hand, &t, 1.0);
  EXPECT_EQ(s.position_d.x(), 0.05);
}

TEST(SimulatedHand, TakesTargetsFromAnotherThreadWhileReading) {
  SimulatedHand hand(Continuous(), NoLatency());
  hand.BeginSession();
  std::atomic<bool> done{false};
  std::thread mouse([&] {
    for (int i = 0; i <= 200; ++i) {
      hand.SetTarget(Vec3(0.0001 * i, 0, 0));
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    done = true;
  });
  double t = 0.0;
  while (!done) ReadFor(hand, &t, 0.001);
  mouse.join();
  const DeviceState s = ReadFor(hand, &t, 1.0);
  EXPECT_NEAR(s.position_d.x(), 0.02, 1e-6);
  EXPECT_NEAR(hand.true_state().target_d.x(), 0.02, 1e-15);
}

TEST(SimulatedHand, ReadAndWriteDoNotAllocate) {
  SimulatedHand hand;
  hand.BeginSession();
  DeviceState s;
  testing::AllocationCounter counter;
  for (int i = 0; i < 2000; ++i) {
    hand.ReadState(i * 1e-3, &s);
    hand.WriteForce(Vec3(0, 0, 0.1));
    if (i == 1000) hand.SetTarget(Vec3(0.01, 0, 0));
  }
  EXPECT_EQ(counter.count(), 0u);
}

TEST(SimulatedHand, RefusesBadSettingsAndPathChangesDuringASession) {
  HandModel bad;
  bad.mass_kg = 0.0;
  EXPECT_THROW(SimulatedHand(SimulatedHandLimits(), bad), std::invalid_argument);
  bad = HandModel{};
  bad.latency_s = 1.0;
  EXPECT_THROW(SimulatedHand(SimulatedHandLimits(), bad), std::invalid_argument);
  SimulatedHand hand;
  EXPECT_THROW(hand.SetTarget(Vec3(NAN, 0, 0)), std::invalid_argument);
  EXPECT_THROW(hand.FollowPath(ScriptedPath{}), std::invalid_argument);
  hand.BeginSession();
  ScriptedPath path;
  path.times_s = {0.0};
  path.positions = {Vec3::Zero()};
  EXPECT_THROW(hand.FollowPath(path), std::logic_error);
  hand.EndSession();
  hand.FollowPath(path);
  EXPECT_TRUE(hand.following_path());
  hand.FollowTarget();
  EXPECT_FALSE(hand.following_path());
}

}  // namespace
}  // namespace hapticad
