// SPDX-License-Identifier: GPL-3.0-or-later
// A geodesic icosphere: each face of an icosahedron split into n^2 triangles, the
// vertices pushed onto the sphere. 20 n^2 triangles: n = 22, 71, 224 give the 9,680,
// 100,820 and 1,003,520 triangles of the CHAI3D reference runs. Vertices shared
// between faces are generated once (the mesh is closed and manifold). One CAD face
// (id 0), outward winding, exact unit normals available as corner normals.
#pragma once

#include "hapticad/core/geometry/triangle_soup.h"

namespace hapticad {

// Throws std::invalid_argument for frequency < 1 or a radius that is not finite and > 0.
TriangleSoup MakeIcosphere(int frequency, double radius, const Vec3& centre = Vec3::Zero(),
                           bool with_corner_normals = false);

// The frequency whose icosphere has the triangle count closest to `triangles`.
int IcosphereFrequencyFor(long long triangles);

}  // namespace hapticad
