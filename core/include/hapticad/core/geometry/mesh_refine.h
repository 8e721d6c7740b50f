// SPDX-License-Identifier: GPL-3.0-or-later
// RefineSoup: splits every edge longer than `max_edge` at its middle until none is,
// keeping the surface conforming (OpenMesh's 2-to-4 edge split), the CAD face of every
// triangle, and the corner normals (each new corner gets its parent triangle's normals
// blended at its position). Optional step of the scene pipeline, after the repair
// (mesh_repair.h): it needs a manifold soup.
//
// Units: the soup's. Not for the servo thread.
#pragma once

#include "hapticad/core/geometry/triangle_soup.h"

namespace hapticad {

// Throws std::invalid_argument for max_edge not finite and > 0, or a soup OpenMesh
// cannot take (a non-manifold edge: repair it first), or one that would grow past
// `max_triangles` (the edge length is too small for the part).
TriangleSoup RefineSoup(const TriangleSoup& soup, double max_edge,
                        std::size_t max_triangles = 20000000);

}  // namespace hapticad
