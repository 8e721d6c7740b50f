// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/triangle_mesh.h"

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

  mesh->has_corner_normals_ = !corner_normals.empty();
  if (mesh->has_corner_normals_) om.request_halfedge_normals();
  om.add_property(mesh->cad_face_prop_, "cad_face");
  mesh->triangles_.reserve(triangles.size());

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
    if (mesh->has_corner_normals_) {
      // the halfedge of this face that points to a corner's vertex carries that corner's normal
      for (auto he : om.fh_range(fh)) {
        const int corner =
            om.to_vertex_handle(he) == vh[0] ? 0 : (om.to_vertex_handle(he) == vh[1] ? 1 : 2);
        om.set_normal(he, corner_normals[t][corner].normalized());
      }
    }
  }
  mesh->cad_faces_ = om.property(mesh->cad_face_prop_).data();
  mesh->num_cad_faces_ = max_face + 1;
  return mesh;
}

Vec3 TriangleMesh::face_normal(std::uint32_t t) const {
  const auto& tri = triangles_[t];
  const Vec3* p = mesh_.points();
  const Vec3 n = (p[tri[1]] - p[tri[0]]).cross(p[tri[2]] - p[tri[0]]);
  const double len = n.norm();
  return len > 0.0 ? Vec3(n / len) : Vec3::Zero();
}

Vec3 TriangleMesh::corner_normal(std::uint32_t t, int corner) const {
  const auto fh = mesh_.face_handle(static_cast<int>(t));
  const auto vh = mesh_.vertex_handle(static_cast<int>(triangles_[t][corner]));
  for (auto he : mesh_.fh_range(fh)) {
    if (mesh_.to_vertex_handle(he) == vh) return mesh_.normal(he);
  }
  return face_normal(t);
}

std::size_t TriangleMesh::CalcMemoryBytes() const {
  // OpenMesh's connectivity: per vertex one halfedge handle, per halfedge next/prev/
  // vertex/face handles, per face one halfedge handle.
  std::size_t bytes = mesh_.n_vertices() * (sizeof(Vec3) + sizeof(int));
  bytes += mesh_.n_halfedges() * 4 * sizeof(int);
  bytes += mesh_.n_faces() * (sizeof(int) + sizeof(std::int32_t));
  if (has_corner_normals_) bytes += mesh_.n_halfedges() * sizeof(OpenMeshTraits::Normal);
  bytes += triangles_.capacity() * sizeof(triangles_[0]);
  return bytes;
}

}  // namespace hapticad
