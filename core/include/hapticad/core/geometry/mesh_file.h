// SPDX-License-Identifier: GPL-3.0-or-later
// Reads a triangle or polygon mesh file (OFF, OBJ, STL ascii/binary, PLY) as a soup,
// exactly as written: duplicate, degenerate or non-manifold faces are kept for the
// repair pipeline to judge (mesh_repair.h). Polygons are fanned into triangles. Every
// triangle gets CAD face 0 (a file has no B-rep). Units: the file's.
#pragma once

#include <string>

#include "hapticad/core/geometry/triangle_soup.h"

namespace hapticad {

// Throws std::runtime_error naming the file when it is missing, a folder, cannot be read,
// holds no faces, or a face has a vertex that is not finite (naming the line in a text
// file, the face in a binary one).
TriangleSoup ReadMeshFile(const std::string& path);

}  // namespace hapticad
