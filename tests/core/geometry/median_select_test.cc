// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/median_select.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

struct Item {
  float key;
  std::uint32_t id;
};

float KeyOf(const Item& item) { return item.key; }

// a[k] is the kth smallest key, nothing before it greater, nothing after it smaller, and
// the items are those it was given
void ExpectSelected(std::vector<Item> items, std::size_t k) {
  std::vector<Item> sorted = items;
  std::sort(sorted.begin(), sorted.end(),
            [](const Item& a, const Item& b) { return a.key < b.key; });
  SelectNth(items.data(), items.size(), k, KeyOf);
  ASSERT_EQ(items[k].key, sorted[k].key);
  for (std::size_t i = 0; i < k; ++i) ASSERT_LE(items[i].key, items[k].key) << i;
  for (std::size_t i = k + 1; i < items.size(); ++i) ASSERT_GE(items[i].key, items[k].key) << i;
  std::vector<std::uint32_t> ids;
  for (const Item& item : items) ids.push_back(item.id);
  std::sort(ids.begin(), ids.end());
  for (std::size_t i = 0; i < ids.size(); ++i) ASSERT_EQ(ids[i], i);
}

std::vector<Item> Items(std::size_t n, const std::function<float(std::size_t)>& key) {
  std::vector<Item> items(n);
  for (std::size_t i = 0; i < n; ++i) items[i] = {key(i), static_cast<std::uint32_t>(i)};
  return items;
}

TEST(SelectNth, RandomKeysOfEverySize) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (std::size_t n : {1, 2, 3, 16, 17, 18, 100, 1000, 4097, 100000}) {
    const auto items = Items(n, [&](std::size_t) { return u(rng); });
    ExpectSelected(items, n / 2);
    ExpectSelected(items, 0);
    ExpectSelected(items, n - 1);
  }
}

TEST(SelectNth, RepeatedKeys) {
  std::mt19937 rng(8);
  std::uniform_int_distribution<int> few(0, 3);
  // a flat face's reference points share a coordinate; a grid's share a few values
  ExpectSelected(Items(10000, [](std::size_t) { return 0.5f; }), 5000);
  ExpectSelected(Items(10000, [&](std::size_t) { return static_cast<float>(few(rng)); }), 5000);
  ExpectSelected(Items(10000, [](std::size_t i) { return i < 9990 ? 1.0f : 0.0f; }), 5000);
  ExpectSelected(Items(10000, [](std::size_t i) { return i % 64 == 0 ? -1.0f : 2.0f; }), 100);
}

TEST(SelectNth, TheKeyRightAfterThePivotsRun) {
  // first round's pivot: the median of a[0] = 0, a[50] = 1, a[100] = 3; 30 keys below it
  // and 20 equal to it, so the wanted a[50] is the first key above them (2.0, in between)
  std::vector<Item> items(101);
  for (std::size_t i = 0; i < 101; ++i) {
    float key = 3.0f + static_cast<float>(100 - i);  // above the pivot, falling
    if (i < 30) key = 0.0f;
    if (i >= 40 && i < 60) key = 1.0f;
    items[i] = {key, static_cast<std::uint32_t>(i)};
  }
  items[100].key = 3.0f;
  items[35].key = 2.0f;
  ExpectSelected(items, 50);
}

TEST(SelectNth, OrderedAndOrganPipeInputs) {
  const std::size_t n = 20001;
  ExpectSelected(Items(n, [](std::size_t i) { return static_cast<float>(i); }), n / 2);
  ExpectSelected(Items(n, [=](std::size_t i) { return static_cast<float>(n - i); }), n / 2);
  // rising then falling: a bad case for a median-of-three pivot, which runs out of rounds
  // and hands over to std::nth_element (the test fails if that hand-over does nothing)
  ExpectSelected(Items(n, [=](std::size_t i) { return static_cast<float>(std::min(i, n - i)); }),
                 n / 2);
}

}  // namespace
}  // namespace hapticad
