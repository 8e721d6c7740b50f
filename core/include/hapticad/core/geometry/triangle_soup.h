// SPDX-License-Identifier: GPL-3.0-or-later
// TriangleSoup: the input to a haptic scene, as a CAD tessellator hands it over.
//
// Shapes: `vertices` is #V points, `triangles` is #T index triples into `vertices`
// (counter-clockwise seen from outside for closed solids; open sheets may wind either
// way), `cad_faces` is #T ids of the B-rep face each triangle came from (>= 0; the
// caller maps ids to names such as "Box.Face3"), `corner_normals` is empty or #T
// triples of unit normals, one per triangle corner, so that a vertex shared by two CAD
// faces can carry each face's exact normal.
// Units: whatever the model uses; the scene builder is told the metres per unit.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "hapticad/core/vec3.h"

namespace hapticad {

struct TriangleSoup {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::int32_t, 3>> triangles;
  std::vector<std::int32_t> cad_faces;
  std::vector<std::array<Vec3, 3>> corner_normals;
};

}  // namespace hapticad
