// SPDX-License-Identifier: GPL-3.0-or-later
// Small analytic meshes for tests: an axis-aligned box with one CAD face per side.
#pragma once

#include "hapticad/core/geometry/triangle_soup.h"

namespace hapticad::testing {

// Box [lo, hi], outward winding, CAD faces 0..5 = -x, +x, -y, +y, -z, +z.
TriangleSoup MakeBoxSoup(const Vec3& lo, const Vec3& hi);

// A single square sheet z = height spanning [-half, half]^2, one CAD face, two triangles.
TriangleSoup MakeSheetSoup(double half, double height);

// Appends box [lo, hi] to `soup` as another piece, its CAD faces numbered after the
// soup's (0..5 in an empty soup), wound outward or (`inward`) inward.
void AppendBoxSoup(TriangleSoup* soup, const Vec3& lo, const Vec3& hi, bool inward = false);

}  // namespace hapticad::testing
