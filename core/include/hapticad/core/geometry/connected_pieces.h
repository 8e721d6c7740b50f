// SPDX-License-Identifier: GPL-3.0-or-later
// ConnectedPieces: the connected pieces of a mesh (its triangles joined through shared
// vertices: a part, a loose sheet) and the box round each. What the solid analysis and
// the convex pieces both start from.
//
// Units and frame: the mesh's. For the build: allocates, O(n).
#pragma once

#include <cstdint>
#include <vector>

#include "hapticad/core/geometry/triangle_mesh.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

struct ConnectedPieces {
  static constexpr std::uint32_t kNone = ~std::uint32_t{0};
  std::vector<std::uint32_t> of_vertex;  // each vertex's piece; kNone for one in no triangle
  std::vector<Vec3> lo;                  // each piece's box
  std::vector<Vec3> hi;
};

ConnectedPieces FindConnectedPieces(const TriangleMesh& mesh);

}  // namespace hapticad
