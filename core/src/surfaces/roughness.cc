// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/surfaces/roughness.h"

#include <limits>
#include <stdexcept>
#include <string>

namespace hapticad {

const std::array<RoughnessCategory, 7>& RoughnessTable() {
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  // seed 000, Table 2 "Surface roughness customization"
  static const std::array<RoughnessCategory, 7> table = {{
      {1, kNone, 0.05, {"N1", "N2"}, 0.1},
      {2, 0.05, 0.2, {"N3", "N4"}, 0.3},
      {3, 0.2, 0.8, {"N5", "N6"}, 0.6},
      {4, 0.8, 3.2, {"N7", "N8"}, 0.9},
      {5, 3.2, 12.5, {"N9", "N10"}, 1.2},
      {6, 12.5, 50.0, {"N11", "N12"}, 1.5},
      {7, 50.0, kNone, {nullptr, nullptr}, 3.0},
  }};
  return table;
}

const RoughnessCategory& GetRoughnessCategory(int category) {
  if (category < 1 || category > 7) {
    throw std::out_of_range("roughness category " + std::to_string(category) +
                            " is not one of 1..7 (seed 000, Table 2)");
  }
  return RoughnessTable()[category - 1];
}

}  // namespace hapticad
