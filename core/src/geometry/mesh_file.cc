// SPDX-License-Identifier: GPL-3.0-or-later
// CGAL translation unit (walled off in hapticad_cgal).
#include "hapticad/core/geometry/mesh_file.h"

#include <stdexcept>
#include <vector>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>

namespace hapticad {

TriangleSoup ReadMeshFile(const std::string& path) {
  using Point = CGAL::Simple_cartesian<double>::Point_3;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  if (!CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false))) {
    throw std::runtime_error(path + ": cannot read a mesh (OFF, OBJ, STL or PLY expected)");
  }
  TriangleSoup soup;
  soup.vertices.reserve(points.size());
  for (const Point& p : points) soup.vertices.emplace_back(p.x(), p.y(), p.z());
  for (const auto& polygon : polygons) {
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
      soup.triangles.push_back({static_cast<std::int32_t>(polygon[0]),
                                static_cast<std::int32_t>(polygon[k]),
                                static_cast<std::int32_t>(polygon[k + 1])});
    }
  }
  if (soup.triangles.empty()) throw std::runtime_error(path + ": the mesh has no faces");
  soup.cad_faces.assign(soup.triangles.size(), 0);
  return soup;
}

}  // namespace hapticad
