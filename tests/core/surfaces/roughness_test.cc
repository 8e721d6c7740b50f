// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/surfaces/roughness.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

// seed 000, Table 2, typed in by hand
struct Row {
  int category;
  double ra_min, ra_max;
  const char* g0;
  const char* g1;
  double grid;
};
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const Row kTable2[] = {
    {1, kNaN, 0.05, "N1", "N2", 0.1},     {2, 0.05, 0.2, "N3", "N4", 0.3},
    {3, 0.2, 0.8, "N5", "N6", 0.6},       {4, 0.8, 3.2, "N7", "N8", 0.9},
    {5, 3.2, 12.5, "N9", "N10", 1.2},     {6, 12.5, 50, "N11", "N12", 1.5},
    {7, 50, kNaN, nullptr, nullptr, 3.0},
};

TEST(RoughnessTable, MatchesTable2RowByRow) {
  for (const Row& row : kTable2) {
    const RoughnessCategory& c = GetRoughnessCategory(row.category);
    EXPECT_EQ(c.category, row.category);
    if (std::isnan(row.ra_min)) {
      EXPECT_TRUE(std::isnan(c.ra_min_um));
    } else {
      EXPECT_EQ(c.ra_min_um, row.ra_min);
    }
    if (std::isnan(row.ra_max)) {
      EXPECT_TRUE(std::isnan(c.ra_max_um));
    } else {
      EXPECT_EQ(c.ra_max_um, row.ra_max);
    }
    if (row.g0) {
      EXPECT_EQ(std::string(c.n_grades[0]), row.g0);
      EXPECT_EQ(std::string(c.n_grades[1]), row.g1);
    } else {
      EXPECT_EQ(c.n_grades[0], nullptr);
      EXPECT_EQ(c.n_grades[1], nullptr);
    }
    EXPECT_EQ(c.grid_size_mm, row.grid);
  }
}

TEST(RoughnessTable, RangesTileTheRaAxis) {
  const auto& t = RoughnessTable();
  for (std::size_t i = 1; i < t.size(); ++i) EXPECT_EQ(t[i].ra_min_um, t[i - 1].ra_max_um);
}

TEST(RoughnessTable, RejectsCategoriesOutside1To7) {
  EXPECT_THROW(GetRoughnessCategory(0), std::out_of_range);
  EXPECT_THROW(GetRoughnessCategory(8), std::out_of_range);
}

}  // namespace
}  // namespace hapticad
