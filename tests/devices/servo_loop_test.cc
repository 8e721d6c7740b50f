// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/servo_loop.h"

#include <stdexcept>

#include <gtest/gtest.h>

#include "alloc_counter.h"
#include "hapticad/devices/simulated_device.h"
#include "test_meshes.h"

namespace hapticad {
namespace {

class ServoOnBox : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = HapticScene::Build(testing::MakeBoxSoup(Vec3(-50, -50, -50), Vec3(50, 50, 50)), 1e-3);
    surfaces_ = std::make_shared<SurfaceTable>();
    ScriptedPath path;  // down onto the top face, 1 mm in, slide 20 mm, up
    path.times_s = {0.0, 0.05, 0.10, 0.30, 0.35};
    path.positions_w = {Vec3(0, 0, 0.06), Vec3(0, 0, 0.049), Vec3(0, 0, 0.049),
                        Vec3(0.02, 0, 0.049), Vec3(0.02, 0, 0.06)};
    limits_.max_force_n = 8.0;
    limits_.max_stiffness_n_per_m = 3000.0;
    device_ = std::make_unique<SimulatedDevice>(path, limits_);
    renderer_ = std::make_unique<ForceRenderer>(
        scene_, surfaces_, RenderLimits{limits_.max_force_n, limits_.max_stiffness_n_per_m});
  }
  std::shared_ptr<const HapticScene> scene_;
  std::shared_ptr<SurfaceTable> surfaces_;
  DeviceLimits limits_;
  std::unique_ptr<SimulatedDevice> device_;
  std::unique_ptr<ForceRenderer> renderer_;
};

TEST_F(ServoOnBox, RunsAtItsRateAndRecordsEveryTick) {
  ServoLoop loop(*device_, *renderer_, ServoConfig{1000.0, 4096});
  const auto trace = loop.RunFor(0.3);
  const ServoStats stats = loop.stats();
  EXPECT_EQ(trace.size(), stats.ticks);
  EXPECT_EQ(stats.trace_dropped, 0u);
  // ticks at 0, 1, ..., 300 ms (0.3 is not a multiple of 1e-3 in binary: the loop
  // must still include 300 ms): every one either ran or was skipped after an overrun
  EXPECT_EQ(trace.size() + stats.skipped_ticks, 301u);
  EXPECT_LE(stats.skipped_ticks, 20u);
  // the loop clock advances one period per tick (plus skipped ones)
  for (std::size_t i = 1; i < trace.size(); ++i) EXPECT_GT(trace[i].time_s, trace[i - 1].time_s);
  // it touched the top face, pressed 1 mm at the default 0.4 N/mm
  int contact = 0;
  for (const auto& s : trace) {
    if (!(s.flags & kContact)) continue;
    ++contact;
    EXPECT_EQ(s.cad_face, 5);
    if (s.time_s > 0.06 && s.time_s < 0.29) {
      EXPECT_NEAR(s.normal_force_n, 0.4, 1e-6);
    }
  }
  EXPECT_GT(contact, 200);
  EXPECT_NEAR(trace.back().time_s, 0.3, 1e-12);
  EXPECT_FALSE(loop.running());
  EXPECT_EQ(device_->last_force_w(), Vec3::Zero());  // Stop() leaves the device at zero force
}

TEST_F(ServoOnBox, TickDoesNotAllocate) {
  ServoLoop loop(*device_, *renderer_, ServoConfig{1000.0, 1024});
  loop.Tick(0.0);
  testing::AllocationCounter counter;
  for (int i = 1; i < 350; ++i) loop.Tick(i * 1e-3);
  EXPECT_EQ(counter.count(), 0u);
  std::vector<TraceSample> trace;
  EXPECT_EQ(loop.DrainTrace(&trace), 350u);
}

TEST_F(ServoOnBox, CountsSamplesLostToAFullRing) {
  ServoLoop loop(*device_, *renderer_, ServoConfig{1000.0, 8});
  for (int i = 0; i < 20; ++i) loop.Tick(i * 1e-3);
  EXPECT_EQ(loop.stats().trace_dropped, 12u);
}

TEST_F(ServoOnBox, RejectsRatesOutsideRange) {
  EXPECT_THROW(ServoLoop(*device_, *renderer_, ServoConfig{0.0, 8}), std::invalid_argument);
  EXPECT_THROW(ServoLoop(*device_, *renderer_, ServoConfig{20000.0, 8}), std::invalid_argument);
}

TEST_F(ServoOnBox, StopIsIdempotentAndStartTwiceIsAnError) {
  ServoLoop loop(*device_, *renderer_);
  loop.Start();
  EXPECT_THROW(loop.Start(), std::logic_error);
  loop.Stop();
  loop.Stop();
  EXPECT_FALSE(loop.running());
}

}  // namespace
}  // namespace hapticad
