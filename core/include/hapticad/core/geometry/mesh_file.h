// SPDX-License-Identifier: GPL-3.0-or-later
// Reads a triangle or polygon mesh file (OFF, OBJ, STL ascii/binary, PLY) as a soup,
// exactly as written: duplicate, degenerate or non-manifold faces are kept for the
// repair pipeline to judge (mesh_repair.h). Polygons are fanned into triangles. Every
// triangle gets CAD face 0 (a file has no B-rep). Units: the file's.
#pragma once

#include <string>

#include "hapticad/core/geometry/triangle_soup.h"

namespace hapticad {

// Throws std::runtime_error naming the file when it is missing, a folder, empty, cannot be
// read, holds no faces, or a face has a vertex that is not finite (naming the line in a
// text file, the face in a binary one). A file that ends early says what its format
// declared and what it holds ("binary STL claims 1200 triangles but holds 37 ...", "OFF
// declares 8 vertices and 12 faces but holds 8 vertices and 5 faces ...", "PLY ends inside
// its header ...", "ASCII STL ends inside its 6th facet ..."). OBJ declares no counts: an
// OBJ cut between two lines reads as a smaller mesh; one cut inside its last line (a
// vertex or face left short) is refused, and one cut before its faces is named as such.
// A binary STL holding more whole triangles than its count says is refused too ("binary
// STL claims 0 triangles but holds 12 ..."): reading the count would drop the rest.
// A count the file's size cannot hold (OFF's vertices, faces or a face's corners, PLY's
// elements or a list's items) is refused before anything is sized from it, saying what
// the file holds where that can be told, else what the counts take against its size.
TriangleSoup ReadMeshFile(const std::string& path);

}  // namespace hapticad
