// SPDX-License-Identifier: GPL-3.0-or-later
// The writer thread of the HID backend against the hidapi emulator: what the tick posts
// is written, the newest first, without the tick ever waiting; a write stuck in the
// "kernel" (the emulator's kSlowWrite, as usbhid's 5 s timeout) shows as a growing command
// delay; failures are final after three; the owner is never held longer than its bounds.
#include "hapticad/devices/hid/hid_output_writer.h"

#include <hidapi/hidapi.h>
#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "alloc_counter.h"
#include "hid_emulator.h"
#include "syscall_counter.h"
#include "thread_stall.h"

namespace hapticad {
namespace {

using hidemu::Fault;
using hidemu::FaultWindow;
using hidemu::FirmwareConfig;
using Clock = std::chrono::steady_clock;

constexpr double kPlugTime = 10.0;

// A valid output report (PROTOCOL.md §3.2) with ENABLE and force z in uN.
HidOutputWriter::Report Force(std::uint16_t sequence, std::int32_t z_un) {
  hid::OutputReport r;
  r.flags = hid::kOutputEnable;
  r.sequence = sequence;
  r.force_un[2] = z_un;
  HidOutputWriter::Report out;
  hid::EncodeOutput(r, out.data());
  return out;
}

double Seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// Waits (real time, at most 5 s) until `done` holds.
template <class F>
bool Eventually(F done) {
  const auto give_up = Clock::now() + std::chrono::seconds(5);
  while (!done()) {
    if (Clock::now() > give_up) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return true;
}

class Writer : public ::testing::Test {
 protected:
  void SetUp() override {
    hidemu::Reset();
    hidemu::UseManualClock(kPlugTime);
  }
  void TearDown() override { hidemu::Reset(); }

  // Plugs in `c` (a session open, so it applies forces) and gives a writer a handle on it.
  std::unique_ptr<HidOutputWriter> Plug(FirmwareConfig c = {}) {
    id_ = hidemu::AddDevice(c);
    hid_device* control = hid_open_path(c.path.c_str());
    std::uint8_t session[8] = {hid::kSessionReportId, hid::kSessionOpen, 0x00, 0x01, 50, 0, 0, 0};
    EXPECT_EQ(hid_send_feature_report(control, session, sizeof session), 8);
    hid_close(control);
    return std::make_unique<HidOutputWriter>(hid_open_path(c.path.c_str()));
  }

  int id_ = -1;
};

TEST_F(Writer, WritesWhatIsPostedAndOnlyTheNewestOfWhatPiledUp) {
  auto w = Plug();
  w->BeginSession();
  w->Post(Force(1, 1000000), kPlugTime);
  ASSERT_TRUE(w->WaitUntilWritten(5.0));
  hidemu::SetTime(kPlugTime + 0.001);
  EXPECT_NEAR(hidemu::GetSnapshot(id_).applied_force_n.z(), 1.0, 1e-9);
  // hold the thread in a job while the tick posts three: only the newest goes out
  auto release = std::make_shared<std::atomic<bool>>(false);
  EXPECT_FALSE(w->Run(
      [release](hid_device*) {
        while (!release->load()) std::this_thread::sleep_for(std::chrono::microseconds(100));
      },
      0.01));
  w->Post(Force(2, 2000000), kPlugTime + 0.001);
  w->Post(Force(3, 3000000), kPlugTime + 0.001);
  w->Post(Force(4, 4000000), kPlugTime + 0.001);
  EXPECT_FALSE(w->WaitUntilWritten(0.02));  // the thread is busy: the wait is bounded
  release->store(true);
  ASSERT_TRUE(w->WaitUntilWritten(5.0));
  hidemu::SetTime(kPlugTime + 0.002);
  const hidemu::Snapshot snap = hidemu::GetSnapshot(id_);
  EXPECT_NEAR(snap.applied_force_n.z(), 4.0, 1e-9);
  EXPECT_EQ(snap.outputs_received, 2u);
  const HidWriterStats stats = w->Stats();
  EXPECT_EQ(stats.posted, 4u);
  EXPECT_EQ(stats.writes, 2u);
  EXPECT_EQ(stats.superseded, 2u);
  EXPECT_EQ(stats.writes_failed, 0u);
  EXPECT_EQ(w->CommandDelayS(kPlugTime + 0.002), 0.0);
}

TEST_F(Writer, AJobDropsTheReportsPostedBeforeItAndRunsAfterTheWriteUnderWay) {
  auto w = Plug();
  w->BeginSession();
  auto order = std::make_shared<std::string>();
  w->Post(Force(1, 1000000), kPlugTime);
  ASSERT_TRUE(w->WaitUntilWritten(5.0));
  auto release = std::make_shared<std::atomic<bool>>(false);
  EXPECT_FALSE(w->Run(
      [release, order](hid_device*) {
        while (!release->load()) std::this_thread::sleep_for(std::chrono::microseconds(100));
        *order += "a";
      },
      0.0));
  w->Post(Force(2, 2000000), kPlugTime);  // waits behind the first job...
  EXPECT_FALSE(w->Run([order](hid_device*) { *order += "b"; }, 0.0));  // ...and the next drops it
  release->store(true);
  ASSERT_TRUE(w->Run([](hid_device*) {}, 5.0));
  EXPECT_EQ(*order, "ab");
  ASSERT_TRUE(w->WaitUntilWritten(5.0));
  EXPECT_EQ(w->Stats().writes, 1u);  // report 2 never went out: the job came after it
  EXPECT_EQ(w->Stats().superseded, 1u);
  hidemu::SetTime(kPlugTime + 0.001);
  EXPECT_NEAR(hidemu::GetSnapshot(id_).applied_force_n.z(), 1.0, 1e-9);
}

TEST_F(Writer, TheTickSideNeitherAllocatesNorMakesASystemCall) {
  auto w = Plug();
  w->BeginSession();
  const HidOutputWriter::Report r = Force(1, 1000);
  {
    testing::AllocationCounter counter;
    for (int i = 0; i < 1000; ++i) {
      w->CommandDelayS(kPlugTime + i * 1e-3);
      w->Post(r, kPlugTime + i * 1e-3);
    }
    EXPECT_EQ(counter.count(), 0u);
  }
  ASSERT_TRUE(w->WaitUntilWritten(5.0));
  // in a child process (where the writer thread does not run: its posts pile up, which is
  // the stuck case too) the tick's half makes no system call, not even to wake the writer
  const long calls = testing::CountSystemCalls([&] {
    for (int i = 0; i < 1000; ++i) {
      w->CommandDelayS(kPlugTime + 1.0 + i * 1e-3);
      w->Post(r, kPlugTime + 1.0 + i * 1e-3);
    }
  });
  EXPECT_EQ(calls, 0);
}

TEST_F(Writer, TheCommandDelayGrowsWhileAWriteIsStuckAndTheStuckWriteTimesOut) {
  FirmwareConfig c;
  c.faults.push_back(FaultWindow{Fault::kSlowWrite, 0.1, 0.2, 5.0});  // as usbhid: 5 s
  auto w = Plug(c);
  w->BeginSession();
  w->Post(Force(1, 1000000), kPlugTime + 0.099);
  ASSERT_TRUE(w->WaitUntilWritten(5.0));
  EXPECT_EQ(w->CommandDelayS(kPlugTime + 0.1), 0.0);
  hidemu::SetTime(kPlugTime + 0.1);
  w->Post(Force(2, 2000000), kPlugTime + 0.1);
  ASSERT_TRUE(Eventually([] { return hidemu::BlockedWrites() == 1; }));
  EXPECT_GT(w->busy_s(), 0.0);
  EXPECT_NEAR(w->CommandDelayS(kPlugTime + 0.103), 0.003, 1e-9);
  w->Post(Force(3, 3000000), kPlugTime + 0.103);  // piles up behind it: the delay is the oldest's
  EXPECT_NEAR(w->CommandDelayS(kPlugTime + 0.250), 0.150, 1e-9);
  EXPECT_FALSE(w->failed());
  // 5 s on the write fails with ETIMEDOUT; report 3 is then written (outside the window)
  hidemu::SetTime(kPlugTime + 5.2);
  ASSERT_TRUE(w->WaitUntilWritten(5.0));
  EXPECT_EQ(w->CommandDelayS(kPlugTime + 5.2), 0.0);
  EXPECT_EQ(hidemu::GetSnapshot(id_).outputs_timed_out, 1u);
  const HidWriterStats stats = w->Stats();
  EXPECT_EQ(stats.writes, 3u);
  EXPECT_EQ(stats.writes_failed, 1u);
  EXPECT_FALSE(w->failed());  // one timeout is not three
}

TEST_F(Writer, EachFinishedWriteRestartsTheDelay) {
  // a device that takes a report every 3 ms while the tick posts every 1 ms: the delay is
  // about one write, not a growing backlog (the newest report replaces the older ones)
  FirmwareConfig c;
  c.faults.push_back(FaultWindow{Fault::kLateWrite, 0.1, 0.2, 0.003});
  auto w = Plug(c);
  w->BeginSession();
  double worst = 0.0;
  // the writer has taken what it can (and is held up in a write, or done) before the
  // clock or the tick moves on
  auto settle = [&] {
    ASSERT_TRUE(Eventually([&] { return hidemu::BlockedWrites() == 1 || w->WaitUntilWritten(0); }));
  };
  for (int i = 100; i < 160; ++i) {
    const double t = kPlugTime + i * 1e-3;
    hidemu::SetTime(t);
    settle();
    worst = std::max(worst, w->CommandDelayS(t));
    w->Post(Force(static_cast<std::uint16_t>(i), 1000), t);
    settle();
  }
  EXPECT_GE(worst, 0.002);
  EXPECT_LE(worst, 0.003 + 1e-9);
  EXPECT_GT(w->Stats().superseded, 30u);
}

TEST_F(Writer, ThreeFailedWritesInARowAreFinalWithHidapisWords) {
  // failures with a success between them are not counted together
  FirmwareConfig c;
  c.faults.push_back(FaultWindow{Fault::kSlowWrite, 0.1, 0.103, 0.001});
  c.faults.push_back(FaultWindow{Fault::kSlowWrite, 0.2, 0.203, 0.001});
  auto w = Plug(c);
  w->BeginSession();
  std::uint16_t sequence = 0;
  auto post_at = [&](double t) {
    hidemu::SetTime(kPlugTime + t);
    w->Post(Force(++sequence, 1000), kPlugTime + t);
    // a blocked write needs the clock to move: give it a ms
    if (!w->WaitUntilWritten(0.2)) {
      hidemu::SetTime(kPlugTime + t + 0.0011);
      ASSERT_TRUE(w->WaitUntilWritten(5.0));
    }
  };
  post_at(0.1000);  // fails
  post_at(0.1015);  // fails
  post_at(0.1500);  // written
  post_at(0.2000);  // fails
  post_at(0.2015);  // fails
  post_at(0.2500);  // written
  EXPECT_FALSE(w->failed());
  EXPECT_EQ(w->Stats().writes_failed, 4u);
  EXPECT_EQ(std::wstring(w->failure_reason()), L"");
  hidemu::Unplug(id_);
  post_at(0.300);
  post_at(0.301);
  EXPECT_FALSE(w->failed());
  post_at(0.302);  // three in a row
  EXPECT_TRUE(w->failed());
  EXPECT_EQ(std::wstring(w->failure_reason()), L"hid_write: No such device");
}

TEST_F(Writer, CopiesTheSchedulingOfThePostingThread) {
  auto w = Plug();
  w->BeginSession();  // before the thread posts (BeginSession's contract)
  std::thread tick([&] {
    // SCHED_BATCH needs no privilege (the servo loop asks SCHED_FIFO, copied the same way)
    sched_param none{};
    ASSERT_EQ(pthread_setschedparam(pthread_self(), SCHED_BATCH, &none), 0);
    w->Post(Force(1, 1000), kPlugTime);
    ASSERT_TRUE(w->WaitUntilWritten(5.0));
    w->EndSession();  // before this thread ends
  });
  tick.join();
  EXPECT_EQ(w->Stats().policy, SCHED_BATCH);
}

TEST_F(Writer, LetsGoOfAWriteStuckInTheKernelWithinItsBound) {
  hidemu::UseRealClock();
  FirmwareConfig c;
  c.path = "emu:abandoned";
  c.faults.push_back(FaultWindow{Fault::kSlowWrite, 0.0, 1e9, 3.0});
  auto w = Plug(c);
  EXPECT_EQ(hidemu::OpenHandles(c.path), 1);
  w->BeginSession();
  w->Post(Force(1, 1000), hidemu::Now());
  ASSERT_TRUE(Eventually([] { return hidemu::BlockedWrites() == 1; }));
  // a job (the session's close) queued behind it runs once the write returns, after the
  // writer is gone: it owns what it uses
  auto closed = std::make_shared<std::atomic<bool>>(false);
  auto start = Clock::now();
  EXPECT_FALSE(w->Run([closed](hid_device*) { closed->store(true); }, 0.05));
  w.reset();
  const double took = Seconds(start, Clock::now());
  // within its bound, not the 3 s the write is stuck (0.5 s of slack for a loaded machine)
  EXPECT_LT(took, 0.05 + HidOutputWriter::kAbandonAfterS + 0.5) << took;
  EXPECT_FALSE(closed->load());
  EXPECT_EQ(hidemu::OpenHandles(c.path), 1);  // the stuck thread still has it
  // when the write times out, the abandoned thread runs the job and closes its handle
  ASSERT_TRUE(Eventually([&] { return hidemu::OpenHandles(c.path) == 0; }));
  EXPECT_TRUE(closed->load());
}

TEST_F(Writer, ItsHandleIsClosedWhenTheDestructorReturns) {
  // The handle used to be closed by whichever of the destructor and the ended thread let go
  // of the writer's state last: now and then the thread, just after the destructor had
  // returned (seen in CI, as a handle still open on a device just closed). Busy threads on
  // every core make the thread lose its core at that moment more often; seeded by nothing:
  // the race is the scheduler's, so this test can only fail on a chance, not pass on one.
  std::atomic<bool> stop{false};
  std::vector<std::thread> busy;
  for (unsigned i = 0; i < std::max(2u, std::thread::hardware_concurrency()); ++i) {
    busy.emplace_back([&stop] {
      while (!stop.load(std::memory_order_relaxed)) {
      }
    });
  }
  int still_open = 0;
  for (int i = 0; i < 300; ++i) {
    auto w = Plug();
    w.reset();
    still_open += hidemu::OpenHandles("emu:0");
  }
  stop = true;
  for (std::thread& t : busy) t.join();
  EXPECT_EQ(still_open, 0);
}

TEST_F(Writer, AThreadOnlyNotScheduledIsWaitedForNotCalledStuck) {
  // the writer kept from running for 0.3 s (a loaded machine), outside hidapi: a 50 ms
  // Run() gave up on it, so BeginSession() called a working device one not taking
  // commands ("a write to it has waited 0.0 s"), and the destructor left its handle open
  auto w = Plug();
  ASSERT_TRUE(w->Run([](hid_device*) {}, 1.0));  // the thread runs (and is named) now
  ASSERT_GE(testing_stall::StallThreads("hid-writer", 0.3), 1);
  auto start = Clock::now();
  EXPECT_TRUE(w->Run([](hid_device*) {}, 0.05));
  EXPECT_GT(Seconds(start, Clock::now()), 0.2);  // it did wait the stall out
  ASSERT_GE(testing_stall::StallThreads("hid-writer", 0.3), 1);
  w.reset();
  EXPECT_EQ(hidemu::OpenHandles("emu:0"), 0);
}

}  // namespace
}  // namespace hapticad
