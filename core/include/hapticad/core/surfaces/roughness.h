// SPDX-License-Identifier: GPL-3.0-or-later
// The seven surface-roughness categories of seed 000, Table 2 (ISO 1302:1992 grades).
//
// Each category binds an Ra range (micrometres), its ISO N-grades, and the "computer
// grid ball size" (mm) with which the paper renders it as a grid texture. Category 1
// has no lower Ra bound ("~ 0.05"), category 7 no upper bound ("50 ~") and no grade
// ("Unclassified"): those bounds are NaN here and null in JSON.
#pragma once

#include <array>

namespace hapticad {

struct RoughnessCategory {
  int category;                         // 1..7
  double ra_min_um;                     // NaN for category 1
  double ra_max_um;                     // NaN for category 7
  std::array<const char*, 2> n_grades;  // nullptr where absent
  double grid_size_mm;
};

// Table 2, row by row.
const std::array<RoughnessCategory, 7>& RoughnessTable();

// The row of `category` (1..7). Throws std::out_of_range otherwise.
const RoughnessCategory& GetRoughnessCategory(int category);

}  // namespace hapticad
