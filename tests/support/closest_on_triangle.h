// SPDX-License-Identifier: GPL-3.0-or-later
// An independent reference for tests of closest-point and distance queries.
#pragma once

#include "hapticad/core/vec3.h"

namespace hapticad::testing {

// The point of triangle abc closest to p, by the Voronoi region p projects into
// (a corner, an edge or the face): Ericson, Real-Time Collision Detection, 5.1.5.
// Any units and frame, the same for all four points.
Vec3 ClosestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace hapticad::testing
