// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/connected_pieces.h"

namespace hapticad {

ConnectedPieces FindConnectedPieces(const TriangleMesh& mesh) {
  return FindConnectedPieces(
      mesh.num_vertices(), mesh.num_triangles(),
      [&mesh](std::size_t t, int k) { return mesh.triangle(static_cast<std::uint32_t>(t))[k]; },
      [&mesh](std::size_t v) { return mesh.vertex(static_cast<std::uint32_t>(v)); });
}

}  // namespace hapticad
