// SPDX-License-Identifier: GPL-3.0-or-later
// CGAL translation unit (walled off in hapticad_cgal).
#include "hapticad/core/geometry/mesh_file.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <vector>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>

namespace hapticad {
namespace {

constexpr const char* kFiniteVertices = "every vertex needs three finite coordinates";

// CGAL refuses a text mesh with a coordinate such as nan or inf without saying where:
// the first line (1-based) holding a number that is not finite, and that number; 0 when
// there is none or the file is not text.
std::size_t FindNonFiniteLine(const std::string& path, std::string* token) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (line.find('\0') != std::string::npos) return 0;  // binary
    std::istringstream words(line);
    std::string word;
    if (!(words >> word)) continue;
    // names, comments and (STL) normals are not vertices
    if (word[0] == '#' || word == "o" || word == "g" || word == "usemtl" || word == "mtllib" ||
        word == "solid" || word == "endsolid" || word == "facet" || word == "comment" ||
        word == "obj_info" || word == "element" || word == "property" || word == "format")
      continue;
    do {
      char* end = nullptr;
      const double v = std::strtod(word.c_str(), &end);
      if (end != word.c_str() && *end == '\0' && !std::isfinite(v)) {
        *token = word;
        return number;
      }
    } while (words >> word);
  }
  return 0;
}

}  // namespace

TriangleSoup ReadMeshFile(const std::string& path) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) throw std::runtime_error(path + ": no such file");
  if (std::filesystem::is_directory(status)) {
    throw std::runtime_error(path +
                             ": is a folder, not a mesh file (give an OFF, OBJ, STL or PLY file)");
  }
  if (!std::ifstream(path, std::ios::binary)) {
    throw std::runtime_error(path + ": cannot be opened (" + std::strerror(errno) + ")");
  }
  using Point = CGAL::Simple_cartesian<double>::Point_3;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  if (!CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false))) {
    std::string token;
    if (const std::size_t line = FindNonFiniteLine(path, &token)) {
      throw std::runtime_error(path + ": line " + std::to_string(line) + ": '" + token +
                               "' is not a finite number; " + kFiniteVertices);
    }
    throw std::runtime_error(path + ": cannot read a mesh (OFF, OBJ, STL or PLY expected)");
  }
  TriangleSoup soup;
  soup.vertices.reserve(points.size());
  for (const Point& p : points) soup.vertices.emplace_back(p.x(), p.y(), p.z());
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const auto& polygon = polygons[f];
    // a binary file reads any bit pattern as a number: said as the text formats say it
    for (const std::size_t v : polygon) {
      if (v < soup.vertices.size() && !soup.vertices[v].allFinite()) {
        std::ostringstream where;
        where << path << ": face " << f + 1 << " has a vertex that is not finite ("
              << soup.vertices[v].x() << ", " << soup.vertices[v].y() << ", "
              << soup.vertices[v].z() << "); " << kFiniteVertices;
        throw std::runtime_error(where.str());
      }
    }
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
