// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/mesh_refine.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

// vector_traits before the Eigen specialisation (as in triangle_mesh.h)
#include <OpenMesh/Core/Utils/vector_traits.hh>

#include <OpenMesh/Core/Geometry/EigenVectorT.hh>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

namespace hapticad {
namespace {

struct Traits : OpenMesh::DefaultTraits {
  using Point = Eigen::Vector3d;
  using Normal = Eigen::Vector3d;
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<Traits>;

// The triangle of the input a face came from: new faces copy it (split_copy), so every
// corner's normal can be blended from the original three.
struct Source {
  std::array<Vec3, 3> corner;
  std::array<Vec3, 3> normal;
  std::int32_t cad_face;
};

Vec3 BlendNormal(const Source& s, const Vec3& p) {
  const Vec3 e1 = s.corner[1] - s.corner[0], e2 = s.corner[2] - s.corner[0], w = p - s.corner[0];
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0.0)) return s.normal[0];
  const double u = (d22 * w.dot(e1) - d12 * w.dot(e2)) / det;
  const double v = (d11 * w.dot(e2) - d12 * w.dot(e1)) / det;
  const Vec3 n = (1.0 - u - v) * s.normal[0] + u * s.normal[1] + v * s.normal[2];
  return n.norm() > 0.0 ? Vec3(n.normalized()) : s.normal[0];
}

}  // namespace

TriangleSoup RefineSoup(const TriangleSoup& soup, double max_edge, std::size_t max_triangles) {
  if (!(std::isfinite(max_edge) && max_edge > 0.0)) {
    throw std::invalid_argument("mesh refinement: the edge length must be finite and > 0");
  }
  // no triangle with every edge <= max_edge is larger than the equilateral one: a lower
  // bound of the count, before anything is built (a 0.01 mm edge on a 100 mm part asked
  // for billions, which took a minute and gigabytes to refuse)
  double area = 0.0;
  for (const auto& tri : soup.triangles) {
    const Vec3& a = soup.vertices[tri[0]];
    area += 0.5 * (soup.vertices[tri[1]] - a).cross(soup.vertices[tri[2]] - a).norm();
  }
  const double at_least = area / (std::sqrt(3.0) / 4.0 * max_edge * max_edge);
  if (at_least > static_cast<double>(max_triangles)) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "mesh refinement: an edge length of %g makes at least %.3g triangles of this "
                  "part's area (at most %zu are built): give an edge length of %.3g or more",
                  max_edge, at_least, max_triangles,
                  max_edge * std::sqrt(at_least / static_cast<double>(max_triangles)));
    throw std::invalid_argument(text);
  }
  const bool normals = !soup.corner_normals.empty();
  Mesh mesh;
  OpenMesh::FPropHandleT<Source> source;
  mesh.add_property(source);
  for (const Vec3& p : soup.vertices) mesh.add_vertex(p);
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    const auto& tri = soup.triangles[t];
    const auto fh = mesh.add_face(mesh.vertex_handle(tri[0]), mesh.vertex_handle(tri[1]),
                                  mesh.vertex_handle(tri[2]));
    if (!fh.is_valid()) {
      throw std::invalid_argument("mesh refinement: triangle " + std::to_string(t) +
                                  " makes a non-manifold edge (repair the soup first)");
    }
    Source s;
    for (int k = 0; k < 3; ++k) {
      s.corner[k] = soup.vertices[tri[k]];
      s.normal[k] = normals ? soup.corner_normals[t][k] : Vec3::Zero();
    }
    s.cad_face = soup.cad_faces[t];
    mesh.property(source, fh) = s;
  }
  // halve the long edges until none is left; each pass at least halves the longest
  const double limit2 = max_edge * max_edge;
  for (bool split = true; split;) {
    split = false;
    const std::size_t edges = mesh.n_edges();  // new edges wait for the next pass
    for (std::size_t e = 0; e < edges; ++e) {
      const auto eh = mesh.edge_handle(static_cast<int>(e));
      const auto he = mesh.halfedge_handle(eh, 0);
      const Vec3 a = mesh.point(mesh.from_vertex_handle(he));
      const Vec3 b = mesh.point(mesh.to_vertex_handle(he));
      if ((b - a).squaredNorm() <= limit2) continue;
      if (mesh.n_faces() + 2 > max_triangles) {
        char text[192];
        std::snprintf(text, sizeof text,
                      "mesh refinement: more than %zu triangles at an edge length of %g: give a "
                      "longer one",
                      max_triangles, max_edge);
        throw std::invalid_argument(text);
      }
      mesh.split_copy(eh, mesh.add_vertex(0.5 * (a + b)));
      split = true;
    }
  }
  TriangleSoup out;
  out.vertices.reserve(mesh.n_vertices());
  for (const auto vh : mesh.vertices()) out.vertices.push_back(mesh.point(vh));
  out.triangles.reserve(mesh.n_faces());
  out.cad_faces.reserve(mesh.n_faces());
  for (const auto fh : mesh.faces()) {
    std::array<std::int32_t, 3> tri{};
    std::array<Vec3, 3> corner_normals;
    int k = 0;
    const Source& s = mesh.property(source, fh);
    for (const auto vh : mesh.fv_range(fh)) {
      tri[k] = vh.idx();
      corner_normals[k] = normals ? BlendNormal(s, mesh.point(vh)) : Vec3::Zero();
      ++k;
    }
    out.triangles.push_back(tri);
    out.cad_faces.push_back(s.cad_face);
    if (normals) out.corner_normals.push_back(corner_normals);
  }
  return out;
}

}  // namespace hapticad
