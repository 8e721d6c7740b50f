// SPDX-License-Identifier: GPL-3.0-or-later
// SurfaceFrame: a tangent frame fixed to a CAD face, in which face-bound effects (the
// roughness grid, the viscous grating, the linear pattern) lay out their coordinates.
//
// The plugin takes it at the face's centre: e1 = the parametric u direction (dS/du)
// turned by the pattern angle about the outward normal, e2 = normal x e1. A point maps
// to (x, y) = ((p - origin) . e1, (p - origin) . e2): exact on planar faces, a
// projection on curved ones. World frame, metres.
#pragma once

#include "hapticad/core/vec3.h"

namespace hapticad {

struct SurfaceFrame {
  Vec3 origin_w = Vec3::Zero();
  Vec3 e1_w = Vec3::UnitX();  // unit
  Vec3 e2_w = Vec3::UnitY();  // unit, orthogonal to e1_w
};

}  // namespace hapticad
