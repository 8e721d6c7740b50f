// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/mailbox.h"

#include <atomic>
#include <chrono>
#include <thread>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

TEST(Mailbox, ReadsTheInitialThenTheLatestValue) {
  Mailbox<int> box(7);
  EXPECT_FALSE(box.has_news());
  EXPECT_EQ(box.Read(), 7);
  box.Write(1);
  box.Write(2);
  EXPECT_TRUE(box.has_news());
  EXPECT_EQ(box.Read(), 2);  // the latest, not a queue
  EXPECT_FALSE(box.has_news());
  EXPECT_EQ(box.Read(), 2);
}

struct Wide {
  long a, b, c, d, e, f, g, h;  // torn copies would mix values
};

TEST(Mailbox, NeverTearsAValueAcrossThreadsAndOnlyMovesForward) {
  Mailbox<Wide> box(Wide{0, 0, 0, 0, 0, 0, 0, 0});
  std::atomic<bool> stop{false};
  std::atomic<long> written{0};
  std::thread writer([&] {
    long i = 0;
    while (!stop.load()) {
      ++i;
      box.Write(Wide{i, i, i, i, i, i, i, i});
      written.store(i);
    }
  });
  // read while the writer writes, until the reader has seen it move many times (the
  // deadline only guards against a hang)
  long last = 0;
  long changes = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while ((changes < 1000 || written.load() < 100000) &&
         std::chrono::steady_clock::now() < deadline) {
    const Wide w = box.Read();
    ASSERT_TRUE(w.a == w.b && w.b == w.c && w.c == w.d && w.d == w.e && w.e == w.f && w.f == w.g &&
                w.g == w.h)
        << w.a << " " << w.h;
    ASSERT_GE(w.a, last);
    if (w.a != last) ++changes;
    last = w.a;
  }
  stop = true;
  writer.join();
  EXPECT_GE(changes, 1000);                 // the reader did see the writer's progress
  EXPECT_EQ(box.Read().a, written.load());  // and sees the last value once it stops
}

}  // namespace
}  // namespace hapticad
