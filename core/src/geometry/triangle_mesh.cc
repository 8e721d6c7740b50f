// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace hapticad {
namespace {

std::string Describe(const char* what, std::size_t index, const std::string& problem) {
  std::ostringstream out;
  out << "triangle mesh: " << what << ' ' << index << ": " << problem;
  return out.str();
}

bool IsFinite(const Vec3& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

}  // namespace

TriangleMesh::TriangleMesh() = default;
TriangleMesh::~TriangleMesh() = default;

std::unique_ptr<TriangleMesh> TriangleMesh::Build(
    const std::vector<Vec3>& vertices_l, const std::vector<std::array<std::int32_t, 3>>& triangles,
    const std::vector<std::int32_t>& cad_faces,
    const std::vector<std::array<Vec3, 3>>& corner_normals) {
  // check shapes before touching OpenMesh, so a bad input leaves nothing half-built
  if (triangles.empty()) throw std::invalid_argument("triangle mesh: no triangles");
  if (cad_faces.size() != triangles.size()) {
    throw std::invalid_argument("triangle mesh: " + std::to_string(cad_faces.size()) +
                                " CAD face ids for " + std::to_string(triangles.size()) +
                                " triangles");
  }
  if (!corner_normals.empty() && corner_normals.size() != triangles.size()) {
    throw std::invalid_argument("triangle mesh: " + std::to_string(corner_normals.size()) +
                                " corner-normal triples for " + std::to_string(triangles.size()) +
                                " triangles");
  }
  for (std::size_t v = 0; v < vertices_l.size(); ++v) {
    if (!IsFinite(vertices_l[v])) throw std::invalid_argument(Describe("vertex", v, "not finite"));
  }
  const auto num_vertices = static_cast<std::int64_t>(vertices_l.size());
  std::int32_t max_face = -1;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (std::int32_t v : triangles[t]) {
      if (v < 0 || v >= num_vertices) {
        throw std::invalid_argument(
            Describe("triangle", t, "vertex index " + std::to_string(v) + " out of range"));
      }
    }
    if (cad_faces[t] < 0)
      throw std::invalid_argument(Describe("triangle", t, "negative CAD face id"));
    max_face = std::max(max_face, cad_faces[t]);
    if (!corner_normals.empty()) {
      for (const Vec3& n : corner_normals[t]) {
        if (!IsFinite(n) || n.squaredNorm() < 0.25) {
          throw std::invalid_argument(Describe("triangle", t, "corner normal not a unit vector"));
        }
      }
    }
  }

  std::unique_ptr<TriangleMesh> mesh(new TriangleMesh());
  OpenMeshTriMesh& om = mesh->mesh_;
  om.reserve(vertices_l.size(), triangles.size() * 3 / 2 + 3, triangles.size());
  for (const Vec3& p : vertices_l) om.add_vertex(p);
  mesh->points_.assign(vertices_l.begin(), vertices_l.end());

  om.add_property(mesh->cad_face_prop_, "cad_face");
  mesh->triangles_.reserve(triangles.size());
  mesh->face_normals_.reserve(triangles.size());
  mesh->corner_normals_.reserve(3 * corner_normals.size());

  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const OpenMeshTriMesh::VertexHandle vh[3] = {om.vertex_handle(tri[0]), om.vertex_handle(tri[1]),
                                                 om.vertex_handle(tri[2])};
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      throw std::invalid_argument(Describe("triangle", t, "repeats a vertex"));
    }
    const OpenMeshTriMesh::FaceHandle fh = om.add_face(vh[0], vh[1], vh[2]);
    if (!fh.is_valid()) {
      throw std::invalid_argument(Describe(
          "triangle", t, "would make a non-manifold edge or vertex (repair the mesh first)"));
    }
    om.property(mesh->cad_face_prop_, fh) = cad_faces[t];
    mesh->triangles_.push_back({static_cast<std::uint32_t>(tri[0]),
                                static_cast<std::uint32_t>(tri[1]),
                                static_cast<std::uint32_t>(tri[2])});
    const Vec3 n =
        (vertices_l[tri[1]] - vertices_l[tri[0]]).cross(vertices_l[tri[2]] - vertices_l[tri[0]]);
    const double len = n.norm();
    mesh->face_normals_.push_back(len > 0.0 ? Vec3(n / len) : Vec3::Zero());
    if (!corner_normals.empty()) {
      for (const Vec3& c : corner_normals[t])
        mesh->corner_normals_.push_back(c.normalized().cast<float>());
    }
  }
  mesh->cad_faces_ = om.property(mesh->cad_face_prop_).data();
  mesh->num_cad_faces_ = max_face + 1;
  mesh->closed_ = std::none_of(om.edges_begin(), om.edges_end(),
                               [&om](OpenMeshTriMesh::EdgeHandle e) { return om.is_boundary(e); });
  for (const Vec3& p : mesh->points_) {
    mesh->bounding_radius_ = std::max(mesh->bounding_radius_, p.norm());
  }
  return mesh;
}

Vec3 TriangleMesh::CalcShadingNormal(std::uint32_t t, const Vec3& point_l) const {
  if (corner_normals_.empty()) return face_normals_[t];
  const auto& tri = triangles_[t];
  const Vec3* p = points_.data();
  const Vec3 e1 = p[tri[1]] - p[tri[0]];
  const Vec3 e2 = p[tri[2]] - p[tri[0]];
  const Vec3 w = point_l - p[tri[0]];
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0.0)) return face_normals_[t];
  // barycentrics of the point's projection, clamped so a point a hair outside blends
  // like the nearest edge
  double u = std::max((d22 * w.dot(e1) - d12 * w.dot(e2)) / det, 0.0);
  double v = std::max((d11 * w.dot(e2) - d12 * w.dot(e1)) / det, 0.0);
  const double sum = u + v;
  if (sum > 1.0) {
    u /= sum;
    v /= sum;
  }
  const Vec3 n =
      (1.0 - u - v) * corner_normal(t, 0) + u * corner_normal(t, 1) + v * corner_normal(t, 2);
  const double len = n.norm();
  return len > 1e-6 ? Vec3(n / len) : face_normals_[t];
}

std::size_t TriangleMesh::CalcMemoryBytes() const {
  // OpenMesh's connectivity: per vertex one halfedge handle, per halfedge next/prev/
  // vertex/face handles, per face one halfedge handle.
  std::size_t bytes = mesh_.n_vertices() * (sizeof(Vec3) + sizeof(int));
  bytes += points_.capacity() * sizeof(Vec3);
  bytes += mesh_.n_halfedges() * 4 * sizeof(int);
  bytes += mesh_.n_faces() * (sizeof(int) + sizeof(std::int32_t));
  bytes += triangles_.capacity() * sizeof(triangles_[0]);
  bytes += face_normals_.capacity() * sizeof(Vec3);
  bytes += corner_normals_.capacity() * sizeof(Eigen::Vector3f);
  return bytes;
}

}  // namespace hapticad
