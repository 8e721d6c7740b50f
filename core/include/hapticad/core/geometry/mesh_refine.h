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

// The default bound on the refined triangles: 4 million (about 1.6 GB while OpenMesh
// splits, 1 GB as a scene), four times the 1M-triangle scenes the engine is measured on.
constexpr std::size_t kMaxRefinedTriangles = 4000000;

// Throws std::invalid_argument for max_edge not finite and > 0, or a soup OpenMesh
// cannot take (a non-manifold edge: repair it first), or one that would grow past
// `max_triangles` (the edge length is too small for the part). A refinement that
// cannot fit is refused before anything is split, in milliseconds: the soup's area
// over the largest triangle of edges max_edge (sqrt(3)/4 max_edge^2) is a lower bound
// of what it makes. One that passes that bound and still grows past `max_triangles` is
// refused when it does.
TriangleSoup RefineSoup(const TriangleSoup& soup, double max_edge,
                        std::size_t max_triangles = kMaxRefinedTriangles);

}  // namespace hapticad
